// Conversions between Eigen (engine) and Bullet (double build) types.
#pragma once

#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

#include <Eigen/Geometry>

namespace drapelab::bullet {

inline btVector3 to_bullet(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }
inline Eigen::Vector3d to_eigen(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }

inline btTransform to_bullet(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d& r = pose.linear();
  const btMatrix3x3 basis(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1),
                          r(2, 2));
  return btTransform(basis, to_bullet(pose.translation()));
}

inline Eigen::Isometry3d to_eigen(const btTransform& pose) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  for (int row = 0; row < 3; ++row) {
    for (int column = 0; column < 3; ++column)
      out.linear()(row, column) = pose.getBasis()[row][column];
    out.translation()[row] = pose.getOrigin()[row];
  }
  return out;
}

}  // namespace drapelab::bullet
