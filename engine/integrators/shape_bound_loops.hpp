// The adaptive substeps' shape bound (stability.hpp shape_rate_bounds) on plain arrays. Like
// particle_loops.hpp, this header and its source include no Eigen: the source is built with OpenMP
// for the build machine's CPU, and without fused multiply-adds, so the bound has the same bits on
// every CPU and for any thread count (each particle sums its own springs in a fixed order; the
// maximum over particles does not depend on the order).
#pragma once

#include <cstdint>
#include <vector>

#include "forces/spring_family_loops.hpp"

namespace drapelab::kernels {

// The springs of each particle, as compressed rows: particle i's springs are
// incident[first[i] .. first[i + 1]), in increasing spring index.
struct IncidentSprings {
  const std::int64_t* first = nullptr;
  const std::int32_t* incident = nullptr;
};

// A spring network in plain arrays (cloth_model.hpp SpringSet): ends, rest length (m), ks (N/m),
// kd (N*s/m).
struct SpringArrays {
  const std::int32_t* v0 = nullptr;
  const std::int32_t* v1 = nullptr;
  const double* rest_length = nullptr;
  const double* ks = nullptr;
  const double* kd = nullptr;
};

struct ShapeRates {
  double stiffness =
      0.0;               // 1/s^2: max over free particles of (2 lambda_max(S_i) + contact k) / m_i
  double damping = 0.0;  // 1/s:   max over free particles of (2 lambda_max(D_i) + contact c) / m_i
};

// Over the n particles at positions x (3 x n, m), each free one's stiffness tensor
// S_i = sum ks [u u^T + max(0, 1 - l0 / l) (I - u u^T)] and damping tensor D_i = sum kd u u^T over
// its springs (ks I and kd I for a spring of zero length), and the largest eigenvalue of each.
// inverse_mass is per particle (1/kg, 0 for a pinned one, which is skipped). Each spring's
// direction is computed once, in a vectorised pass over the springs into `terms` (room for 8 x
// spring_count), then each particle sums its own springs' terms.
ShapeRates shape_rate_maxima(std::int64_t n, IncidentSprings adjacency, SpringArrays springs,
                             const double* inverse_mass, const double* x, double contact_stiffness,
                             double contact_damping, std::int64_t spring_count, double* terms);

// The same maxima for a cloth whose springs are spring families (spring_family_loops.hpp: every
// regular grid), without index lists: chunk by chunk, each particle adds, family by family, the
// terms of the spring it starts (slot i) and of the one it ends (slot i - offset), each computed
// where it is needed (twice per spring, in unit-stride vectorised loops, where index lists make
// every term a scattered read). Equal to shape_rate_maxima to rounding (the sums run in another
// order); the same bits for any thread count.
ShapeRates family_shape_rate_maxima(std::int64_t n, const std::vector<SpringFamily>& families,
                                    const double* inverse_mass, const double* x,
                                    double contact_stiffness, double contact_damping);

// The largest eigenvalue of the symmetric 3 x 3 matrix with diagonal (a, b, c) and off-diagonal
// entries d = (0,1), e = (0,2), f = (1,2): the characteristic cubic's largest root, found from
// above by Newton's method (no trigonometric functions: this runs twice per particle at every
// evaluation), widened by 1e-9 relative so rounding never puts it below the true value.
double largest_symmetric_eigenvalue(double a, double b, double c, double d, double e, double f);

}  // namespace drapelab::kernels
