// A drag on the cloth: a particle pulled toward a moving target by a spring of rest length 0, as
// the viewer's mouse does and as a scene's `interactions:` replays it. The target moves through
// keyframes, linearly between them; the drag acts from the first keyframe to the last and is
// released after it, unless it is still held (the viewer's button down), when the target stays at
// the last keyframe. Every solver applies it as a soft distance constraint of length 0 whose far
// end is the target (distance_constraints.hpp).
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace drapelab {

struct DragKeyframe {
  double t = 0.0;                                    // s
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  // m
};

struct DragTrack {
  int particle = 0;                     // the particle pulled
  double stiffness = 0.0;               // N/m, of the spring
  double damping = 0.0;                 // N*s/m, along it
  std::vector<DragKeyframe> keyframes;  // in increasing time
  bool held = false;                    // acts on after the last keyframe (a live drag)

  // Whether the drag pulls at time t (s).
  bool active(double t) const {
    if (keyframes.empty() || t < keyframes.front().t) return false;
    return held || t <= keyframes.back().t;
  }
  // The target (m) and its velocity (m/s) at time t (s), for an active drag.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> target(double t) const;
};

}  // namespace drapelab
