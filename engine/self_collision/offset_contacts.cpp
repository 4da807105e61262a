// Offset self-contacts' detection and conservative bounds (offset_contacts.hpp).
#include "self_collision/offset_contacts.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include "core/contact_rows.hpp"
#include "core/proximity.hpp"
#include "core/thread_blocks.hpp"

namespace drapelab {
namespace {

// Particles per detection block; a block's work is a few dozen closest-point tests per particle,
// so threads pay off well below the particle passes' kParallelParticles.
constexpr std::int64_t kDetectionBlock = 128;
constexpr std::int64_t kParallelDetection = 1024;

// target = min(target, value), safe against other threads doing the same. A minimum does not
// depend on the order the values come in.
void lower_to(double& target, double value) {
  std::atomic_ref<double> shared(target);
  double seen = shared.load(std::memory_order_relaxed);
  while (value < seen && !shared.compare_exchange_weak(seen, value, std::memory_order_relaxed)) {
  }
}

double mean_rest_edge(const ClothModel& model, const std::vector<std::array<std::int32_t, 2>>& e) {
  double sum = 0.0;
  for (const auto& [a, b] : e)
    sum += (model.rest_positions.col(a) - model.rest_positions.col(b)).norm();
  return e.empty() ? 0.0 : sum / static_cast<double>(e.size());
}

}  // namespace

OffsetContacts::OffsetContacts(const ClothModel& model, const SelfCollisionSettings& settings)
    : settings_(settings),
      barrier_{settings.thickness_or(model.thickness), settings.stiffness},
      topology_(model) {
  // The reach: far enough that a flat sheet's bound is set by its own neighbours, and at least
  // twice the offset. On a square grid of spacing s a particle lies 0.707 s from the far edge of a
  // neighbouring triangle, and the mean edge (sides and diagonals) is 1.14 s: 0.75 of it is 0.85 s.
  // Each search looks this far round every primitive, so its cost grows as its cube: 0.75 of the
  // mean edge took 24 ms where the whole mean edge took 37 on a folded 65 x 65 sheet, one thread.
  reach_ = std::max(2.0 * barrier_.offset, 0.75 * mean_rest_edge(model, topology_.edges()));
  const int n = model.particle_count();
  nearest_.assign(static_cast<std::size_t>(n), reach_);
  bound_.assign(static_cast<std::size_t>(n), 0.0);
  anchor_ = model.rest_positions;
  row_offsets_.assign(static_cast<std::size_t>(n) + 1, 0);
}

void OffsetContacts::find_point_triangle(const Eigen::Matrix3Xd& x) {
  const Eigen::Matrix3Xi& tri = topology_.triangles();
  const double reach2 = reach_ * reach_, offset = barrier_.offset;
  boxes_.resize(static_cast<std::size_t>(tri.cols()));
  for (int t = 0; t < tri.cols(); ++t)
    boxes_[t] = box_of({x.col(tri(0, t)), x.col(tri(1, t)), x.col(tri(2, t))}, reach_);
  grid_.build(boxes_, cell_size_for(boxes_, reach_));
  const std::int64_t n = x.cols();
  const std::int64_t blocks = (n + kDetectionBlock - 1) / kDetectionBlock;
  block_found_.resize(static_cast<std::size_t>(blocks));
  block_shared_.resize(static_cast<std::size_t>(blocks));
  kernels::for_each_block_balanced(blocks, n >= kParallelDetection, [&](std::int64_t block) {
    std::vector<Found>& found = block_found_[static_cast<std::size_t>(block)];
    std::vector<Found>& shared = block_shared_[static_cast<std::size_t>(block)];
    found.clear();
    shared.clear();
    const std::int64_t end = std::min(n, (block + 1) * kDetectionBlock);
    for (std::int64_t pi = block * kDetectionBlock; pi < end; ++pi) {
      const int p = static_cast<int>(pi);
      const Eigen::Vector3d point = x.col(p);
      grid_.for_each_item_containing(point, [&](std::int32_t t) {
        if (topology_.is_corner(p, t)) return;
        const int corner[3] = {tri(0, t), tri(1, t), tri(2, t)};
        const PointTriangleProximity near =
            closest_point_on_triangle(point, x.col(corner[0]), x.col(corner[1]), x.col(corner[2]));
        const double d2 = (point - near.closest).squaredNorm();
        if (d2 >= reach2) return;
        const double d = std::sqrt(d2);
        lower_to(nearest_[p], d);
        for (const int c : corner) lower_to(nearest_[c], d);
        if (d >= offset) return;
        // Admitted only in the feasible region of the feature the closest point lies on.
        if (near.region == TriangleRegion::face) {
          found.push_back({SelfContactKind::point_face, {p, corner[0], corner[1], corner[2]}, d});
        } else if (near.region == TriangleRegion::edge) {
          const int i = corner[(near.feature + 1) % 3], j = corner[(near.feature + 2) % 3];
          const int a = std::min(i, j), b = std::max(i, j);
          if (topology_.nearest_edge_everywhere(x, p, a, b))
            shared.push_back({SelfContactKind::point_edge, {p, a, b, -1}, d});
        } else {
          const int q = corner[near.feature];
          if (!topology_.adjacent(p, q) && topology_.nearest_corner_everywhere(x, p, q))
            shared.push_back(
                {SelfContactKind::point_point, {std::min(p, q), std::max(p, q), -1, -1}, d});
        }
      });
    }
  });
}

void OffsetContacts::find_edge_edge(const Eigen::Matrix3Xd& x) {
  const auto& edges = topology_.edges();
  const double offset = barrier_.offset;
  const std::int64_t count = static_cast<std::int64_t>(edges.size());
  boxes_.resize(edges.size());
  edge_reach_.resize(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    boxes_[e] = box_of({x.col(edges[e][0]), x.col(edges[e][1])}, 0.0);
    // An edge pair matters to a particle's bound only when nearer than what the particle-triangle
    // pairs found for it, and to the contacts only within the offset: each edge looks that far
    // (taken before the search, so every thread reads the same reach).
    edge_reach_[e] = std::max(offset, std::max(nearest_[static_cast<std::size_t>(edges[e][0])],
                                               nearest_[static_cast<std::size_t>(edges[e][1])]));
  }
  // Cells as large as a query (an edge's box and the reach on each side), so that a query covers
  // at most two cells along each axis: scanning the entries of the cells a query covers was most
  // of the detection's time. On the 65 x 65 heap (vbd, 0.5 s) cells of the mean edge's box alone
  // took 1.68 to 1.80 s of self-contact, these 1.36 to 1.45 s.
  grid_.build(boxes_, cell_size_for(boxes_, offset) + 2.0 * reach_);
  const std::int64_t blocks = (count + kDetectionBlock - 1) / kDetectionBlock;
  block_edge_found_.resize(static_cast<std::size_t>(blocks));
  kernels::for_each_block_balanced(blocks, count >= kParallelDetection, [&](std::int64_t block) {
    std::vector<Found>& found = block_edge_found_[static_cast<std::size_t>(block)];
    found.clear();
    const std::int64_t end = std::min(count, (block + 1) * kDetectionBlock);
    for (std::int64_t ea = block * kDetectionBlock; ea < end; ++ea) {
      const auto& e = edges[static_cast<std::size_t>(ea)];
      const double reach = edge_reach_[static_cast<std::size_t>(ea)];
      Box query = boxes_[static_cast<std::size_t>(ea)];
      query.min.array() -= reach;
      query.max.array() += reach;
      grid_.for_each_item_overlapping(query, [&](std::int32_t eb) {
        if (eb == ea) return;
        // Each pair once, from the edge that looks farther (the lower index of two that look as
        // far): its reach is the pair's, and the other edge's search skips it before the
        // closest points.
        const double other_reach = edge_reach_[static_cast<std::size_t>(eb)];
        if (other_reach > reach || (other_reach == reach && eb < ea)) return;
        const auto& f = edges[static_cast<std::size_t>(eb)];
        if (e[0] == f[0] || e[0] == f[1] || e[1] == f[0] || e[1] == f[1]) return;
        // The lower edge first, whichever edge searches: the same bits either way.
        const auto& low = ea < eb ? e : f;
        const auto& high = ea < eb ? f : e;
        const SegmentProximity near = closest_points_of_segments(x.col(low[0]), x.col(low[1]),
                                                                 x.col(high[0]), x.col(high[1]));
        const double d = (near.on_first - near.on_second).norm();
        if (d >= reach) return;
        for (const int p : {e[0], e[1], f[0], f[1]}) lower_to(nearest_[p], d);
        // Nearest at an end: that end's particle-triangle test holds the contact.
        if (d >= offset || !(near.s > 0.0 && near.s < 1.0 && near.t > 0.0 && near.t < 1.0)) return;
        found.push_back({SelfContactKind::edge_edge, {low[0], low[1], high[0], high[1]}, d});
      });
    }
  });
}

void OffsetContacts::detect(const Eigen::Matrix3Xd& x, const Eigen::Vector3d& shift) {
  const auto started = std::chrono::steady_clock::now();
  std::fill(nearest_.begin(), nearest_.end(), reach_);
  find_point_triangle(x);
  find_edge_edge(x);
  store_contacts();
  for (std::size_t i = 0; i < bound_.size(); ++i)
    bound_[i] = kConservativeBoundFraction * nearest_[i];
  recentre(x, shift);
  ++stats_.rebuilds;
  stats_.candidates = contact_count();
  detection_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

void OffsetContacts::recentre(const Eigen::Matrix3Xd& x, const Eigen::Vector3d& shift) {
  anchor_ = x.colwise() + shift;
}

void OffsetContacts::store_contacts() {
  // Edges and corners found from several triangles, once each (the nearest of equal keys first).
  shared_.clear();
  for (const std::vector<Found>& block : block_shared_)
    shared_.insert(shared_.end(), block.begin(), block.end());
  std::sort(shared_.begin(), shared_.end());
  shared_.erase(std::unique(shared_.begin(), shared_.end(),
                            [](const Found& a, const Found& b) {
                              return a.kind == b.kind && a.particle == b.particle;
                            }),
                shared_.end());
  kind_.clear();
  particle_.clear();
  normal_force_.clear();
  const auto add = [&](const Found& f) {
    kind_.push_back(f.kind);
    particle_.insert(particle_.end(), f.particle.begin(), f.particle.end());
    normal_force_.push_back(-barrier_.slope(f.distance));
  };
  for (const std::vector<Found>& block : block_found_)
    for (const Found& f : block) add(f);
  for (const std::vector<Found>& block : block_edge_found_)
    for (const Found& f : block) add(f);
  for (const Found& f : shared_) add(f);
  index_contact_rows(nearest_.size(), particle_, 4, row_offsets_, row_contact_, row_slot_, fill_);
}

OffsetContactArrays OffsetContacts::arrays() const {
  OffsetContactArrays a;
  a.count = contact_count();
  a.offsets = row_offsets_.data();
  a.contact = row_contact_.data();
  a.slot = row_slot_.data();
  a.kind = kind_.data();
  a.particle = particle_.data();
  a.normal_force = normal_force_.data();
  a.offset = barrier_.offset;
  a.stiffness = barrier_.stiffness;
  a.damping = settings_.damping;
  a.kinetic_friction = settings_.friction;
  a.static_friction = settings_.static_friction_or_kinetic();
  a.anchor = anchor_.data();
  a.bound = bound_.data();
  return a;
}

void OffsetContacts::record_end_state(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& start,
                                      double h, double friction_velocity) {
  totals_ = offset_contact_totals(arrays(), x.data(), start.data(), h, friction_velocity);
  ++stats_.evaluations;
  stats_.contacts_last = totals_.pushing;
  stats_.contacts_total += totals_.pushing;
  stats_.normal_force_last = totals_.normal_force;
  stats_.friction_force_last = totals_.friction_force;
  stats_.spring_energy_last = totals_.energy;
  stats_.dissipated_power_last = totals_.dissipated_power;
}

}  // namespace drapelab
