// Backward Euler's share of the contacts between particles (weighted_contact.hpp), for both
// forms of the solve: each contact becomes a coupling (coupling.hpp) for the products, plus, per
// moving particle i, its diagonal block and its right-hand side term.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "drapelab/weighted_contact.hpp"
#include "integrators/coupling.hpp"

namespace drapelab {

// For a step of h (s) from velocities v (m/s): fills `couplings` (cleared first) and calls
// add(i, block, rhs) for every moving particle i of every contact with its diagonal block
// (h c + h^2 k) w_i^2 n n^T (kg) and its right-hand side term h^2 (K v0)_i =
// -h^2 k w_i n (n . sum_j w_j v0_j - end_rate) (N s). `moving(i)` is false for a pinned particle.
template <typename Moving, typename AddToParticle>
void build_couplings(const std::vector<WeightedContact>& contacts, const Eigen::Matrix3Xd& v,
                     double h, Moving&& moving, std::vector<kernels::Coupling>& couplings,
                     AddToParticle&& add) {
  couplings.clear();
  for (const WeightedContact& touch : contacts) {
    kernels::Coupling coupling;
    coupling.coefficient = h * touch.damping + h * h * touch.stiffness;
    const Eigen::Vector3d& n = touch.normal;
    for (int c = 0; c < 3; ++c) coupling.normal[c] = n[c];
    double closing = -touch.end_rate;  // m/s: n . sum_j w_j v0_j, less the far end's rate
    for (int k = 0; k < 4; ++k) {
      coupling.particle[k] = touch.particle[k];
      coupling.weight[k] = touch.weight[k];
      if (touch.particle[k] >= 0) closing += touch.weight[k] * n.dot(v.col(touch.particle[k]));
    }
    const Eigen::Matrix3d along = n * n.transpose();
    for (int k = 0; k < 4; ++k) {
      const int i = touch.particle[k];
      if (i < 0 || !moving(i)) continue;
      const double w = touch.weight[k];
      add(i, Eigen::Matrix3d(coupling.coefficient * w * w * along),
          Eigen::Vector3d(-h * h * touch.stiffness * w * closing * n));
    }
    couplings.push_back(coupling);
  }
}

}  // namespace drapelab
