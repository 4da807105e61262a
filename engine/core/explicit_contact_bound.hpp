// The penalty spring and damper of a weighted contact (a collider's edge or corner against the
// cloth's edges and triangles, or the cloth against itself) as an explicit scheme may take them.
//
// Such a contact acts on the point sum_j w_j x_j, whose effective mass is m_e = 1 / sum_j w_j^2 /
// m_j. A particle of 1e-4 kg under the default damper c = 5 N s/m has 2 m / c = 4e-5 s, below the
// step that a light cloth's springs allow (a cotton sheet's 1e-4 s), and a particle often sits in
// several such contacts at once (every cloth edge across a box edge, every triangle over a corner).
// An explicit step then returns more energy than the contact took: the sheet jumps off the box.
//
// So each contact takes its damper implicitly over the step, on its own point (a Jacobi step):
// the damping force that leaves the relative normal velocity u' = u / (1 + h c L / m_e) is
//   c' = c / (1 + h c L / m_e),
// where L, the contact's load, is the most contacts of its kind any of its particles is in, so that
// L contacts on one particle together damp it by at most the velocity it has. The spring likewise
// becomes k' = k / (1 + h^2 k L / m_e). On the contact's point, symplectic Euler then has
//   h^2 k' L / m_e + 2 h c' L / m_e < 1 + 2 < 4,
// its stability condition, at any step; and h^2 w^2 = h^2 k' L / m_e < 1 means a point that leaves
// the contact within one step leaves with less kinetic energy than the spring held (a one-step
// bounce returns h^2 w^2 of it): the contact cannot add energy whatever dt is. At the steps
// where the explicit contact was already stable (h^2 k L / m_e << 1 and h c L / m_e << 1) both are
// unchanged; a resting contact keeps its force k' depth with k' close to k.
// Implicit Euler and vertex block descent take the same contacts into their solves and use k and c
// as they are.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace drapelab {

struct PenaltyRates {
  double stiffness = 0.0;  // N/m
  double damping = 0.0;    // N*s/m
};

// `inverse_effective_mass` = sum_j w_j^2 / m_j (1/kg), `load` >= 1, `h` s (none when h <= 0).
inline PenaltyRates step_bounded_penalty(double stiffness, double damping,
                                         double inverse_effective_mass, double load, double h) {
  if (!(h > 0.0) || !(inverse_effective_mass > 0.0)) return {stiffness, damping};
  const double rate = std::max(load, 1.0) * inverse_effective_mass;  // 1/kg
  return {stiffness / (1.0 + h * h * stiffness * rate), damping / (1.0 + h * damping * rate)};
}

// How many contacts of one evaluation each particle is in (the load L above). Counts are kept for
// every particle and reset only where they were raised, so an evaluation costs its contacts only.
class ContactLoads {
 public:
  explicit ContactLoads(int particle_count = 0)
      : count_(static_cast<std::size_t>(particle_count), 0) {}

  void clear() {
    for (const std::int32_t i : touched_) count_[static_cast<std::size_t>(i)] = 0;
    touched_.clear();
  }
  // One more contact on each of `particles` whose weight is not zero (-1: an unused slot).
  template <std::size_t N>
  void add(const std::array<int, N>& particles, const std::array<double, N>& weights) {
    for (std::size_t s = 0; s < N; ++s) {
      if (particles[s] < 0 || weights[s] == 0.0) continue;
      int& c = count_[static_cast<std::size_t>(particles[s])];
      if (c++ == 0) touched_.push_back(particles[s]);
    }
  }
  // The load of a contact on `particles`: the most contacts any of them is in (at least 1).
  template <std::size_t N>
  double load(const std::array<int, N>& particles, const std::array<double, N>& weights) const {
    int most = 1;
    for (std::size_t s = 0; s < N; ++s)
      if (particles[s] >= 0 && weights[s] != 0.0)
        most = std::max(most, count_[static_cast<std::size_t>(particles[s])]);
    return most;
  }

 private:
  std::vector<int> count_;
  std::vector<std::int32_t> touched_;
};

}  // namespace drapelab
