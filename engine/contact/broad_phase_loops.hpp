// The contact phase's broad phase on plain arrays (no Eigen: built for the build machine's CPU, so
// that the test of every particle vectorises).
#pragma once

#include <cstdint>

namespace drapelab::kernels {

// The contact broad phase for one posed collider, in plain numbers: a plane keeps the particles
// less than `radius` above it; any other shape those inside its bounding box and bounding sphere
// (both grown by the particle radius). Lengths in m.
struct NearCollider {
  bool plane = false;
  double normal[3] = {0.0, 0.0, 0.0};                          // plane: unit world normal
  double offset = 0.0;                                         // plane: n . p of a point on it
  double radius = 0.0;                                         // plane: the particle radius
  double low[3] = {0.0, 0.0, 0.0}, high[3] = {0.0, 0.0, 0.0};  // bounding box corners
  double center[3] = {0.0, 0.0, 0.0};                          // bounding sphere centre
  double reach_squared = 0.0;  // (bounding radius + particle radius)^2
};

// Writes to `near` (room for end - begin) the particles begin <= i < end that may touch the
// collider, in increasing order, and returns how many. A branch-free test per particle, so it
// vectorises.
int near_particles(const NearCollider& collider, const double* x, int begin, int end, int* near);

}  // namespace drapelab::kernels
