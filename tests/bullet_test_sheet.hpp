// The square sheet the Bullet bridge suites build their cloths from: n x n particles in the xz plane,
// 1 cm thick, springs of 500 / 50 / 5 N/m without damping (every solver's damping is then its own).
#pragma once

#include <Eigen/Core>

#include "drapelab/grid_cloth.hpp"

namespace drapelab::testing {

// `size` (m) along each side, `center` (m), total `mass` (kg).
inline GridClothSpec bullet_test_sheet(int n, double size, const Eigen::Vector3d& center, double mass) {
  GridClothSpec spec;
  spec.nx = spec.ny = n;
  spec.size = {size, size};
  spec.center = center;
  spec.mass = mass;
  spec.thickness = 0.01;
  spec.stretch = {500.0, 0.0};
  spec.shear = {50.0, 0.0};
  spec.bend = {5.0, 0.0};
  return spec;
}

}  // namespace drapelab::testing
