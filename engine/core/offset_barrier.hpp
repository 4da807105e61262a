// The contact energy of offset geometric contact (Chen et al., "Offset Geometric Contact", 2025) as
// a function of the distance d between two parts of the cloth, on plain values. With r the offset
// (the thickness the two parts keep), k the stiffness and tau = r / 2:
//
//   g(d) = k (r - d)^2 / 2                      for tau <= d < r   (a spring while the gap is wide)
//   g(d) = k tau^2 (ln(tau / d) + 1 / 2)        for 0 < d < tau    (a barrier as it closes)
//   g(d) = 0                                    for d >= r
//
// The barrier's weight k tau^2 makes g, g' and g'' continuous at tau (there g' = -k tau and
// g'' = k), so a Newton step meets no kink; g grows without bound as d -> 0, so no finite force
// closes the gap, whatever k is. g'' > 0 below r: the energy is convex in d.
#pragma once

#include <cmath>

namespace drapelab {

struct OffsetBarrier {
  double offset = 0.0;     // m, r
  double stiffness = 0.0;  // N/m, k

  double switch_distance() const { return 0.5 * offset; }  // m, tau

  // g(d) (J).
  double energy(double d) const {
    if (d >= offset) return 0.0;
    const double tau = switch_distance();
    if (d >= tau) return 0.5 * stiffness * (offset - d) * (offset - d);
    return stiffness * tau * tau * (std::log(tau / d) + 0.5);
  }
  // g'(d) (N): never positive, so -g' is the push apart.
  double slope(double d) const {
    if (d >= offset) return 0.0;
    const double tau = switch_distance();
    if (d >= tau) return -stiffness * (offset - d);
    return -stiffness * tau * tau / d;
  }
  // g''(d) (N/m).
  double curvature(double d) const {
    if (d >= offset) return 0.0;
    const double tau = switch_distance();
    if (d >= tau) return stiffness;
    return stiffness * tau * tau / (d * d);
  }
};

}  // namespace drapelab
