// The adaptive substeps' shape bound on plain arrays (shape_bound_loops.hpp). Built without
// contraction into fused multiply-adds: the same bits on every CPU.
#include "drapelab/shape_bound_loops.hpp"

#include <algorithm>
#include <cmath>

#include "drapelab/particle_loops.hpp"

namespace drapelab::kernels {
namespace {

inline double largest_eigenvalue(double a, double b, double c, double d, double e, double f) {
  // With q the mean eigenvalue and B = (A - q I) / p scaled to unit spread, the eigenvalues are
  // q + 2 p t for the roots t of 4 t^3 - 3 t = det(B) / 2 = r (cos 3 phi = 4 cos^3 phi - 3 cos phi, so
  // t = cos(acos(r) / 3) is the largest). Without trigonometric functions: at t = 1/2 + s the cubic is
  // 6 s^2 + 4 s^3 = 1 + r, so 1/2 + sqrt((1 + r) / 6) (and 1) lie above the root, and Newton's method
  // on this cubic, convex above its largest root, descends to it from there.
  const double off = d * d + e * e + f * f;
  const double q = (a + b + c) / 3.0;
  const double spread = (a - q) * (a - q) + (b - q) * (b - q) + (c - q) * (c - q) + 2.0 * off;
  if (spread <= 0.0) return q;  // a multiple of the identity
  const double p = std::sqrt(spread / 6.0);
  const double ba = (a - q) / p, bb = (b - q) / p, bc = (c - q) / p;
  const double bd = d / p, be = e / p, bf = f / p;
  const double det = ba * (bb * bc - bf * bf) - bd * (bd * bc - bf * be) + be * (bd * bf - bb * be);
  const double r = std::clamp(0.5 * det, -1.0, 1.0);
  double t = std::min(1.0, 0.5 + std::sqrt((1.0 + r) / 6.0));
  for (int k = 0; k < 3; ++k) {
    const double excess = 4.0 * t * t * t - 3.0 * t - r;  // > 0 above the root
    const double slope = 12.0 * t * t - 3.0;              // > 0 for t > 1/2
    if (!(excess > 0.0 && slope > 0.0)) break;            // at the root, to rounding
    t -= excess / slope;
  }
  const double largest = q + 2.0 * p * t;
  return largest + 1e-9 * std::abs(largest);
}

}  // namespace

double largest_symmetric_eigenvalue(double a, double b, double c, double d, double e, double f) {
  return largest_eigenvalue(a, b, c, d, e, f);
}

ShapeRates shape_rate_maxima(std::int64_t n, IncidentSprings adjacency, SpringArrays s, const double* inverse_mass,
                             const double* x, double contact_stiffness, double contact_damping) {
  double stiffness_rate = 0.0, damping_rate = 0.0;  // 1/s^2, 1/s
  // Each particle recomputes its springs' terms rather than adding into shared tensors: no writes to
  // other particles, so the threads need no coordination and the sums keep one order.
#pragma omp parallel for schedule(static) reduction(max : stiffness_rate, damping_rate) if (n >= kParallelParticles)
  for (std::int64_t i = 0; i < n; ++i) {
    const double w = inverse_mass[i];  // 1/kg, 0 when pinned
    if (w == 0.0) continue;
    double t[12] = {};  // S_i (xx, yy, zz, xy, xz, yz) in N/m, then D_i in N*s/m
    for (std::int64_t k = adjacency.first[i]; k < adjacency.first[i + 1]; ++k) {
      const std::int32_t e = adjacency.incident[k];
      const std::int64_t a = s.v0[e], b = s.v1[e];
      const double dx = x[3 * a] - x[3 * b], dy = x[3 * a + 1] - x[3 * b + 1], dz = x[3 * a + 2] - x[3 * b + 2];
      const double squared = dx * dx + dy * dy + dz * dz;  // m^2
      if (squared > 0.0) {
        const double inverse_length = 1.0 / std::sqrt(squared);  // 1/m
        const double ux = dx * inverse_length, uy = dy * inverse_length, uz = dz * inverse_length;
        const double across = std::max(0.0, 1.0 - s.rest_length[e] * inverse_length);  // per ks
        const double along = s.ks[e] * (1.0 - across);  // N/m on u u^T, once the across part is split off
        const double isotropic = s.ks[e] * across;      // N/m on I
        const double uu[6] = {ux * ux, uy * uy, uz * uz, ux * uy, ux * uz, uy * uz};
        for (int c = 0; c < 6; ++c) {
          t[c] += along * uu[c] + (c < 3 ? isotropic : 0.0);
          t[6 + c] += s.kd[e] * uu[c];
        }
      } else {  // no direction: count it as stiff and damped in every direction
        for (int c = 0; c < 3; ++c) {
          t[c] += s.ks[e];
          t[6 + c] += s.kd[e];
        }
      }
    }
    const double stiffness = largest_eigenvalue(t[0], t[1], t[2], t[3], t[4], t[5]);
    const double damping = largest_eigenvalue(t[6], t[7], t[8], t[9], t[10], t[11]);
    stiffness_rate = std::max(stiffness_rate, (2.0 * stiffness + contact_stiffness) * w);
    damping_rate = std::max(damping_rate, (2.0 * damping + contact_damping) * w);
  }
  return {stiffness_rate, damping_rate};
}

}  // namespace drapelab::kernels
