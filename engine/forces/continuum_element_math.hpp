// The small vector helpers the continuum's element loops share (continuum_elements.cpp,
// continuum_force_loops.cpp): dot and cross products of 3-vectors and an atan2 that vectorises.
// Like those sources, no Eigen: they are built with OpenMP for the build machine's CPU.
#pragma once

#include <algorithm>
#include <cmath>

namespace drapelab::kernels {

inline constexpr double kPi = 3.14159265358979323846;

inline double dot3(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline void cross3(const double* a, const double* b, double* out) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

// atan2(y, x) in (-pi, pi] without a library call, so that the hinge loop vectorises, and with
// one division: the angle of (|x|, |y|) is that of (max, min) or pi/2 minus it, in [0, pi/4];
// subtracting the nearest of the angles j pi/16 (tan(a - b) = (tan a - tan b) / (1 + tan a tan b),
// one quotient of min and max) leaves an angle within pi/32, whose tangent u <= 0.0985 needs 8
// terms of the odd series atan(u) = u - u^3/3 + u^5/5 - ... for less than 1e-17 relative; then
// the octant and the quadrant. (0, 0) gives 0.
[[gnu::always_inline]] inline double angle_of(double y, double x) {
  const double ax = std::fabs(x), ay = std::fabs(y);
  const double low = std::min(ax, ay), high = std::max(ax, ay);
  // The nearest j pi/16 to atan(low / high): compare with the midpoints' tangents tan((2j+1)
  // pi/32).
  double tangent = 0.0, base = 0.0;  // tan(j pi/16) and j pi/16 (rad)
  tangent = low > 0.09849140335716425 * high ? 0.198912367379658 : tangent;
  base = low > 0.09849140335716425 * high ? 0.19634954084936207 : base;
  tangent = low > 0.3033466836073424 * high ? 0.41421356237309503 : tangent;
  base = low > 0.3033466836073424 * high ? 0.39269908169872414 : base;
  tangent = low > 0.5345111359507916 * high ? 0.6681786379192989 : tangent;
  base = low > 0.5345111359507916 * high ? 0.5890486225480862 : base;
  tangent = low > 0.8206787908286602 * high ? 1.0 : tangent;
  base = low > 0.8206787908286602 * high ? 0.25 * kPi : base;
  const double denominator = high + tangent * low;
  const double u = denominator > 0.0 ? (low - tangent * high) / denominator : 0.0;
  const double z = u * u, z2 = z * z, z4 = z2 * z2;
  // 1 - z/3 + z^2/5 - ... - z^7/15 in Estrin's pairs, so the terms do not wait on each other
  // (the coefficients as constants: a division by 3 is a division, a product by 1/3 is not)
  constexpr double c1 = 1.0 / 3, c2 = 1.0 / 5, c3 = 1.0 / 7, c4 = 1.0 / 9, c5 = 1.0 / 11,
                   c6 = 1.0 / 13, c7 = 1.0 / 15;
  const double series =
      (1.0 - c1 * z) + z2 * (c2 - c3 * z) + z4 * ((c4 - c5 * z) + z2 * (c6 - c7 * z));
  double phi = base + u * series;
  phi = ay > ax ? 0.5 * kPi - phi : phi;
  phi = x < 0.0 ? kPi - phi : phi;
  return y < 0.0 ? -phi : phi;
}

}  // namespace drapelab::kernels
