// Colliders as kinematic Bullet bodies (see bullet_colliders.hpp).
#include "bullet_colliders.hpp"

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>

#include "bullet_math.hpp"

namespace drapelab::bullet {
namespace {

// A plane becomes a box this thick and wide (m): btStaticPlaneShape goes through Bullet's concave
// path, whose signed distance is 0, so soft bodies cannot rest on it (docs/bullet.md, "Soft-rigid
// contact through the signed-distance cache").
constexpr double kPlaneHalfThickness = 5.0;
constexpr double kPlaneHalfWidth = 500.0;

Eigen::Matrix3d y_onto(const Eigen::Vector3d& direction) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitY(), direction.normalized())
      .toRotationMatrix();
}

void add_convex_parts(const TriangleMesh& mesh, double edge_margin, BulletShape& out) {
  auto compound = std::make_unique<btCompoundShape>();
  for (const std::vector<int>& part : connected_parts(mesh)) {
    auto hull = std::make_unique<btConvexHullShape>();
    for (const int v : part)
      hull->addPoint(to_bullet(Eigen::Vector3d(mesh.vertices.col(v))), false);
    hull->recalcLocalAabb();
    hull->setMargin(edge_margin);
    compound->addChildShape(btTransform::getIdentity(), hull.get());
    out.parts.push_back(std::move(hull));
  }
  compound->setMargin(edge_margin);
  out.shape = std::move(compound);
}

// GImpact keeps its triangles' margin (default 1 cm) outside the surface: the cloth rests that far
// off, so the mesh gets the edge margin like a box.
void add_triangles(const TriangleMesh& mesh, double edge_margin, BulletShape& out) {
  out.mesh_coordinates.assign(mesh.vertices.data(), mesh.vertices.data() + mesh.vertices.size());
  out.mesh_indices.assign(mesh.triangles.data(), mesh.triangles.data() + mesh.triangles.size());
  out.mesh_triangles = std::make_unique<btTriangleIndexVertexArray>(
      static_cast<int>(mesh.triangles.cols()), out.mesh_indices.data(), 3 * sizeof(int),
      static_cast<int>(mesh.vertices.cols()), out.mesh_coordinates.data(), 3 * sizeof(btScalar));
  auto shape = std::make_unique<btGImpactMeshShape>(out.mesh_triangles.get());
  shape->setMargin(edge_margin);
  shape->updateBound();
  out.shape = std::move(shape);
}

}  // namespace

BulletShape make_bullet_shape(const Collider& c, double edge_margin, BulletMeshShape mesh_shape) {
  BulletShape out;
  switch (c.shape) {
    case ColliderShape::sphere:
      out.shape = std::make_unique<btSphereShape>(c.radius);
      break;
    case ColliderShape::capsule:
      out.shape =
          std::make_unique<btCapsuleShape>(c.radius, c.height);  // height: between cap centres
      out.shape_in_collider.linear() = y_onto(c.axis);
      break;
    case ColliderShape::cylinder:
      out.shape = std::make_unique<btCylinderShape>(btVector3(c.radius, 0.5 * c.height, c.radius));
      out.shape->setMargin(edge_margin);
      out.shape_in_collider.linear() = y_onto(c.axis);
      break;
    case ColliderShape::box:
      out.shape = std::make_unique<btBoxShape>(to_bullet(c.half_extents));
      out.shape->setMargin(edge_margin);
      break;
    case ColliderShape::plane:
      out.shape = std::make_unique<btBoxShape>(
          btVector3(kPlaneHalfWidth, kPlaneHalfThickness, kPlaneHalfWidth));
      out.shape->setMargin(edge_margin);
      out.shape_in_collider.linear() = y_onto(c.normal);
      out.shape_in_collider.translation() = -kPlaneHalfThickness * c.normal.normalized();
      break;
    case ColliderShape::mesh:
      if (mesh_shape == BulletMeshShape::triangles)
        add_triangles(*c.mesh, edge_margin, out);
      else
        add_convex_parts(*c.mesh, edge_margin, out);
      break;
  }
  return out;
}

KinematicColliders::KinematicColliders(const std::vector<Collider>& colliders, double edge_margin,
                                       btDynamicsWorld& world, double friction_divisor,
                                       BulletMeshShape mesh_shape)
    : world_(world), colliders_(colliders) {
  for (const auto& collider : colliders_) {
    shapes_.push_back(make_bullet_shape(collider, edge_margin, mesh_shape));
    btCollisionShape* shape = shapes_.back().shape.get();
    btVector3 inertia(0, 0, 0);  // kg m^2, in the shape's principal axes
    if (collider.dynamic()) shape->calculateLocalInertia(collider.dynamic_mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(collider.dynamic_mass, nullptr, shape, inertia);
    info.m_friction = collider.friction / friction_divisor;
    info.m_startWorldTransform =
        to_bullet(collider_pose(collider, 0.0) * shapes_.back().shape_in_collider);
    auto body = std::make_unique<btRigidBody>(info);
    if (!collider.dynamic())
      body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    body->setActivationState(DISABLE_DEACTIVATION);
    world_.addRigidBody(body.get());
    bodies_.push_back(std::move(body));
  }
}

KinematicColliders::~KinematicColliders() {
  for (auto& body : bodies_) world_.removeRigidBody(body.get());
}

void KinematicColliders::move_to(double t0, double t1) {
  const double h = t1 - t0;
  for (std::size_t c = 0; c < bodies_.size(); ++c) {
    if (colliders_[c].dynamic()) continue;  // the world moves it
    const Eigen::Isometry3d before =
        collider_pose(colliders_[c], t0) * shapes_[c].shape_in_collider;
    const Eigen::Isometry3d after = collider_pose(colliders_[c], t1) * shapes_[c].shape_in_collider;
    btRigidBody& body = *bodies_[c];
    body.setInterpolationWorldTransform(to_bullet(before));
    body.setWorldTransform(to_bullet(after));
    // Velocities of the motion over the substep, for contact response and friction.
    const Eigen::AngleAxisd turn(after.linear() * before.linear().transpose());
    const Eigen::Vector3d angular =
        h > 0.0 ? Eigen::Vector3d(turn.axis() * turn.angle() / h) : Eigen::Vector3d::Zero();
    const Eigen::Vector3d linear =
        h > 0.0 ? Eigen::Vector3d((after.translation() - before.translation()) / h)
                : Eigen::Vector3d::Zero();
    body.setLinearVelocity(to_bullet(linear));
    body.setAngularVelocity(to_bullet(angular));
    body.setInterpolationLinearVelocity(to_bullet(linear));
    body.setInterpolationAngularVelocity(to_bullet(angular));
  }
}

Eigen::Isometry3d KinematicColliders::collider_pose_in_world(std::size_t c) const {
  return to_eigen(bodies_[c]->getWorldTransform()) * shapes_[c].shape_in_collider.inverse();
}

ColliderSubstepMotion KinematicColliders::substep_motion(std::size_t c, double h) const {
  const btRigidBody& body = *bodies_[c];
  ColliderSubstepMotion motion;
  if (colliders_[c].dynamic()) {
    // A dynamic body's origin is its centre of mass (its shape sits there, unshifted).
    motion.start = collider_pose_in_world(c);
    motion.velocity = to_eigen(body.getLinearVelocity());
    motion.angular_velocity = to_eigen(body.getAngularVelocity());
    motion.end = motion.start;
    motion.end.translation() += h * motion.velocity;
    const double turn = h * motion.angular_velocity.norm();  // rad
    if (turn > 0.0)
      motion.end.linear() =
          Eigen::AngleAxisd(turn, motion.angular_velocity.normalized()).toRotationMatrix() *
          motion.start.linear();
    return motion;
  }
  motion.start =
      to_eigen(body.getInterpolationWorldTransform()) * shapes_[c].shape_in_collider.inverse();
  motion.end = collider_pose_in_world(c);
  // Bullet's linear velocity is that of the shape's origin; the collider's origin differs from it
  // where the shape is offset in the collider's frame (a plane's box), so take the collider
  // origin's own displacement over the substep. The angular velocity is the same for both frames.
  if (h > 0.0) motion.velocity = (motion.end.translation() - motion.start.translation()) / h;
  motion.angular_velocity = to_eigen(body.getAngularVelocity());
  return motion;
}

void KinematicColliders::write_substep(double t0, double h, ColliderPoseTable& table) const {
  table.set_substep(t0, t0 + h);
  for (std::size_t c = 0; c < bodies_.size(); ++c) table.set(c, substep_motion(c, h));
}

std::vector<BodyState> KinematicColliders::dynamic_bodies() const {
  std::vector<BodyState> out;
  for (std::size_t c = 0; c < bodies_.size(); ++c) {
    if (!colliders_[c].dynamic()) continue;
    BodyState body;
    body.collider = static_cast<int>(c);
    body.pose = collider_pose_in_world(c);
    body.velocity = to_eigen(bodies_[c]->getLinearVelocity());
    body.angular_velocity = to_eigen(bodies_[c]->getAngularVelocity());
    out.push_back(body);
  }
  return out;
}

void KinematicColliders::apply_loads(const std::vector<ColliderForce>& forces) {
  apply(forces, /*impulse_step=*/0.0);
}

void KinematicColliders::apply_impulses(const std::vector<ColliderForce>& forces, double h) {
  apply(forces, h);
}

void KinematicColliders::apply(const std::vector<ColliderForce>& forces, double impulse_step) {
  for (std::size_t c = 0; c < bodies_.size() && c < forces.size(); ++c) {
    if (!colliders_[c].dynamic()) continue;
    btRigidBody& body = *bodies_[c];
    const Eigen::Vector3d centre = to_eigen(body.getCenterOfMassPosition());
    // The moment about the centre of mass from the moment about the world origin.
    const Eigen::Vector3d moment = forces[c].torque - centre.cross(forces[c].force);
    if (impulse_step > 0.0) {
      body.applyCentralImpulse(to_bullet(impulse_step * forces[c].force));
      body.applyTorqueImpulse(to_bullet(impulse_step * moment));
    } else {
      body.applyCentralForce(to_bullet(forces[c].force));
      body.applyTorque(to_bullet(moment));
    }
  }
}

int KinematicColliders::index_of(const btCollisionObject* body) const {
  for (std::size_t c = 0; c < bodies_.size(); ++c)
    if (bodies_[c].get() == body) return static_cast<int>(c);
  return -1;
}

}  // namespace drapelab::bullet
