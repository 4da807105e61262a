// A circular cloth of concentric rings, for drape tests: a centre particle, then `rings` rings out
// to the radius, each with about 2 pi r / (ring spacing) particles so that triangles stay close to
// equilateral and particles carry similar areas. When a support radius is given, one ring lies
// exactly on it (the rings inside and outside are spaced evenly on their own), so the drape
// coefficient has no offset from a support edge falling between rings.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "drapelab/cloth_limits.hpp"
#include "drapelab/mesh_cloth.hpp"

namespace drapelab {

struct DiscSpec {
  double radius = 0.15;                   // m
  int rings = 20;                         // rings from the centre to the rim, >= 1
  Eigen::Vector3d center{0.0, 1.0, 0.0};  // m
  Eigen::Vector3d rotation =
      Eigen::Vector3d::Zero();    // deg, Euler (x, y, z); unrotated it is horizontal
  std::optional<double> ring_at;  // m, a radius in (0, radius) that must be a ring
};

// Ring radii r_1 .. r_rings (m), increasing, the last equal to the radius.
std::vector<double> disc_ring_radii(const DiscSpec& spec);
// Particles on ring k (k >= 1). Throws std::invalid_argument when they exceed kMaxClothParticles.
int disc_ring_count(const DiscSpec& spec, int ring);
// The disc's particle, spring (an upper bound) and triangle counts, computed without building it.
ClothSize disc_cloth_size(const DiscSpec& spec);

// The disc's vertices (centre first, then ring by ring from angle 0 about +y), triangles wound
// counter-clockwise about the (rotated) +y normal, and planar UVs. Throws std::invalid_argument on
// rings < 1, radius <= 0, ring_at outside (0, radius), or a size beyond cloth_limits.hpp.
TriangleMesh make_disc_mesh(const DiscSpec& spec);

// Index of the first particle of ring k (ring 0 is the centre particle).
int disc_ring_start(const DiscSpec& spec, int ring);

}  // namespace drapelab
