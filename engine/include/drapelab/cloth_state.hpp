// ClothState: what a step writes. Cheap to copy; the model is never written by a step.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace drapelab {

struct ClothState {
  Eigen::Matrix3Xd x;  // positions, m, 3 x N (node i is the same material point in every solver)
  Eigen::Matrix3Xd v;  // velocities, m/s, 3 x N
  double time = 0.0;   // s, simulated
  std::int64_t step_count = 0;
};

}  // namespace drapelab
