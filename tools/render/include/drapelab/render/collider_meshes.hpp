// Triangle meshes of the collider shapes for drawing, in the collider's local frame (the frame of
// collider_pose: origin at its centre, the shape's own axes before `rotation`), so one mesh per
// collider is built once and posed at every frame with collider_pose(c, t).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "drapelab/collider.hpp"
#include "drapelab/render/camera.hpp"

namespace drapelab::render {

struct DrawMesh {
  Eigen::Matrix3Xd positions;  // m, 3 x V
  Eigen::Matrix3Xd normals;    // unit, 3 x V (outward)
  Eigen::Matrix3Xf colors;     // RGB in [0, 1], 3 x V
  Eigen::Matrix3Xi triangles;  // vertex indices, counter-clockwise seen from outside
};

// Sphere, capped cylinder, capsule and box as the contact model sees them (cylinder and capsule
// along `axis`, of full length `height` between cap centres; a capsule's hemispheres add `radius`
// at each end), and a mesh collider's own triangles. Smooth normals on curved surfaces, flat ones
// on caps, box faces and across a mesh's sharp edges. `color` for every vertex.
DrawMesh solid_collider_mesh(const Collider& collider, const Eigen::Vector3f& color);

// A plane drawn as a finite square floor patch of half side `half_size` (m) with a checker of
// `tile` m squares, centred on the foot (in the plane) of `local_center`, a point given in the
// plane collider's local frame. Two tile colours.
DrawMesh plane_patch_mesh(const Collider& plane, const Eigen::Vector3d& local_center,
                          double half_size, double tile, const Eigen::Vector3f& color_a,
                          const Eigen::Vector3f& color_b);

// A tile size of 1, 2 or 5 times a power of ten close to span / 10 (m): a floor grid with round
// sizes.
double round_tile_size(double span);

// The world-space box of a solid collider at a pose (planes are unbounded and give an empty box).
void add_collider_bounds(const Collider& collider, const Eigen::Isometry3d& pose, Bounds& bounds);

}  // namespace drapelab::render
