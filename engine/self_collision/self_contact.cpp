// Self-collision's broad phase, narrow phase and forces (self_contact.hpp).
#include "self_collision/self_contact.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/pair_penalty.hpp"
#include "core/proximity.hpp"

namespace drapelab {
namespace {

Eigen::Vector3d unit_or_up(const Eigen::Vector3d& v) {
  const double length = v.norm();
  return length > 0.0 ? Eigen::Vector3d(v / length) : Eigen::Vector3d::UnitY();
}

// The self contacts' rules in the shared pass (weighted_contact_pass.hpp): both sides are the
// cloth's; a push needs an overlap (pair_penalty.hpp), and its power and friction are counted as
// at the particle contacts.
constexpr WeightedContactRules kSelfContactRules{.against_surface = false,
                                                 .skip_pinned = false,
                                                 .push_needs_overlap = true,
                                                 .power_of_clamped_push = true,
                                                 .friction_needs_static = true};

}  // namespace

SelfContact::SelfContact(const ClothModel& model, const SelfCollisionSettings& settings)
    : model_(model),
      settings_(settings),
      thickness_(settings.thickness_or(model.thickness)),
      margin_(2.0 * thickness_),
      topology_(model) {
  pass_ = WeightedContactPass(model.particle_count());
}

bool SelfContact::needs_search(const Eigen::Matrix3Xd& x) const {
  if (!searched_) return true;
  const Eigen::Vector3d mean_motion = (x - searched_x_).rowwise().mean();  // m
  const double limit = 0.25 * margin_ * margin_;                           // (margin / 2)^2
  for (int i = 0; i < x.cols(); ++i)
    if ((x.col(i) - searched_x_.col(i) - mean_motion).squaredNorm() > limit) return true;
  return false;
}

void SelfContact::search(const Eigen::Matrix3Xd& x) {
  const double reach = thickness_ + margin_;  // m
  const double reach2 = reach * reach;
  const auto& tri = model_.triangles;
  point_triangle_.clear();
  edge_edge_.clear();

  boxes_.resize(static_cast<std::size_t>(tri.cols()));
  for (int t = 0; t < tri.cols(); ++t)
    boxes_[t] = box_of({x.col(tri(0, t)), x.col(tri(1, t)), x.col(tri(2, t))}, reach);
  grid_.build(boxes_, cell_size_for(boxes_, reach));
  for (int p = 0; p < x.cols(); ++p) {
    const Eigen::Vector3d point = x.col(p);
    for (const std::int32_t t : grid_.items_near(point)) {
      if (tri(0, t) == p || tri(1, t) == p || tri(2, t) == p) continue;
      if (!boxes_[t].contains(point)) continue;
      const PointTriangleProximity near =
          closest_point_on_triangle(point, x.col(tri(0, t)), x.col(tri(1, t)), x.col(tri(2, t)));
      if ((point - near.closest).squaredNorm() < reach2) point_triangle_.push_back({p, t});
    }
  }

  const auto& edges = topology_.edges();
  boxes_.resize(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e)
    boxes_[e] = box_of({x.col(edges[e][0]), x.col(edges[e][1])}, 0.5 * reach);
  grid_.build(boxes_, cell_size_for(boxes_, reach));
  grid_.for_each_overlapping_pair([&](std::int32_t a, std::int32_t b) {
    const auto& ea = edges[a];
    const auto& eb = edges[b];
    if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) return;
    const SegmentProximity near =
        closest_points_of_segments(x.col(ea[0]), x.col(ea[1]), x.col(eb[0]), x.col(eb[1]));
    if ((near.on_first - near.on_second).squaredNorm() < reach2) edge_edge_.push_back({a, b});
  });
  searched_x_ = x;
  searched_ = true;
  ++stats_.rebuilds;
  stats_.candidates = static_cast<std::int64_t>(point_triangle_.size() + edge_edge_.size());
}

void SelfContact::find_contacts(const Eigen::Matrix3Xd& x) {
  const double thickness2 = thickness_ * thickness_;
  const auto& tri = model_.triangles;
  contacts_.clear();
  shared_.clear();
  for (const auto& [p, t] : point_triangle_) {
    const int corner[3] = {tri(0, t), tri(1, t), tri(2, t)};
    const Eigen::Vector3d a = x.col(corner[0]), b = x.col(corner[1]), c = x.col(corner[2]);
    const PointTriangleProximity near = closest_point_on_triangle(x.col(p), a, b, c);
    if ((x.col(p) - near.closest).squaredNorm() >= thickness2) continue;
    if (near.region == TriangleRegion::face) {
      WeightedContactPoint contact;
      contact.particle = {p, corner[0], corner[1], corner[2]};
      contact.weight = {1.0, -near.weights[0], -near.weights[1], -near.weights[2]};
      contact.normal = unit_or_up((b - a).cross(c - a));  // where the sides meet
      contacts_.push_back(contact);
    } else if (near.region == TriangleRegion::edge) {
      const int i = corner[(near.feature + 1) % 3], j = corner[(near.feature + 2) % 3];
      if (topology_.nearest_edge_everywhere(x, p, std::min(i, j), std::max(i, j)))
        shared_.push_back({p, std::min(i, j), std::max(i, j)});
    } else {
      const int q = corner[near.feature];
      if (!topology_.adjacent(p, q) && topology_.nearest_corner_everywhere(x, p, q))
        shared_.push_back({std::min(p, q), std::max(p, q), -1});
    }
  }
  const auto& edges = topology_.edges();
  for (const auto& [ea, eb] : edge_edge_) {
    const auto& e = edges[ea];
    const auto& f = edges[eb];
    const SegmentProximity near =
        closest_points_of_segments(x.col(e[0]), x.col(e[1]), x.col(f[0]), x.col(f[1]));
    // Nearest at an end: that end's particle-triangle test has the contact already.
    if (!(near.s > 0.0 && near.s < 1.0 && near.t > 0.0 && near.t < 1.0)) continue;
    if ((near.on_first - near.on_second).squaredNorm() >= thickness2) continue;
    WeightedContactPoint contact;
    contact.particle = {e[0], e[1], f[0], f[1]};
    contact.weight = {1.0 - near.s, near.s, -(1.0 - near.t), -near.t};
    contact.normal = unit_or_up((x.col(e[1]) - x.col(e[0])).cross(x.col(f[1]) - x.col(f[0])));
    contacts_.push_back(contact);
  }
  std::sort(shared_.begin(), shared_.end());
  shared_.erase(std::unique(shared_.begin(), shared_.end()), shared_.end());
  for (const SharedFeature& s : shared_) {
    WeightedContactPoint contact;
    if (s.c < 0) {
      contact.particle = {s.a, s.b, -1, -1};
      contact.weight = {1.0, -1.0, 0.0, 0.0};
    } else {
      const Eigen::Vector3d from = x.col(s.b), along = x.col(s.c) - from;
      const double length2 = along.squaredNorm();
      const double t =
          length2 > 0.0 ? std::clamp((x.col(s.a) - from).dot(along) / length2, 0.0, 1.0) : 0.0;
      contact.particle = {s.a, s.b, s.c, -1};
      contact.weight = {1.0, -(1.0 - t), -t, 0.0};
    }
    contacts_.push_back(contact);
  }
  // Each contact's line between its two sides, r = sum_j w_j x_j (m): its normal and depth.
  const double kinetic = settings_.friction, fixed = settings_.static_friction_or_kinetic();
  for (WeightedContactPoint& contact : contacts_) {
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (int s = 0; s < 4; ++s)
      if (contact.particle[s] >= 0) r += contact.weight[s] * x.col(contact.particle[s]);
    const PairPenalty apart = pair_separation(r, contact.normal);
    contact.normal = apart.normal;
    contact.depth = thickness_ - apart.distance;
    contact.static_friction = fixed;
    contact.kinetic_friction = kinetic;
  }
}

void SelfContact::add_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, double h,
                             const Eigen::VectorXd& inverse_mass, Eigen::Matrix3Xd& force,
                             std::vector<WeightedContact>* active) {
  ++stats_.evaluations;
  if (needs_search(x)) search(x);
  find_contacts(x);
  pass_.run(contacts_, kSelfContactRules, settings_.stiffness, settings_.damping, h, v,
            inverse_mass, force, active, totals_);
  const WeightedContactTotals& total = totals_.front();
  stats_.contacts_last = total.pushing;
  stats_.contacts_total += total.pushing;
  stats_.normal_force_last = total.normal_force;
  stats_.friction_force_last = total.friction_force;
  stats_.spring_energy_last = total.spring_energy;
  stats_.dissipated_power_last = total.power.dissipated;
}

}  // namespace drapelab
