// Colliders shared by every solver of a scene: sphere, capped cylinder, capsule, box and plane
// (a half-space), each with a pose, an optional kinematic motion and a friction coefficient.
// One definition; converted once to FCL (contact_fcl.hpp) and once to Bullet (bullet_bridge/).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace drapelab {

enum class ColliderShape { sphere, cylinder, capsule, box, plane };
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
  ColliderMotion motion;
};

// R = Rz(z) Ry(y) Rx(x): rotate about the fixed x axis first, then y, then z (angles in degrees).
Eigen::Matrix3d euler_rotation(const Eigen::Vector3d& degrees);

// The collider's rigid transform at time t (s): local frame -> world. The local frame has its
// origin at the collider's centre (a plane: its point) and the shape's own axes before `rotation`.
// With keyframes: translation = the interpolated keyframe centre, rotation = R_keyframes(t) *
// R(rotation).
Eigen::Isometry3d collider_pose(const Collider& collider, double t);

// Velocity (m/s) at time t of the collider's material point that is at world position p.
Eigen::Vector3d collider_point_velocity(const Collider& collider, double t,
                                        const Eigen::Vector3d& p);

}  // namespace drapelab
