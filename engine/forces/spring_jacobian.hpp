// Derivatives of the damped spring force (spring_force.hpp) for implicit integration.
//
// With d = x1 - x2, l = |d|, u = d / l, P = I - u u^T (projector across the spring), w = v1 - v2:
//   elastic  f1 = -ks (l - l0) u         df1/dx1 = -ks [u u^T + (1 - l0 / l) P]
//   viscous  f1 = -kd (w . u) u          df1/dv1 = -kd u u^T
//                                        df1/dx1 = -(kd / l) [(w . u) P + u w^T P]
// and, since the force depends on x1 - x2 and v1 - v2 only, df1/dx2 = -df1/dx1, df2 = -df1.
// Units: df/dx in N/m, df/dv in N*s/m.
#pragma once

#include <Eigen/Core>
#include <algorithm>

namespace drapelab {

struct SpringJacobian {
  Eigen::Matrix3d dforce_dx = Eigen::Matrix3d::Zero();  // d f1 / d x1, N/m
  Eigen::Matrix3d dforce_dv = Eigen::Matrix3d::Zero();  // d f1 / d v1, N*s/m
};

// The exact derivative of damped_spring_force, elastic and viscous parts together. The viscous
// part's position derivative is not symmetric, so the implicit solve leaves it out (see below);
// this full form is what finite differences check.
inline SpringJacobian spring_jacobian_exact(const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                                            const Eigen::Vector3d& v1, const Eigen::Vector3d& v2,
                                            double ks, double kd, double rest_length) {
  SpringJacobian j;
  const Eigen::Vector3d d = x1 - x2;
  const double length = d.norm();
  if (length == 0.0) return j;  // the force is zero there (spring_force.hpp)
  const Eigen::Vector3d u = d / length;
  const Eigen::Matrix3d along = u * u.transpose();
  const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - along;
  const Eigen::Vector3d w = v1 - v2;
  j.dforce_dx = -ks * (along + (1.0 - rest_length / length) * across) -
                (kd / length) * (w.dot(u) * across + u * (across * w).transpose());
  j.dforce_dv = -kd * along;
  return j;
}

// What the implicit solve uses: the elastic position derivative and the viscous velocity
// derivative, both symmetric and negative semidefinite so that M - h D - h^2 K is positive definite
// and conjugate gradients apply. Two departures from the exact Jacobian, both as in Baraff & Witkin
// (1998) and Choi & Ko (2002): the across-spring term (1 - l0 / l) is clamped at 0 for a compressed
// spring (it would be negative, making the matrix indefinite; a compressed spring buckles rather
// than pushes sideways), and the viscous force's position derivative (proportional to the relative
// velocity, not symmetric) is left out.
inline SpringJacobian spring_jacobian_for_solve(const Eigen::Vector3d& x1,
                                                const Eigen::Vector3d& x2, double ks, double kd,
                                                double rest_length) {
  SpringJacobian j;
  const Eigen::Vector3d d = x1 - x2;
  const double length = d.norm();
  if (length == 0.0) return j;
  const Eigen::Vector3d u = d / length;
  const Eigen::Matrix3d along = u * u.transpose();
  const double transverse = std::max(0.0, 1.0 - rest_length / length);
  j.dforce_dx = -ks * (along + transverse * (Eigen::Matrix3d::Identity() - along));
  j.dforce_dv = -kd * along;
  return j;
}

}  // namespace drapelab
