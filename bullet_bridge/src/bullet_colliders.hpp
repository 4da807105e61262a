// The scene's colliders as kinematic Bullet rigid bodies, driven from the same collider_pose(t) as
// every other solver.
#pragma once

#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>
#include <BulletDynamics/Dynamics/btDynamicsWorld.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <memory>
#include <vector>

#include "drapelab/collider.hpp"
#include "drapelab/collider_pose_table.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::bullet {

// A Bullet shape for a collider, and where the shape sits in the collider's frame (Bullet's
// cylinder and capsule lie along local y; a plane becomes a thick box whose top face is the plane).
struct BulletShape {
  // A mesh's parts, which its compound `shape` refers to, or its triangles, which its GImpact
  // `shape` reads in place: declared first, so they outlive it.
  std::vector<std::unique_ptr<btCollisionShape>> parts;
  std::vector<btScalar> mesh_coordinates;  // m, x y z per vertex
  std::vector<int> mesh_indices;           // three per triangle
  std::unique_ptr<btTriangleIndexVertexArray> mesh_triangles;
  std::unique_ptr<btCollisionShape> shape;
  Eigen::Isometry3d shape_in_collider = Eigen::Isometry3d::Identity();
};

// How a mesh collider reaches Bullet (docs/bullet.md, "Mesh colliders").
enum class BulletMeshShape {
  // The convex hulls of its connected parts in one btCompoundShape: the classic cloth meets only
  // convex shapes through its signed-distance cache, and a triangle-mesh shape holds it 10 cm off
  // the surface or lets it through. Concave parts are filled.
  convex_parts,
  // Its triangles as a btGImpactMeshShape, for the deformable cloth's face contacts, which run
  // GJK against each triangle: the concave surface itself. Needs GImpact's collision algorithm
  // registered on the world's dispatcher.
  triangles,
};

// The one conversion from our Collider to Bullet. `edge_margin` (m) is given to boxes, cylinders
// and meshes, whose edges Bullet rounds by their margin (spheres and capsules are exact).
BulletShape make_bullet_shape(const Collider& collider, double edge_margin,
                              BulletMeshShape mesh_shape = BulletMeshShape::convex_parts);

// Bodies for every collider in one world: kinematic ones, which move_to(t0, t1) poses at t1 with
// the velocities of the motion over [t0, t1], as a substep needs; and the dynamic colliders'
// (colliders[].dynamic) rigid bodies, which the world moves (mass from the scene, inertia from the
// shape, no damping, never put to sleep). Each body's friction is the
// collider's divided by `friction_divisor`, for a soft body whose kDF (which Bullet multiplies into
// every collider's friction) is not 1.
class KinematicColliders {
 public:
  KinematicColliders(const std::vector<Collider>& colliders, double edge_margin,
                     btDynamicsWorld& world, double friction_divisor = 1.0,
                     BulletMeshShape mesh_shape = BulletMeshShape::convex_parts);
  ~KinematicColliders();
  KinematicColliders(const KinematicColliders&) = delete;
  KinematicColliders& operator=(const KinematicColliders&) = delete;

  void move_to(double t0, double t1);
  // The collider index of a Bullet body, or -1.
  int index_of(const btCollisionObject* body) const;
  std::size_t size() const { return bodies_.size(); }
  // Where Bullet has collider c now, as the collider's own pose (its shape offset taken out).
  Eigen::Isometry3d collider_pose_in_world(std::size_t c) const;
  // Collider c's motion over the substep of length h (s) that move_to prepared, read back from its
  // Bullet body: the start (interpolation) and end (world) transforms and the velocities. For a
  // dynamic body, called before the world moves it: its pose now, and the end pose its velocities
  // predict.
  ColliderSubstepMotion substep_motion(std::size_t c, double h) const;
  // Every collider's substep_motion over [t0, t0 + h] (s) into `table`, for a guest or for the
  // constraints that read the bodies where this world holds them.
  void write_substep(double t0, double h, ColliderPoseTable& table) const;
  // Collider c's rigid body (to anchor cloth nodes to a dynamic one).
  btRigidBody* rigid_body(std::size_t c) { return bodies_[c].get(); }
  // The dynamic bodies' states, in scene order.
  std::vector<BodyState> dynamic_bodies() const;
  // Applies to each dynamic body the load of `forces` (one per collider: force, and moment about
  // the world origin), for the world's next substep.
  void apply_loads(const std::vector<ColliderForce>& forces);
  // The same loads held over a substep of h (s), given to the bodies at once as the impulse h F
  // (and h M). The deformable world needs this: its rigid bodies integrate an applied force twice
  // (once with gravity before its solve, once more inside its constraint solver).
  void apply_impulses(const std::vector<ColliderForce>& forces, double h);

 private:
  // Forces (impulse_step 0) or the impulses impulse_step F (s).
  void apply(const std::vector<ColliderForce>& forces, double impulse_step);

  btDynamicsWorld& world_;
  std::vector<Collider> colliders_;
  std::vector<BulletShape> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
};

}  // namespace drapelab::bullet
