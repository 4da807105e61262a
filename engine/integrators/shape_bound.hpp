// The adaptive substeps' shape-dependent bound: the rates of drapelab/stability.hpp evaluated at
// the cloth's current shape rather than at rest, with a workspace kept between calls.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "drapelab/stability.hpp"
#include "forces/spring_family_loops.hpp"

namespace drapelab {

// Particle i's stiffness tensor S_i sums its springs' elastic Jacobian blocks
//   P = ks [u u^T + max(0, 1 - l0 / l) (I - u u^T)]   (spring_jacobian_for_solve; ks I when l = 0)
// and its damping tensor D_i their kd u u^T. Each P is positive semidefinite, so for any
// displacement field (a - b)^T P (a - b) <= 2 a^T P a + 2 b^T P b, and summing over springs
//   omega_max^2 <= K = max_i 2 lambda_max(S_i) / m_i,   c_max <= C = max_i 2 lambda_max(D_i) / m_i
//   + air
// (compressed springs' negative across-spring stiffness only lowers omega). Gershgorin's bounds
// above are the same with the trace in place of lambda_max: for a flat sheet, whose springs at a
// particle span the plane equally, lambda_max is half the trace and the step 1.4 to 1.5 times
// longer. The bound holds at x only, so a caller re-evaluates it as the cloth moves. The contact
// adds as above. `workspace` holds each particle's list of springs and room for per-spring terms,
// built on the first call: keep one per model, so that later calls allocate nothing. Runs on the
// spring-loop threads (shape_bound_loops.hpp), with the same bits for any thread count.
struct ShapeBoundWorkspace {
  std::vector<std::int64_t> first;  // particle i's springs are incident[first[i] .. first[i + 1])
  std::vector<std::int32_t> incident;  // spring indices, increasing within each particle
  std::vector<double> terms;  // per spring: u u^T and ks split across it (shape_bound_loops.hpp)
};
// `families`, when given, are the model's springs as spring families (spring_families.hpp): the
// tensors are then summed family by family in unit-stride loops (shape_bound_loops.hpp
// family_shape_rate_maxima), several times faster on a grid, equal to the index-list sums to
// rounding; the workspace is then not used.
NetworkRates shape_rate_bounds(const ClothModel& model, const Eigen::Matrix3Xd& x,
                               double air_damping, ContactRates contact,
                               ShapeBoundWorkspace& workspace,
                               const std::vector<SpringFamily>* families = nullptr);
// Symplectic Euler's stable step (s) at shape x from those bounds, without the contact (it takes
// the contact at the step's end): the step adaptive substeps follow.
double shape_stable_step(const ClothModel& model, const Eigen::Matrix3Xd& x, double air_damping,
                         ShapeBoundWorkspace& workspace,
                         const std::vector<SpringFamily>* families = nullptr);

}  // namespace drapelab
