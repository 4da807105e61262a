// Particle-versus-collider queries with FCL's exact closed-form shape routines. A particle is a
// sphere of radius r (the cloth's thickness); FCL's sphere-{sphere, capsule, cylinder, box,
// halfspace} intersection routines, called directly, give the exact penetration depth and normal
// (docs/bullet.md, "FCL queries we use" and "FCL accuracy"). A mesh collider is FCL's hierarchy of
// its triangles, searched for the nearest point and signed by pseudo-normals (mesh_surface.hpp).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <vector>

#include "drapelab/collider.hpp"
#include "drapelab/mesh_surface.hpp"

namespace fcl {
template <typename S>
class CollisionGeometry;
template <typename S>
struct ContactPoint;
}  // namespace fcl

namespace drapelab {

// A collider as FCL geometry. FCL's cylinder and capsule lie along their local z axis, so
// `shape_in_collider` turns z onto the collider's axis; FCL's box takes full side lengths.
struct FclCollider {
  std::shared_ptr<fcl::CollisionGeometry<double>> geometry;
  Eigen::Isometry3d shape_in_collider =
      Eigen::Isometry3d::Identity();  // FCL shape frame -> collider frame
  // A mesh collider's surface, whose hierarchy `geometry` holds; null for the other shapes.
  std::shared_ptr<const MeshSurface> mesh;
};

// The one conversion from our Collider to FCL geometry. A mesh collider must have its mesh; a
// mesh_surface_problem in it throws std::invalid_argument (the scene loader reports it first).
FclCollider make_fcl_collider(const Collider& collider);

// Overlap of a particle sphere (centre x, radius r, m) with a collider posed by `shape_pose`
// (FCL shape frame -> world, i.e. collider_pose * shape_in_collider).
struct ParticleContact {
  double depth = 0.0;                                 // m, > 0: how far the sphere reaches inside
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  // unit, out of the collider (push direction)
};

// Calls FCL's closed-form sphere-shape routines directly with a reused contact buffer, one per
// thread, so a query allocates nothing after a thread's first contact (fcl::collide builds a new
// buffer on every call). Safe to query from several threads at once.
class ParticleContactQuery {
 public:
  explicit ParticleContactQuery(double radius);  // m, the particle sphere's radius
  ~ParticleContactQuery();
  ParticleContactQuery(const ParticleContactQuery&) = delete;
  ParticleContactQuery& operator=(const ParticleContactQuery&) = delete;

  // The contact when the sphere overlaps the collider; nothing when they are apart. A mesh
  // collider sees a particle inside it at any depth while the particle is within the mesh's box.
  std::optional<ParticleContact> contact(const FclCollider& collider,
                                         const Eigen::Isometry3d& shape_pose,
                                         const Eigen::Vector3d& x) const;
  // Signed distance from the particle's surface to the collider (m): d(x) - r, negative inside the
  // thickness shell. Exact: FCL's contact depth when overlapping; otherwise FCL's distance, or for
  // a half-space its own signed distance.
  double clearance(const FclCollider& collider, const Eigen::Isometry3d& shape_pose,
                   const Eigen::Vector3d& x) const;
  double radius() const { return radius_; }

 private:
  double radius_;
  std::shared_ptr<fcl::CollisionGeometry<double>> sphere_;
};

// Radius (m) of the smallest sphere about the FCL shape frame's origin that holds the shape, exact
// for every shape make_fcl_collider makes (a sphere's own radius, not the sphere around its
// bounding box, which is sqrt(3) times larger); infinite for a plane.
double bounding_radius(const FclCollider& collider);

// World-space bounding box of a posed collider, grown by `margin` (m). Unbounded for a plane.
Eigen::AlignedBox3d collider_bounds(const FclCollider& collider,
                                    const Eigen::Isometry3d& shape_pose, double margin);

}  // namespace drapelab
