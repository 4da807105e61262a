// Collider edges and corners against the cloth's edges and triangles (edge_contact.hpp).
#include "contact/edge_contact.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "cloth/mesh_edges.hpp"
#include "core/feature_push.hpp"
#include "core/proximity.hpp"

namespace drapelab {
namespace {

// Fewest and most chords per cylinder rim.
constexpr int kFewestChords = 16;
constexpr int kMostChords = 1024;

ColliderFeatures box_features(const Eigen::Vector3d& half) {
  ColliderFeatures features;
  features.shape = ColliderShape::box;
  features.half_extents = half;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d sign((corner & 1) ? 1.0 : -1.0, (corner & 2) ? 1.0 : -1.0,
                               (corner & 4) ? 1.0 : -1.0);
    const ColliderFeatures::Faces corner_faces{Eigen::Vector3d(sign.x(), 0.0, 0.0),
                                               Eigen::Vector3d(0.0, sign.y(), 0.0),
                                               Eigen::Vector3d(0.0, 0.0, sign.z())};
    features.corners.push_back({sign.cwiseProduct(half), sign.normalized(), corner_faces});
    // The edges from this corner towards +x, +y, +z, each found once (from its lower end).
    for (int axis = 0; axis < 3; ++axis) {
      if (sign[axis] > 0.0) continue;
      Eigen::Vector3d other = sign;
      other[axis] = 1.0;
      Eigen::Vector3d outward = sign;
      outward[axis] = 0.0;
      const Eigen::Vector3d& first = corner_faces[(axis + 1) % 3];
      features.edges.push_back({sign.cwiseProduct(half),
                                other.cwiseProduct(half),
                                outward.normalized(),
                                {first, corner_faces[(axis + 2) % 3], first}});
    }
  }
  return features;
}

ColliderFeatures cylinder_features(const Eigen::Vector3d& axis, double radius, double height,
                                   double thickness) {
  ColliderFeatures features;
  const Eigen::Vector3d a = axis.normalized();
  const Eigen::Vector3d u = a.unitOrthogonal(), w = a.cross(u);
  features.shape = ColliderShape::cylinder;
  features.rim_frame << u, w, a;
  features.radius = radius;
  features.half_height = 0.5 * height;
  // Chords of sag radius (1 - cos(pi / count)) <= thickness / 8.
  const double half_angle = std::acos(std::max(-1.0, 1.0 - thickness / (8.0 * radius)));
  const double wanted = half_angle > 0.0 ? std::ceil(std::numbers::pi / half_angle) : kMostChords;
  const int count =
      static_cast<int>(std::clamp(wanted, double{kFewestChords}, double{kMostChords}));
  features.chords = count;
  for (const double side : {-1.0, 1.0}) {
    const Eigen::Vector3d rim_center = side * 0.5 * height * a;
    for (int k = 0; k < count; ++k) {
      const double from = 2.0 * std::numbers::pi * k / count;
      const double to = 2.0 * std::numbers::pi * (k + 1) / count;
      const double middle = 0.5 * (from + to);
      const Eigen::Vector3d radial = std::cos(middle) * u + std::sin(middle) * w;
      const Eigen::Vector3d cap = side * a;
      features.edges.push_back({rim_center + radius * (std::cos(from) * u + std::sin(from) * w),
                                rim_center + radius * (std::cos(to) * u + std::sin(to) * w),
                                (radial + cap).normalized(),
                                {cap, radial, cap}});
    }
  }
  return features;
}

ColliderFeatures::Faces posed(const Eigen::Isometry3d& pose, const ColliderFeatures::Faces& faces) {
  return {pose.linear() * faces[0], pose.linear() * faces[1], pose.linear() * faces[2]};
}

Eigen::AlignedBox3d segment_box(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  Eigen::AlignedBox3d box(a);
  box.extend(b);
  return box;
}

// The collider edges' rules in the shared pass (weighted_contact_pass.hpp): the other side is the
// collider's moving surface; a contact whose particles are all pinned takes no push, a push's
// power counts only while it pushes, and friction acts whatever the static coefficient.
constexpr WeightedContactRules kColliderEdgeRules{.against_surface = true,
                                                  .skip_pinned = true,
                                                  .push_needs_overlap = false,
                                                  .power_of_clamped_push = false,
                                                  .friction_needs_static = false};

}  // namespace

ColliderFeatures collider_features(const Collider& collider, const FclCollider& shape,
                                   double thickness) {
  switch (collider.shape) {
    case ColliderShape::box:
      return box_features(collider.half_extents);
    case ColliderShape::cylinder:
      return cylinder_features(collider.axis, collider.radius, collider.height, thickness);
    case ColliderShape::mesh:
      return shape.mesh ? mesh_features(*shape.mesh) : ColliderFeatures{};
    default:
      return {};
  }
}

EdgeContact::EdgeContact(const ClothModel& model, const ContactModel& contacts)
    : model_(model), thickness_(model.thickness), pass_(model.particle_count()) {
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    features_.push_back(
        collider_features(contacts.collider(c), contacts.fcl_collider(c), thickness_));
    active_ = active_ || !features_.back().empty();
  }
  if (active_) edges_ = mesh_edges(model.triangles);
  pass_totals_.resize(contacts.size());
  totals_.resize(contacts.size());
}

void EdgeContact::add_load(EdgeContactTotals& total, const WeightedContactPoint& f,
                           const Eigen::Matrix3Xd& x, const Eigen::Vector3d& on_cloth) {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // m
  double weights = 0.0;
  for (int s = 0; s < 4; ++s)
    if (f.particle[s] >= 0) {
      point += f.weight[s] * x.col(f.particle[s]);
      weights += f.weight[s];
    }
  if (weights != 0.0) point /= weights;
  total.force -= on_cloth;
  total.torque -= point.cross(on_cloth);
}

void EdgeContact::add_forces(const ContactModel& contacts, double t, double h,
                             const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                             const Eigen::VectorXd& inverse_mass, Eigen::Matrix3Xd& force,
                             std::vector<WeightedContact>* active) {
  std::fill(totals_.begin(), totals_.end(), EdgeContactTotals{});
  if (!active_) return;
  find_contacts(contacts, t, x);
  push_and_rub(contacts, h, x, v, inverse_mass, force, active);
}

double EdgeContact::stored_energy(const ContactModel& contacts, double t,
                                  const Eigen::Matrix3Xd& x) {
  if (!active_) return 0.0;
  find_contacts(contacts, t, x);
  const double k = contacts.parameters().stiffness;  // N/m
  double energy = 0.0;                               // J
  for (const WeightedContactPoint& f : found_) energy += 0.5 * k * f.depth * f.depth;
  return energy;
}

Eigen::AlignedBox3d EdgeContact::pose_features(std::size_t c, const Eigen::Isometry3d& pose,
                                               double reach) {
  const ColliderFeatures& local = features_[c];
  posed_edges_.clear();
  Eigen::AlignedBox3d box;
  for (const auto& e : local.edges) {
    posed_edges_.push_back(
        {pose * e.from, pose * e.to, pose.linear() * e.outward, posed(pose, e.faces)});
    box.extend(posed_edges_.back().from);
    box.extend(posed_edges_.back().to);
  }
  posed_corners_.clear();
  for (const auto& k : local.corners) {
    posed_corners_.push_back({pose * k.at, pose.linear() * k.outward, posed(pose, k.faces)});
    box.extend(posed_corners_.back().at);
  }
  box.min().array() -= reach;
  box.max().array() += reach;
  return box;
}

void EdgeContact::find_near(const ContactModel& contacts, double t, const Eigen::Matrix3Xd& x,
                            double reach_distance, std::vector<FeatureContact>& near) {
  near.clear();
  if (!active_) return;
  const double reach2 = reach_distance * reach_distance;
  for (std::size_t c = 0; c < features_.size(); ++c) {
    const ColliderFeatures& local = features_[c];
    if (local.empty()) continue;
    const Collider& collider = contacts.collider(c);
    const Eigen::Isometry3d pose = contacts.pose(c, t);
    const Eigen::Isometry3d to_local = pose.inverse();
    const Eigen::AlignedBox3d reach = pose_features(c, pose, reach_distance);
    const auto add = [&](std::array<std::int32_t, 3> particle, const ColliderFeatures::Edge& e,
                         const Eigen::Vector3d& at) {
      near.push_back({particle, e.from, e.to, e.outward, e.faces,
                      contacts.surface_velocity(c, t, at), collider.static_friction,
                      collider.friction, static_cast<int>(c)});
    };
    // Every collider edge within the reach of a cloth edge, wherever their closest points lie
    // now: the sweeps pick the nearest as the cloth slides along the collider.
    for (const auto& edge : edges_) {
      const int a = edge[0], b = edge[1];
      if (!segment_box(x.col(a), x.col(b)).intersects(reach)) continue;
      local.candidate_edges(to_local * x.col(a), to_local * x.col(b), reach_distance,
                            [&](std::size_t index) {
                              const auto& e = posed_edges_[index];
                              const SegmentProximity pair =
                                  closest_points_of_segments(x.col(a), x.col(b), e.from, e.to);
                              if ((pair.on_first - pair.on_second).squaredNorm() < reach2)
                                add({a, b, -1}, e, pair.on_second);
                            });
    }
    for (Eigen::Index tri = 0; tri < model_.triangles.cols(); ++tri) {
      const int i = model_.triangles(0, tri), j = model_.triangles(1, tri),
                k = model_.triangles(2, tri);
      Eigen::AlignedBox3d span = segment_box(x.col(i), x.col(j));
      span.extend(x.col(k));
      if (posed_corners_.empty() || !span.intersects(reach)) continue;
      for (const auto& corner : posed_corners_) {
        if (span.exteriorDistance(corner.at) >= reach_distance) continue;
        const PointTriangleProximity point =
            closest_point_on_triangle(corner.at, x.col(i), x.col(j), x.col(k));
        if ((point.closest - corner.at).squaredNorm() < reach2)
          add({i, j, k}, {corner.at, corner.at, corner.outward, corner.faces}, corner.at);
      }
    }
  }
}

void EdgeContact::find_contacts(const ContactModel& contacts, double t, const Eigen::Matrix3Xd& x) {
  found_.clear();
  const double h2 = thickness_ * thickness_;
  // Where a cloth point at `cloth` touches a collider feature at `feature`: the push direction and
  // depth by feature_push's law, or nothing.
  auto touch = [&](const Eigen::Vector3d& cloth, const Eigen::Vector3d& feature,
                   const Eigen::Vector3d& outward, const ColliderFeatures::Faces& faces,
                   WeightedContactPoint& into) {
    const Eigen::Vector3d r = cloth - feature;
    if (r.squaredNorm() >= h2) return false;
    const double normals[9] = {faces[0].x(), faces[0].y(), faces[0].z(), faces[1].x(), faces[1].y(),
                               faces[1].z(), faces[2].x(), faces[2].y(), faces[2].z()};
    return feature_push::push(r.data(), outward.data(), normals, thickness_, into.normal.data(),
                              into.depth);
  };
  for (std::size_t c = 0; c < features_.size(); ++c) {
    const ColliderFeatures& local = features_[c];
    if (local.empty()) continue;
    const Collider& collider = contacts.collider(c);
    // Keeps the nearest contact found, if any, with its collider's friction.
    const auto keep = [&](WeightedContactPoint& best) {
      if (best.particle[0] < 0) return;
      best.static_friction = collider.static_friction;
      best.kinetic_friction = collider.friction;
      found_.push_back(best);
    };
    const Eigen::Isometry3d pose = contacts.pose(c, t);
    const Eigen::Isometry3d to_local = pose.inverse();
    const Eigen::AlignedBox3d reach = pose_features(c, pose, thickness_);
    // Collider edges against cloth edges: the nearest collider edge, if it is nearest to the
    // inside of the cloth edge (at an end, the particle contact has it).
    for (const auto& edge : edges_) {
      const int a = edge[0], b = edge[1];  // named, not bound: lambdas capture them below
      if (!segment_box(x.col(a), x.col(b)).intersects(reach)) continue;
      WeightedContactPoint best;
      double best_distance2 = h2;
      local.candidate_edges(
          to_local * x.col(a), to_local * x.col(b), thickness_, [&](std::size_t index) {
            const auto& e = posed_edges_[index];
            const SegmentProximity near =
                closest_points_of_segments(x.col(a), x.col(b), e.from, e.to);
            // Nearest at a cloth edge's end: the particle contact has it; at a collider edge's
            // end: the corner (or the next chord) has it, and the edge's two faces alone do not
            // say which side of the collider the point is on.
            if (!(near.s > 0.0 && near.s < 1.0 && near.t > 0.0 && near.t < 1.0)) return;
            const double d2 = (near.on_first - near.on_second).squaredNorm();
            if (d2 >= best_distance2) return;
            WeightedContactPoint candidate;
            if (!touch(near.on_first, near.on_second, e.outward, e.faces, candidate)) return;
            candidate.particle = {a, b, -1, -1};
            candidate.weight = {1.0 - near.s, near.s, 0.0, 0.0};
            candidate.surface_velocity = contacts.surface_velocity(c, t, near.on_second);
            candidate.group = static_cast<int>(c);
            best = candidate;
            best_distance2 = d2;
          });
      keep(best);
    }
    // Collider corners against the inside of cloth triangles.
    if (posed_corners_.empty()) continue;
    for (Eigen::Index tri = 0; tri < model_.triangles.cols(); ++tri) {
      const int i = model_.triangles(0, tri), j = model_.triangles(1, tri),
                k = model_.triangles(2, tri);
      Eigen::AlignedBox3d span = segment_box(x.col(i), x.col(j));
      span.extend(x.col(k));
      if (!span.intersects(reach)) continue;
      WeightedContactPoint best;
      double best_distance2 = h2;
      for (const auto& corner : posed_corners_) {
        if (span.exteriorDistance(corner.at) >= thickness_) continue;
        const PointTriangleProximity near =
            closest_point_on_triangle(corner.at, x.col(i), x.col(j), x.col(k));
        if (near.region != TriangleRegion::face) continue;
        const double d2 = (near.closest - corner.at).squaredNorm();
        if (d2 >= best_distance2) continue;
        WeightedContactPoint candidate;
        if (!touch(near.closest, corner.at, corner.outward, corner.faces, candidate)) continue;
        candidate.particle = {i, j, k, -1};
        candidate.weight = {near.weights[0], near.weights[1], near.weights[2], 0.0};
        candidate.surface_velocity = contacts.surface_velocity(c, t, corner.at);
        candidate.group = static_cast<int>(c);
        best = candidate;
        best_distance2 = d2;
      }
      keep(best);
    }
  }
}

void EdgeContact::push_and_rub(const ContactModel& contacts, double h, const Eigen::Matrix3Xd& x,
                               const Eigen::Matrix3Xd& v, const Eigen::VectorXd& inverse_mass,
                               Eigen::Matrix3Xd& force, std::vector<WeightedContact>* active) {
  const ContactParameters& p = contacts.parameters();
  pass_.run(found_, kColliderEdgeRules, p.stiffness, p.damping, h, v, inverse_mass, force, active,
            pass_totals_);
  for (std::size_t c = 0; c < totals_.size(); ++c) {
    const WeightedContactTotals& sum = pass_totals_[c];
    EdgeContactTotals& total = totals_[c];
    total.contact_count = static_cast<int>(sum.pushing);
    total.normal_force = sum.normal_force;
    total.friction_force = sum.friction_force;
    total.power = sum.power;
  }
  // The collider's load: every push, then every friction, as the pass applied them.
  const std::vector<WeightedContactOutcome>& outcome = pass_.outcomes();
  for (std::size_t e = 0; e < found_.size(); ++e) {
    if (outcome[e].push <= 0.0) continue;
    const WeightedContactPoint& f = found_[e];
    EdgeContactTotals& total = totals_[static_cast<std::size_t>(f.group)];
    total.max_depth = std::max(total.max_depth, f.depth);
    add_load(total, f, x, outcome[e].push * f.normal);
  }
  for (std::size_t e = 0; e < found_.size(); ++e)
    if (outcome[e].rubbed)
      add_load(totals_[static_cast<std::size_t>(found_[e].group)], found_[e], x,
               outcome[e].friction);
}

}  // namespace drapelab
