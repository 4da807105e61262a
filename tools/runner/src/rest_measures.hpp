// How a solver comes to rest, from its recorded frames (docs/metrics.md, "Summary-level measures"):
//   settle time  the first frame time after which kinetic energy stays below 1e-6 of the largest
//                gravity energy released so far (E_g(0) - E_g(t), maximised over the run);
//   rest jitter  the mass-weighted RMS speed sqrt(2 KE / M) averaged (as a mean square) over the
//                frames of the run's last simulated second.
#pragma once

#include <optional>
#include <vector>

namespace drapelab::runner {

class RestTracker {
 public:
  // One recorded frame: time (s), kinetic and gravity energy (J), total mass (kg).
  void add(double time, double kinetic_energy, double gravity_energy, double total_mass);
  std::optional<double> settle_time() const;  // s; empty when it never settles or nothing fell
  std::optional<double> rest_jitter() const;  // m/s; empty before any frame

 private:
  std::vector<double> times_, kinetic_, gravity_;
  double mass_ = 0.0;
};

}  // namespace drapelab::runner
