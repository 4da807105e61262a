// The damped spring of the cloth assignment, as pure functions over plain values.
//
//   f1 = -[ks (|x1 - x2| - l0) + kd ((v1 - v2) . (x1 - x2) / |x1 - x2|)] (x1 - x2) / |x1 - x2|
//   f2 = -f1
//
// Units: x in m, v in m/s, ks in N/m, kd in N*s/m, l0 in m, force in N, energy in J.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace drapelab {

// Force on particle 1 (particle 2 receives the negative). A spring of zero length has no direction
// and exerts no force (returns zero rather than NaN).
inline Eigen::Vector3d damped_spring_force(const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                                           const Eigen::Vector3d& v1, const Eigen::Vector3d& v2,
                                           double ks, double kd, double rest_length) {
  const Eigen::Vector3d d = x1 - x2;
  const double length = d.norm();
  if (length == 0.0) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d direction = d / length;
  const double elastic = ks * (length - rest_length);    // N
  const double viscous = kd * (v1 - v2).dot(direction);  // N
  return -(elastic + viscous) * direction;
}

// The power the damper takes, kd ((v1 - v2) . (x1 - x2) / |x1 - x2|)^2 (W); zero at zero length.
inline double spring_damper_power(const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                                  const Eigen::Vector3d& v1, const Eigen::Vector3d& v2, double kd) {
  const Eigen::Vector3d d = x1 - x2;
  const double length = d.norm();
  if (length == 0.0) return 0.0;
  const double rate = (v1 - v2).dot(d) / length;  // m/s
  return kd * rate * rate;
}

// Elastic energy 1/2 ks (|x1 - x2| - l0)^2 (J); its negative gradient w.r.t. x1 is the elastic
// force.
inline double spring_energy(const Eigen::Vector3d& x1, const Eigen::Vector3d& x2, double ks,
                            double rest_length) {
  const double extension = (x1 - x2).norm() - rest_length;
  return 0.5 * ks * extension * extension;
}

}  // namespace drapelab
