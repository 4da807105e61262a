// Colliders shared by every solver of a scene: sphere, capped cylinder, capsule, box, plane (a
// half-space) and triangle mesh, each with a pose, an optional kinematic motion and a friction
// coefficient.
// One definition; converted once to FCL (contact_fcl.hpp) and once to Bullet (bullet_bridge/).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "drapelab/triangle_mesh.hpp"

namespace drapelab {

enum class ColliderShape { sphere, cylinder, capsule, box, plane, mesh };
const char* collider_shape_name(ColliderShape shape);

// A pose at time t, for linear keyframe motion: the collider's centre in the world, and a rotation
// applied after the collider's own `rotation`, about that centre.
struct ColliderKeyframe {
  double t = 0.0;                                    // s
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // m, world
  Eigen::Vector3d rotation =
      Eigen::Vector3d::Zero();  // deg, Euler angles (x, y, z), see euler_rotation
};

// Kinematic motion: either constant velocities, or keyframes (then the velocities must be zero).
struct ColliderMotion {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // m/s of the centre
  Eigen::Vector3d angular_velocity =
      Eigen::Vector3d::Zero();              // deg/s, world axes, about the centre
  std::vector<ColliderKeyframe> keyframes;  // increasing t; held before and after

  bool is_static() const {
    return keyframes.empty() && velocity.isZero(0) && angular_velocity.isZero(0);
  }
};

// Where a frame sits in its parent's frame (the world's for a collider without a parent): its
// centre, its rotation at rest and its kinematic motion, all given in the parent's frame.
struct ColliderFrame {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();    // m
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();  // deg, Euler angles (x, y, z)
  ColliderMotion motion;
};

struct Collider {
  std::string name;
  ColliderShape shape = ColliderShape::sphere;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // m; for a plane, a point on it; unused with
                                                     //    keyframes, which give the centre
  double radius = 0.5;                               // m: sphere, cylinder, capsule
  double height = 1.0;  // m: full length along the axis (capsule: of its
                        //    segment, without the end caps)
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();  // cylinder and capsule, before rotation (unit)
  Eigen::Vector3d half_extents{0.5, 0.5, 0.5};      // m: box
  Eigen::Vector3d normal =
      Eigen::Vector3d::UnitY();  // plane, before rotation (unit); solid below it
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();  // deg, Euler angles (x, y, z)
  double friction = 0.3;                               // kinetic Coulomb coefficient
  double static_friction = 0.3;                        // static Coulomb coefficient, >= friction
  // mesh: the surface in the collider's own frame (m: the OBJ file's coordinates times
  // mesh_scale, so the file's origin sits at `center`), shared by every copy of the collider; and
  // the file and scale as the scene gave them, for resolved.yaml.
  std::shared_ptr<const TriangleMesh> mesh;
  std::string mesh_file;
  Eigen::Vector3d mesh_scale = Eigen::Vector3d::Ones();
  ColliderMotion motion;
  // The collider it moves with (empty: none): then center, rotation and motion are in that
  // collider's frame, and `ancestors` holds the frames it moves with, nearest first (the scene
  // loader fills them in from the names).
  std::string parent;
  std::vector<ColliderFrame> ancestors;
  // colliders[].dynamic: a rigid body of this mass (kg) in each solver's Bullet world, moved by
  // gravity and by that solver's cloth; 0 for a kinematic collider. A dynamic collider has no
  // motion and no parent: collider_pose(t) gives its pose at t = 0 for every t, and each solver
  // reports where its own copy of the body is (Solver::bodies()).
  double dynamic_mass = 0.0;

  bool dynamic() const { return dynamic_mass > 0.0; }

  // Its own frame in its parent's.
  ColliderFrame frame() const { return {center, rotation, motion}; }
  // Whether it moves at all: by its own motion, by an ancestor's, or as a dynamic body.
  bool moves() const;
};

// R = Rz(z) Ry(y) Rx(x): rotate about the fixed x axis first, then y, then z (angles in degrees).
Eigen::Matrix3d euler_rotation(const Eigen::Vector3d& degrees);

// A frame's rigid transform at time t (s): its own coordinates -> its parent's. The frame has its
// origin at the centre and the shape's own axes before `rotation`. With keyframes: translation =
// the interpolated keyframe centre, rotation = R_keyframes(t) * R(rotation).
Eigen::Isometry3d frame_pose(const ColliderFrame& frame, double t);
// Velocity (m/s, in the parent's axes) at time t of the frame's material point at p (the parent's
// coordinates), relative to the parent's frame.
Eigen::Vector3d frame_point_velocity(const ColliderFrame& frame, double t,
                                     const Eigen::Vector3d& p);

// The collider's rigid transform at time t (s): local frame -> world, its ancestors' poses
// composed with its own (root first): W = A_root(t) ... A_parent(t) A_own(t).
Eigen::Isometry3d collider_pose(const Collider& collider, double t);

// Velocity (m/s) at time t of the collider's material point that is at world position p: the sum
// over the chain of each frame's own point velocity, turned into the world by the frames above
// it.
Eigen::Vector3d collider_point_velocity(const Collider& collider, double t,
                                        const Eigen::Vector3d& p);

}  // namespace drapelab
