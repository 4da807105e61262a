// FCL conversion and particle queries (see contact_fcl.hpp).
#include "drapelab/contact_fcl.hpp"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/utility.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/halfspace.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/sphere_box.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/sphere_capsule.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/sphere_cylinder.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/sphere_sphere.h>
#include <fcl/narrowphase/distance.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace drapelab {

FclCollider make_fcl_collider(const Collider& c) {
  FclCollider out;
  switch (c.shape) {
    case ColliderShape::sphere:
      out.geometry = std::make_shared<fcl::Sphere<double>>(c.radius);
      break;
    case ColliderShape::cylinder:
    case ColliderShape::capsule: {
      if (c.shape == ColliderShape::cylinder)
        out.geometry = std::make_shared<fcl::Cylinder<double>>(c.radius, c.height);
      else
        out.geometry = std::make_shared<fcl::Capsule<double>>(c.radius, c.height);
      // FCL's axis is local z: rotate z onto the collider's axis.
      out.shape_in_collider.linear() =
          Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), c.axis.normalized())
              .toRotationMatrix();
      break;
    }
    case ColliderShape::box:
      out.geometry = std::make_shared<fcl::Box<double>>(2.0 * c.half_extents);
      break;
    case ColliderShape::plane:
      // A half-space through the collider's origin: solid where n.p <= 0 (FCL's Plane is
      // two-sided).
      out.geometry = std::make_shared<fcl::Halfspace<double>>(c.normal.normalized(), 0.0);
      break;
    case ColliderShape::mesh: {
      if (!c.mesh) throw std::invalid_argument("mesh collider '" + c.name + "' has no mesh");
      auto surface = std::make_shared<const MeshSurface>(*c.mesh);
      out.geometry = surface->bvh();
      out.mesh = std::move(surface);
      break;
    }
  }
  out.geometry->computeLocalAABB();
  return out;
}

ParticleContactQuery::ParticleContactQuery(double radius)
    : radius_(radius), sphere_(std::make_shared<fcl::Sphere<double>>(radius)) {
  sphere_->computeLocalAABB();
}

ParticleContactQuery::~ParticleContactQuery() = default;

std::optional<ParticleContact> ParticleContactQuery::contact(const FclCollider& collider,
                                                             const Eigen::Isometry3d& shape_pose,
                                                             const Eigen::Vector3d& x) const {
  if (collider.mesh) {
    const auto near = collider.mesh->signed_nearest(shape_pose.inverse() * x, radius_);
    if (!near || !(near->distance < radius_)) return std::nullopt;
    return ParticleContact{radius_ - near->distance, shape_pose.linear() * near->normal};
  }
  fcl::Transform3d particle_pose = fcl::Transform3d::Identity();
  particle_pose.translation() = x;
  // The closed forms fcl::collide dispatches to for these pairs, called directly (docs/bullet.md,
  // "FCL queries we use").
  const auto& particle = static_cast<const fcl::Sphere<double>&>(*sphere_);
  const fcl::CollisionGeometry<double>& shape = *collider.geometry;
  // One scratch list per thread (the contact phase queries from several), cleared, capacity kept.
  thread_local std::vector<fcl::ContactPoint<double>> contacts;
  contacts.clear();
  bool touching = false;
  switch (shape.getNodeType()) {
    case fcl::GEOM_SPHERE:
      touching = fcl::detail::sphereSphereIntersect(particle, particle_pose,
                                                    static_cast<const fcl::Sphere<double>&>(shape),
                                                    shape_pose, &contacts);
      break;
    case fcl::GEOM_CAPSULE:
      touching = fcl::detail::sphereCapsuleIntersect(
          particle, particle_pose, static_cast<const fcl::Capsule<double>&>(shape), shape_pose,
          &contacts);
      break;
    case fcl::GEOM_CYLINDER:
      touching = fcl::detail::sphereCylinderIntersect(
          particle, particle_pose, static_cast<const fcl::Cylinder<double>&>(shape), shape_pose,
          &contacts);
      break;
    case fcl::GEOM_BOX:
      touching = fcl::detail::sphereBoxIntersect(particle, particle_pose,
                                                 static_cast<const fcl::Box<double>&>(shape),
                                                 shape_pose, &contacts);
      break;
    case fcl::GEOM_HALFSPACE:
      touching = fcl::detail::sphereHalfspaceIntersect(
          particle, particle_pose, static_cast<const fcl::Halfspace<double>&>(shape), shape_pose,
          &contacts);
      break;
    default:
      return std::nullopt;  // make_fcl_collider makes only the shapes above
  }
  if (!touching || contacts.empty()) return std::nullopt;
  // FCL's normal points from the first object (the particle) into the second (the collider).
  return ParticleContact{contacts.front().penetration_depth, -contacts.front().normal.normalized()};
}

double ParticleContactQuery::clearance(const FclCollider& collider,
                                       const Eigen::Isometry3d& shape_pose,
                                       const Eigen::Vector3d& x) const {
  if (collider.mesh) {
    const auto near =
        collider.mesh->nearest(shape_pose.inverse() * x, std::numeric_limits<double>::infinity());
    return near->distance - radius_;
  }
  if (const auto touching = contact(collider, shape_pose, x)) return -touching->depth;
  if (collider.geometry->getNodeType() == fcl::GEOM_HALFSPACE) {
    // FCL has no sphere-halfspace distance routine (its libccd fallback crashes: a half-space has
    // no support point), but the half-space's own signed distance is exact.
    const auto& halfspace = static_cast<const fcl::Halfspace<double>&>(*collider.geometry);
    return halfspace.signedDistance(shape_pose.inverse() * x) - radius_;
  }
  // Sphere-{sphere, capsule, cylinder, box} distances are FCL closed forms.
  fcl::Transform3d particle_pose = fcl::Transform3d::Identity();
  particle_pose.translation() = x;
  fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  fcl::distance(sphere_.get(), particle_pose, collider.geometry.get(), shape_pose, request, result);
  return result.min_distance;
}

double bounding_radius(const FclCollider& collider) {
  if (collider.mesh) return collider.mesh->vertices().colwise().norm().maxCoeff();
  const fcl::CollisionGeometry<double>& shape = *collider.geometry;
  switch (shape.getNodeType()) {
    case fcl::GEOM_SPHERE:
      return static_cast<const fcl::Sphere<double>&>(shape).radius;
    case fcl::GEOM_CAPSULE: {
      const auto& capsule = static_cast<const fcl::Capsule<double>&>(shape);
      return 0.5 * capsule.lz + capsule.radius;
    }
    case fcl::GEOM_CYLINDER: {
      const auto& cylinder = static_cast<const fcl::Cylinder<double>&>(shape);
      return std::hypot(0.5 * cylinder.lz, cylinder.radius);
    }
    case fcl::GEOM_BOX:
      return 0.5 * static_cast<const fcl::Box<double>&>(shape).side.norm();
    case fcl::GEOM_HALFSPACE:
      return std::numeric_limits<double>::infinity();
    default:
      break;
  }
  const fcl::AABBd& local = shape.aabb_local;  // any other shape: the sphere around its local box
  return 0.5 * (local.max_ - local.min_).norm() + local.center().norm();
}

Eigen::AlignedBox3d collider_bounds(const FclCollider& collider,
                                    const Eigen::Isometry3d& shape_pose, double margin) {
  const double infinity = std::numeric_limits<double>::infinity();
  if (collider.geometry->getNodeType() == fcl::GEOM_HALFSPACE)
    return Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-infinity),
                               Eigen::Vector3d::Constant(infinity));
  // The eight corners of the local box, posed: a box that holds the posed shape.
  const fcl::AABBd& local = collider.geometry->aabb_local;
  Eigen::AlignedBox3d world;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p((corner & 1) ? local.max_.x() : local.min_.x(),
                            (corner & 2) ? local.max_.y() : local.min_.y(),
                            (corner & 4) ? local.max_.z() : local.min_.z());
    world.extend(shape_pose * p);
  }
  world.min().array() -= margin;
  world.max().array() += margin;
  return world;
}

}  // namespace drapelab
