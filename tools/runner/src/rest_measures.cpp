// Settle time and rest jitter (rest_measures.hpp).
#include "rest_measures.hpp"

#include <algorithm>
#include <cmath>

namespace drapelab::runner {

void RestTracker::add(double time, double kinetic_energy, double gravity_energy,
                      double total_mass) {
  times_.push_back(time);
  kinetic_.push_back(kinetic_energy);
  gravity_.push_back(gravity_energy);
  mass_ = total_mass;
}

std::optional<double> RestTracker::settle_time() const {
  if (times_.empty()) return std::nullopt;
  double released = 0.0;  // J
  for (double g : gravity_) released = std::max(released, gravity_.front() - g);
  if (!(released > 0.0)) return std::nullopt;
  const double quiet = 1e-6 * released;
  // Walk back from the end while the cloth is quiet; the settle time is where that stretch began.
  std::size_t first_quiet = times_.size();
  while (first_quiet > 0 && kinetic_[first_quiet - 1] < quiet) --first_quiet;
  if (first_quiet == times_.size()) return std::nullopt;  // still moving at the last frame
  return times_[first_quiet];
}

std::optional<double> RestTracker::rest_jitter() const {
  if (times_.empty() || !(mass_ > 0.0)) return std::nullopt;
  const double from = times_.back() - 1.0;  // s: the last simulated second
  double sum = 0.0;
  int count = 0;
  for (std::size_t k = 0; k < times_.size(); ++k)
    if (times_[k] >= from - 1e-12) {
      sum += 2.0 * kinetic_[k] / mass_;  // mass-weighted mean square speed, m^2/s^2
      ++count;
    }
  return std::sqrt(sum / count);
}

}  // namespace drapelab::runner
