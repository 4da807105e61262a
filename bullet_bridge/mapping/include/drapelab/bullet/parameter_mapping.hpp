// How our cloth's parameters become Bullet's (docs/bullet.md, "Mapping our parameters to the
// classic cloth" and "Fairness table"). Plain arithmetic on our model and colliders, with no Bullet
// header, so that the scene loader can choose Bullet's defaults without linking Bullet.
#pragma once

#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/collider.hpp"
#include "drapelab/triangle_mesh.hpp"

namespace drapelab::bullet {

// The classic cloth's link stiffness matches our springs while ks w h^2 stays below this (5 % in a
// network); above it the classic cloth is measurably softer.
inline constexpr double kMaxMappedLinkCompliance = 0.1;

// kLST of a link with stiffness ks (N/m) between particles of inverse masses summing to w (1/kg),
// for n sweeps of substep h (s): 1 - (1 + ks w h^2)^(-1/n), exact for one link.
double mapped_link_stiffness(double ks, double w, double h, int iterations);

// The largest ks w over the model's springs (1/s^2); times h^2 it is the ratio above.
double largest_link_rate(const ClothModel& model);

// The longest substep (s) at which every link stays within kMaxMappedLinkCompliance; infinity
// without springs.
double largest_mapped_step(const ClothModel& model);

// A voxel size that resolves the colliders: min(margin, smallest feature / 10) (m).
double default_voxel_size(const std::vector<Collider>& colliders, double margin);

// Whether every connected part of the mesh is convex: each of its vertices on or behind the plane
// of each of its triangles, to rounding of the mesh's size. The convex hulls of such parts are the
// mesh itself.
bool mesh_parts_are_convex(const TriangleMesh& mesh);

// Whether the deformable cloth meets the scene's mesh colliders as their triangles (face contacts
// against a GImpact mesh): when any of them has a concave part, which its hull would fill.
// Otherwise it meets them as their parts' hulls, by node contacts as it does the primitives, at a
// fraction of the cost (docs/bullet.md, "Mesh colliders").
bool deformable_meets_mesh_triangles(const std::vector<Collider>& colliders);

}  // namespace drapelab::bullet
