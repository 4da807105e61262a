// The moving target of a drag (see drag_track.hpp).
#include "drapelab/drag_track.hpp"

namespace drapelab {

std::pair<Eigen::Vector3d, Eigen::Vector3d> DragTrack::target(double t) const {
  if (keyframes.empty()) return {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  if (t <= keyframes.front().t) return {keyframes.front().target, Eigen::Vector3d::Zero()};
  for (std::size_t k = 1; k < keyframes.size(); ++k) {
    const DragKeyframe& a = keyframes[k - 1];
    const DragKeyframe& b = keyframes[k];
    if (t > b.t) continue;
    const double span = b.t - a.t;  // s, > 0 (keyframes increase)
    const Eigen::Vector3d velocity = (b.target - a.target) / span;
    return {a.target + (t - a.t) * velocity, velocity};
  }
  return {keyframes.back().target, Eigen::Vector3d::Zero()};  // held after the last keyframe
}

}  // namespace drapelab
