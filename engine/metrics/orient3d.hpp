// The orient3d predicate, exact for every finite double input: a floating-point evaluation whose
// sign is trusted when Shewchuk's static error bound proves it, and an exact evaluation with GMP
// integers when it cannot (docs/metrics.md, "Self-intersections").
#pragma once

#include <Eigen/Core>
#include <optional>

namespace drapelab {

// Sign of det[a - d; b - d; c - d]: +1 when d lies below the plane of a, b, c (a, b, c
// counter-clockwise seen from above), -1 above, 0 when the four points are coplanar. Inputs must be
// finite. Swapping any two points flips the sign.
int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
             const Eigen::Vector3d& d);

// The floating-point stage alone: the sign when the rounded determinant is farther from 0 than its
// error bound, nothing when the bound cannot decide (then only the exact stage can).
std::optional<int> orient3d_filtered(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                     const Eigen::Vector3d& c, const Eigen::Vector3d& d);

// The exact stage alone: every coordinate scaled exactly to a whole number, no rounding anywhere.
int orient3d_exact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d);

}  // namespace drapelab
