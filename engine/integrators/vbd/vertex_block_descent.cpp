// Vertex block descent's step driver (vertex_block_descent.hpp): the particles' spring lists and
// contact slots, built once; per step the collider contact planes, the contacts between particles,
// the inertial target, the initial guess, the sweeps and coarse steps with Chebyshev acceleration,
// the new velocities and what each collider's contact did. The particle graph is in
// particle_graph.cpp, the coarse step in coarse_step.cpp.
#include "integrators/vbd/vertex_block_descent.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>

#include "forces/continuum_arrays.hpp"
#include "integrators/particle_loops.hpp"
#include "integrators/vbd/vbd_loops.hpp"

namespace drapelab {
namespace {

// Collider planes kept per particle: a particle touches at most a corner's three faces in the
// scenes drapelab runs; a fourth slot leaves room for a second collider.
constexpr int kPlaneSlots = 4;

// Sweeps per coarse step: every second sweep. On the 65 x 65 sphere drape at 1/60 s, a coarse
// step before every sweep brought the sheet 6.9 cm from the reference for 1.0 s of wall time per
// simulated second, every second sweep 7.3 cm for 0.74 s, every fifth 10 cm for 0.56 s, and none
// 24 cm for 0.43 s.
constexpr int kCoarseEvery = 2;

// Self-contact detections per step at most: the first, and one before each iteration that follows
// an iteration in which too many moves were cut short at their bounds (below), with extra
// iterations past the sweeps asked for while that lasts. Past it the step ends with its moves cut
// short, which only slows the cloth (self_collision_truncations counts them).
constexpr int kMostDetections = 32;

// Moves cut short that call for another detection: more than one particle in a thousand. A few
// particles cut short wait for the next step (their cut moves only take kinetic energy); on the
// 65 x 65 heap, 0.5 s, any cut move called 4.65 detections a step and cost 5.2 s, more than one in
// a thousand 2.48 and 3.5 s, with the same heap (kinetic energy 0.0135 and 0.0130 J at the end).
std::int64_t cut_moves_tolerated(int n) { return n / 1000; }

void store(double* to, const Eigen::Vector3d& value) {
  to[0] = value[0];
  to[1] = value[1];
  to[2] = value[2];
}

}  // namespace

VertexBlockDescent::VertexBlockDescent(const ClothModel& model, VbdSettings settings)
    : settings_(settings) {
  build_coarse_system(model);
  const int n = model.particle_count();
  // A continuum cloth's sweeps take its elements instead of its springs; the springs, built from
  // the same fabric properties, stay the coarse step's model of the stiffness between aggregates.
  const SpringSet no_springs;
  const SpringSet& springs = model.uses_continuum() ? no_springs : model.springs;
  if (model.uses_continuum()) continuum_ = continuum_arrays(*model.continuum);
  // Springs per particle, as compressed rows: count, then place each spring at both its ends.
  spring_offsets_.assign(static_cast<std::size_t>(n) + 1, 0);
  for (std::size_t e = 0; e < springs.size(); ++e) {
    ++spring_offsets_[static_cast<std::size_t>(springs.v0[e]) + 1];
    ++spring_offsets_[static_cast<std::size_t>(springs.v1[e]) + 1];
  }
  for (int i = 0; i < n; ++i) spring_offsets_[i + 1] += spring_offsets_[i];
  const std::size_t entries = static_cast<std::size_t>(spring_offsets_.back());
  spring_other_.resize(entries);
  spring_rest_.resize(entries);
  spring_ks_.resize(entries);
  spring_kd_.resize(entries);
  std::vector<std::int32_t> fill(spring_offsets_.begin(), spring_offsets_.end() - 1);
  for (std::size_t e = 0; e < springs.size(); ++e)
    for (int end = 0; end < 2; ++end) {
      const std::int32_t at = end == 0 ? springs.v0[e] : springs.v1[e];
      const std::size_t slot = static_cast<std::size_t>(fill[static_cast<std::size_t>(at)]++);
      spring_other_[slot] = end == 0 ? springs.v1[e] : springs.v0[e];
      spring_rest_[slot] = springs.rest_length[e];
      spring_ks_[slot] = springs.ks[e];
      spring_kd_[slot] = springs.kd[e];
    }
  const auto colors = color_particles(model);
  color_offsets_.assign(1, 0);
  for (const auto& members : colors) {
    color_particles_.insert(color_particles_.end(), members.begin(), members.end());
    color_offsets_.push_back(static_cast<std::int32_t>(color_particles_.size()));
  }
  stats_.colors = static_cast<int>(colors.size());
  const std::size_t slots = static_cast<std::size_t>(n) * kPlaneSlots;
  plane_count_.assign(static_cast<std::size_t>(n), 0);
  plane_collider_.resize(slots);
  plane_point_.resize(3 * slots);
  plane_normal_.resize(3 * slots);
  plane_surface_move_.resize(3 * slots);
  plane_kinetic_.resize(slots);
  plane_fixed_.resize(slots);
  start_.resize(3, n);
  inertia_.resize(3, n);
  sweep_start_.resize(3, n);
  previous_v_.resize(3, n);
  previous_x_.resize(3, n);
  base_v_.resize(3, n);
}

void VertexBlockDescent::find_planes(const ClothModel& model, const VbdStepInput& input,
                                     double velocity_step, const Eigen::Matrix3Xd& x,
                                     const Eigen::Matrix3Xd& v) {
  std::fill(plane_count_.begin(), plane_count_.end(), 0);
  if (!input.contacts || input.contacts->empty()) return;
  const ContactModel& contacts = *input.contacts;
  const double radius = contacts.query().radius();  // m
  // The query sphere reaches a margin beyond the thickness: twice the fastest particle's travel
  // over the step, and at least the thickness, so a particle that can reach a surface during the
  // step has its plane.
  const double fastest = v.colwise().norm().maxCoeff();  // m/s
  const double reach = radius + std::max(radius, 2.0 * fastest * input.h);
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
      }
    });
  }
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
  coupling_offsets_.assign(static_cast<std::size_t>(n) + 1, 0);
  for (std::size_t c = 0; c < count; ++c) {
    const WeightedContact& w = couplings[c];
    for (int s = 0; s < 4; ++s) {
      coupling_particle_[4 * c + s] = w.particle[s];
      coupling_weight_[4 * c + s] = w.weight[s];
      if (w.particle[s] >= 0) ++coupling_offsets_[static_cast<std::size_t>(w.particle[s]) + 1];
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
  for (int i = 0; i < n; ++i) coupling_offsets_[i + 1] += coupling_offsets_[i];
  coupling_contact_.resize(static_cast<std::size_t>(coupling_offsets_.back()));
  coupling_slot_.resize(coupling_contact_.size());
  std::vector<std::int32_t> fill(coupling_offsets_.begin(), coupling_offsets_.end() - 1);
  for (std::size_t c = 0; c < count; ++c)
    for (int s = 0; s < 4; ++s) {
      const int i = couplings[c].particle[s];
      if (i < 0) continue;
      const std::size_t at = static_cast<std::size_t>(fill[static_cast<std::size_t>(i)]++);
      coupling_contact_[at] = static_cast<std::int32_t>(c);
      coupling_slot_[at] = s;
    }
}

void VertexBlockDescent::step(const ClothModel& model, const VbdStepInput& input,
                              Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& v,
                              std::vector<ColliderContactTotals>& totals) {
  const int n = model.particle_count();
  // BDF2, x(n+1) = X + b v(n+1) and v(n+1) = V + b a(n+1) with X = (4 x(n) - x(n-1)) / 3,
  // V = (4 v(n) - v(n-1)) / 3 and b = 2 h / 3, is backward Euler's problem with X, V and b in place
  // of x(n), v(n) and h. It needs the last step, taken with the same h; without it (the first step,
  // a change of step), the step is backward Euler's.
  const bool second_order = settings_.order == 2 && history_step_ == input.h;
  const double h = second_order ? 2.0 * input.h / 3.0 : input.h;  // s: the b above
  if (second_order) {
    start_ = (4.0 * x - previous_x_) / 3.0;
    base_v_ = (4.0 * v - previous_v_) / 3.0;
  } else {
    start_ = x;
    base_v_ = v;
  }
  find_planes(model, input, h, x, v);
  const bool coupled = input.couplings && !input.couplings->empty();
  if (coupled) index_couplings(n, *input.couplings, x, input.h);
  // y = X + b V + b^2 (g + f_explicit / m)
  inertia_ = start_ + h * base_v_;
  inertia_.colwise() += (h * h) * input.gravity;
  if (input.explicit_force && input.explicit_force->cols() == n)
    inertia_ += (h * h) * (*input.explicit_force * model.inverse_mass.asDiagonal());
  previous_x_ = x;  // x(n): the next step's history
  // The initial guess: X + b V, the motion without the step's forces. The paper's adaptive guess
  // adds the part of gravity each particle felt over the last step; with a fixed budget of sweeps
  // that part is not always taken back where the cloth is held, and an undamped curtain then gained
  // energy (9.6 J from 2.45 J in 2 s at 1/120 s, 10 sweeps). The fall itself comes from the
  // translation step after every sweep.
  // A pinned particle with a velocity is carried by a collider (attachments.hpp): it moves too.
  for (int i = 0; i < n; ++i)
    if (!model.is_pinned(i) || !base_v_.col(i).isZero(0))
      x.col(i) = start_.col(i) + h * base_v_.col(i);

  kernels::VbdProblem problem;
  problem.n = n;
  problem.h = h;
  problem.air_damping = input.air_damping;
  problem.friction_velocity = settings_.friction_velocity;
  problem.mass = model.mass.data();
  problem.inverse_mass = model.inverse_mass.data();
  problem.start = start_.data();
  problem.inertia = inertia_.data();
  problem.sweep_start = sweep_start_.data();
  problem.springs = {spring_offsets_.data(), spring_other_.data(), spring_rest_.data(),
                     spring_ks_.data(), spring_kd_.data()};
  if (continuum_) problem.continuum = &*continuum_;
  stats_.contacts_last = std::accumulate(plane_count_.begin(), plane_count_.end(), std::int64_t{0});
  if (input.contacts && !input.contacts->empty()) {
    const ContactParameters& k = input.contacts->parameters();
    contact_ = {input.contacts->query().radius(), k.stiffness, k.damping};
    problem.planes = {kPlaneSlots,
                      plane_count_.data(),
                      plane_point_.data(),
                      plane_normal_.data(),
                      plane_surface_move_.data(),
                      plane_kinetic_.data(),
                      plane_fixed_.data(),
                      input.contacts->query().radius(),
                      k.stiffness,
                      k.damping};
  }
  if (coupled)
    problem.couplings = {
        coupling_offsets_.data(),   coupling_contact_.data(),   coupling_slot_.data(),
        coupling_particle_.data(),  coupling_weight_.data(),    coupling_normal_.data(),
        coupling_depth_.data(),     coupling_stiffness_.data(), coupling_damping_.data(),
        coupling_two_sided_.data(), coupling_end_rate_.data()};
  problem.color_offsets = color_offsets_.data();
  problem.color_particles = color_particles_.data();
  problem.colors = static_cast<int>(color_offsets_.size()) - 1;

  // Chebyshev semi-iteration: x(k) = w_k (sweep(x(k-1)) - x(k-2)) + x(k-2), with w_1 = 1,
  // w_2 = 2 / (2 - rho^2), w_k = 4 / (4 - rho^2 w_(k-1)).
  const double rho = settings_.chebyshev_rho;
  const bool accelerate = rho > 0.0;
  OffsetContacts* self = input.self_contacts;
  std::int64_t truncated = self ? detect_self_contacts(model, *self, problem, x) : 0;
  std::int64_t truncated_total = truncated;
  int detections = self ? 1 : 0;
  if (accelerate) before_last_ = x;
  double omega = 1.0, last_move = 0.0;
  int k = 0;
  // The sweeps asked for, and more while moves are still cut short at their bounds: a part of the
  // cloth that moves fast against its neighbours (an impact, a whip) gets there a bound at a time.
  const std::int64_t tolerated = cut_moves_tolerated(n);
  for (; k < settings_.iterations || (truncated > tolerated && detections < kMostDetections); ++k) {
    // Moves were cut short: look again from here, where the bounds are known to hold.
    if (self && truncated > tolerated && detections < kMostDetections) {
      self->detect(x, Eigen::Vector3d::Zero());
      problem.self_contacts = self->arrays();
      ++detections;
    }
    truncated = 0;
    if (accelerate) iteration_start_ = x;
    if (self) sweep_start_ = x;
    // The coarse step first, so that the sweep after it settles what it moved into contact.
    if (settings_.coarse_correction && k % kCoarseEvery == 0) {
      coarse_step(problem, true, x);
      truncated += kernels::vbd_keep_within_bounds(problem, x.data());
    }
    if (coupled || self) sweep_start_ = x;
    const kernels::VbdSweepResult sweep = kernels::vbd_sweep(problem, x.data());
    last_move = sweep.largest_move;
    truncated += sweep.truncated;
    if (accelerate) {
      omega = k == 0 ? 1.0 : k == 1 ? 2.0 / (2.0 - rho * rho) : 4.0 / (4.0 - rho * rho * omega);
      if (k > 0) x = omega * (x - before_last_) + before_last_;
      before_last_ = iteration_start_;
      truncated += kernels::vbd_keep_within_bounds(problem, x.data());
    }
    truncated_total += truncated;
  }
  previous_v_ = v;
  history_step_ = input.h;
  v = (x - start_) / h;
  ++stats_.steps;
  stats_.iterations_total += k;
  stats_.last_sweep_move = last_move;
  stats_.last_sweep_move_max = std::max(stats_.last_sweep_move_max, last_move);
  record_contact_totals(x, h, totals);
  if (self) {
    self->record_end_state(x, start_, h, settings_.friction_velocity);
    self->count_truncations(truncated_total);
    stats_.self_contact_detections += detections;
  }
}

std::int64_t VertexBlockDescent::detect_self_contacts(const ClothModel& model, OffsetContacts& self,
                                                      kernels::VbdProblem& problem,
                                                      Eigen::Matrix3Xd& x) {
  // x(n), with the pins where the step takes them: they move with their colliders, not within a
  // bound, so the bounds are set around where they end.
  detection_x_ = previous_x_;
  bool pinned = false;
  for (int i = 0; i < model.particle_count(); ++i)
    if (model.is_pinned(i)) {
      detection_x_.col(i) = x.col(i);
      pinned = true;
    }
  // A free cloth's common translation over the step moves no part of it towards another: the
  // bounds follow it. Not where something holds part of the cloth back: a pin, or a collider the
  // guess touches, which the bounds would otherwise carry the particle through.
  bool near_collider = false;
  for (int i = 0; i < model.particle_count() && !near_collider; ++i)
    for (int k = 0; k < plane_count_[static_cast<std::size_t>(i)]; ++k) {
      const std::size_t e = static_cast<std::size_t>(i) * kPlaneSlots + static_cast<std::size_t>(k);
      const Eigen::Map<const Eigen::Vector3d> n(&plane_normal_[3 * e]);
      const Eigen::Map<const Eigen::Vector3d> point(&plane_point_[3 * e]);
      if ((x.col(i) - point).dot(n) < contact_.radius) near_collider = true;  // the guess touches
    }
  const Eigen::Vector3d shift = pinned || near_collider
                                    ? Eigen::Vector3d::Zero()
                                    : Eigen::Vector3d((x - detection_x_).rowwise().mean());
  self.detect(detection_x_, shift);
  problem.self_contacts = self.arrays();
  return kernels::vbd_keep_within_bounds(problem, x.data());
}

void VertexBlockDescent::record_contact_totals(const Eigen::Matrix3Xd& x, double h,
                                               std::vector<ColliderContactTotals>& totals) const {
  if (totals.empty()) return;
  for (ColliderContactTotals& t : totals) t = ColliderContactTotals{};
  // The plane's spring-damper at the end state, and the friction the end state's slip implies.
  for (std::size_t i = 0; i < plane_count_.size(); ++i)
    for (int k = 0; k < plane_count_[i]; ++k) {
      const std::size_t e = i * kPlaneSlots + static_cast<std::size_t>(k);
      const Eigen::Map<const Eigen::Vector3d> n(&plane_normal_[3 * e]);
      const Eigen::Map<const Eigen::Vector3d> point(&plane_point_[3 * e]);
      const double depth = contact_.radius - (x.col(static_cast<Eigen::Index>(i)) - point).dot(n);
      if (depth <= 0.0) continue;
      const Eigen::Map<const Eigen::Vector3d> surface(&plane_surface_move_[3 * e]);
      const Eigen::Vector3d rel =
          x.col(static_cast<Eigen::Index>(i)) - start_.col(static_cast<Eigen::Index>(i)) - surface;
      const double fn =
          std::max(0.0, contact_.stiffness * depth - contact_.damping * rel.dot(n) / h);
      ColliderContactTotals& t = totals[static_cast<std::size_t>(plane_collider_[e])];
      // The step's mean velocities relative to the surface and of the surface (m/s).
      const Eigen::Vector3d relative_velocity = rel / h, surface_velocity = surface / h;
      t.power += push_power(fn, contact_.stiffness * depth, n, relative_velocity, surface_velocity);
      if (fn <= 0.0) continue;
      ++t.contact_count;
      t.normal_force += fn;
      const Eigen::Vector3d slide = rel - rel.dot(n) * n;  // m over the step
      const double slip = slide.norm();
      const double scale = settings_.friction_velocity * h;
      const double friction =
          slip < scale ? plane_fixed_[e] * fn * slip / scale : plane_kinetic_[e] * fn;  // N
      t.friction_force += friction;
      t.max_depth = std::max(t.max_depth, depth);
      Eigen::Vector3d on_cloth = fn * n;  // N
      if (slip > 0.0) {
        const Eigen::Vector3d rub = -(friction / slip) * slide;  // N
        on_cloth += rub;
        t.power += friction_power(rub, relative_velocity, surface_velocity);
      }
      t.force -= on_cloth;
      t.torque -= Eigen::Vector3d(x.col(static_cast<Eigen::Index>(i))).cross(on_cloth);
    }
}

}  // namespace drapelab
