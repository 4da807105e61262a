// vbd's contacts for one step (vertex_block_descent.hpp): the collider planes under the particles,
// the colliders' edges and corners near the cloth's edges and triangles, and the couplings between
// particles, each as the arrays the sweeps read (vbd_loops.hpp).
#include <algorithm>
#include <chrono>

#include "core/contact_rows.hpp"
#include "integrators/particle_loops.hpp"
#include "integrators/vbd/vertex_block_descent.hpp"

namespace drapelab {
namespace {

void store(double* to, const Eigen::Vector3d& value) {
  to[0] = value[0];
  to[1] = value[1];
  to[2] = value[2];
}

}  // namespace

void VertexBlockDescent::find_planes(const ClothModel& model, const VbdStepInput& input,
                                     double velocity_step, const Eigen::Matrix3Xd& x,
                                     const Eigen::Matrix3Xd& v) {
  std::fill(plane_count_.begin(), plane_count_.end(), 0);
  if (!input.contacts || input.contacts->empty()) return;
  const ContactModel& contacts = *input.contacts;
  const double reach = contact_reach(input, v);              // m
  const double radius = contacts.query().radius();           // m
  const double stiffness = contacts.parameters().stiffness;  // N/m
  const ParticleContactQuery query(reach);
  const double end_time = input.t + input.h;
  const int n = model.particle_count();
  const std::int64_t blocks = (n + kernels::kPhaseBlock - 1) / kernels::kPhaseBlock;
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const Eigen::Isometry3d pose = contacts.shape_pose(c, end_time);
    const Eigen::AlignedBox3d bounds = collider_bounds(contacts.fcl_collider(c), pose, reach);
    const Collider& collider = contacts.collider(c);
    kernels::for_each_block(blocks, n >= kernels::kParallelParticles, [&](std::int64_t block) {
      const int begin = static_cast<int>(block * kernels::kPhaseBlock);
      const int end = static_cast<int>(std::min<std::int64_t>(n, begin + kernels::kPhaseBlock));
      for (int i = begin; i < end; ++i) {
        std::int32_t& count = plane_count_[static_cast<std::size_t>(i)];
        if (model.is_pinned(i) || count >= kPlaneSlots || !bounds.contains(x.col(i))) continue;
        const auto touch = query.contact(contacts.fcl_collider(c), pose, x.col(i));
        if (!touch) continue;
        const std::size_t e = static_cast<std::size_t>(i) * kPlaneSlots + count++;
        // The surface point under the particle: the query sphere reaches `depth` past it.
        const Eigen::Vector3d point = x.col(i) - (reach - touch->depth) * touch->normal;
        store(&plane_point_[3 * e], point);
        store(&plane_normal_[3 * e], touch->normal);
        store(&plane_surface_move_[3 * e],
              velocity_step * contacts.surface_velocity(c, end_time, point));
        plane_collider_[e] = static_cast<std::int32_t>(c);
        plane_kinetic_[e] = collider.friction;
        plane_fixed_[e] = std::max(collider.friction, collider.static_friction);
        // Friction's load, lagged: the spring's push at the particle's start.
        const double start_depth = radius - (reach - touch->depth);  // m
        plane_load_[e] = stiffness * std::max(0.0, start_depth);
      }
    });
  }
}

double VertexBlockDescent::contact_reach(const VbdStepInput& input, const Eigen::Matrix3Xd& v) {
  const double radius = input.contacts->query().radius();  // m
  const double fastest = v.colwise().norm().maxCoeff();    // m/s
  return radius + std::max(radius, 2.0 * fastest * input.h);
}

void VertexBlockDescent::find_features(int n, const VbdStepInput& input, double velocity_step,
                                       const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v) {
  const auto started = std::chrono::steady_clock::now();
  input.features->find_near(*input.contacts, input.t + input.h, x, contact_reach(input, v),
                            near_features_);
  stats_.feature_search_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  // The pairs come grouped by cloth primitive and collider: each group is one contact.
  FeatureArrays& a = features_;
  a.clear();
  const std::size_t count = near_features_.size();
  for (std::size_t k = 0; k < count; ++k) {
    const FeatureContact& f = near_features_[k];
    if (k == 0 || f.particle != near_features_[k - 1].particle ||
        f.collider != near_features_[k - 1].collider) {
      a.range.push_back(static_cast<std::int32_t>(k));
      a.particle.insert(a.particle.end(), f.particle.begin(), f.particle.end());
      for (int d = 0; d < 3; ++d) a.surface_move.push_back(velocity_step * f.surface_velocity[d]);
      a.kinetic.push_back(f.kinetic_friction);
      a.fixed.push_back(std::max(f.kinetic_friction, f.static_friction));
      a.collider.push_back(f.collider);
    }
    for (int d = 0; d < 3; ++d) {
      a.from.push_back(f.from[d]);
      a.to.push_back(f.to[d]);
      a.outward.push_back(f.outward[d]);
    }
    for (const Eigen::Vector3d& face : f.faces)
      a.faces.insert(a.faces.end(), face.begin(), face.end());
  }
  a.range.push_back(static_cast<std::int32_t>(count));
  const std::size_t contacts = a.collider.size();
  index_contact_rows(static_cast<std::size_t>(n), a.particle, 3, a.rows, a.row_contact, a.row_slot,
                     row_scratch_);
  // Friction's lagged load: the spring's push where the step starts.
  a.load.assign(contacts, 0.0);
  const kernels::VbdFeatures at_start = feature_view(input.contacts->query().radius(), 0.0, 0.0);
  const auto position = [&](std::int32_t j) { return x.data() + 3 * static_cast<std::int64_t>(j); };
  const double stiffness = input.contacts->parameters().stiffness;  // N/m
  for (std::size_t c = 0; c < contacts; ++c) {
    kernels::FeatureGeometry g;
    if (kernels::feature_geometry(at_start, static_cast<std::int64_t>(c), position, x.data(), g))
      a.load[c] = stiffness * std::max(0.0, g.depth);
  }
}

kernels::VbdFeatures VertexBlockDescent::feature_view(double radius, double stiffness,
                                                      double damping) const {
  const FeatureArrays& a = features_;
  return {.offsets = a.rows.data(),
          .contact = a.row_contact.data(),
          .slot = a.row_slot.data(),
          .particle = a.particle.data(),
          .feature_offsets = a.range.data(),
          .surface_move = a.surface_move.data(),
          .kinetic = a.kinetic.data(),
          .fixed = a.fixed.data(),
          .load = a.load.data(),
          .from = a.from.data(),
          .to = a.to.data(),
          .outward = a.outward.data(),
          .faces = a.faces.data(),
          .radius = radius,
          .stiffness = stiffness,
          .damping = damping};
}

void VertexBlockDescent::index_couplings(int n, const std::vector<WeightedContact>& couplings,
                                         const Eigen::Matrix3Xd& x, double h) {
  const std::size_t count = couplings.size();
  coupling_particle_.resize(4 * count);
  coupling_weight_.resize(4 * count);
  coupling_normal_.resize(3 * count);
  coupling_depth_.resize(count);
  coupling_stiffness_.resize(count);
  coupling_damping_.resize(count);
  coupling_end_rate_.resize(count);
  coupling_two_sided_.resize(count);
  for (std::size_t c = 0; c < count; ++c) {
    const WeightedContact& w = couplings[c];
    for (int s = 0; s < 4; ++s) {
      coupling_particle_[4 * c + s] = w.particle[s];
      coupling_weight_[4 * c + s] = w.weight[s];
    }
    store(&coupling_normal_[3 * c], w.normal);
    // The depth is linearised at x(n); the sweeps measure displacements from start_ (X).
    double shift = 0.0;  // m: n . sum_j w_j (X_j - x_j(n))
    for (int s = 0; s < 4; ++s)
      if (w.particle[s] >= 0)
        shift += w.weight[s] * w.normal.dot(start_.col(w.particle[s]) - x.col(w.particle[s]));
    // The far end's own motion over the step deepens it (a moving collider point).
    coupling_depth_[c] = w.depth - shift + h * w.end_rate;
    coupling_end_rate_[c] = w.end_rate;
    coupling_stiffness_[c] = w.stiffness;
    coupling_damping_[c] = w.damping;
    coupling_two_sided_[c] = w.two_sided ? 1 : 0;
  }
  index_contact_rows(static_cast<std::size_t>(n), coupling_particle_, 4, coupling_offsets_,
                     coupling_contact_, coupling_slot_, row_scratch_);
}

}  // namespace drapelab
