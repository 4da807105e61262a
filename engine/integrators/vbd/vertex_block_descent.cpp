// Vertex block descent's step driver (vertex_block_descent.hpp): the particles' spring lists and
// contact slots, built once; per step the collider contact planes, the contacts between particles,
// the inertial target, the initial guess, the sweeps and coarse steps with Chebyshev acceleration,
// the new velocities. The particle graph is in particle_graph.cpp, the coarse step in
// coarse_step.cpp, the step's contacts in vbd_contacts.cpp and what each collider's contact did
// in vbd_contact_totals.cpp.
#include "integrators/vbd/vertex_block_descent.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <numeric>

#include "forces/continuum_arrays.hpp"
#include "integrators/particle_loops.hpp"
#include "integrators/vbd/vbd_loops.hpp"

namespace drapelab {
namespace {

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

// Sweeps a passive step may add while its end holds more energy than its start (below). On a
// cotton sheet settling over a cylinder's rim, 20 sweeps in all still gained 0.0036 J over the
// run, 30 gained 0.0002.
constexpr int kMostEnergySweeps = 20;

// Moves cut short that call for another detection: more than one particle in a thousand. A few
// particles cut short wait for the next step (their cut moves only take kinetic energy); on the
// 65 x 65 heap, 0.5 s, any cut move called 4.65 detections a step and cost 5.2 s, more than one in
// a thousand 2.48 and 3.5 s, with the same heap (kinetic energy 0.0135 and 0.0130 J at the end).
std::int64_t cut_moves_tolerated(int n) { return n / 1000; }

}  // namespace

VertexBlockDescent::VertexBlockDescent(const ClothModel& model, VbdSettings settings)
    : settings_(settings) {
  const int n = model.particle_count();
  // A continuum cloth's sweeps take its elements instead of its springs; the springs, built from
  // the same fabric properties, stay the coarse step's model of the stiffness between aggregates.
  const SpringSet no_springs;
  const SpringSet& springs = model.uses_continuum() ? no_springs : model.springs;
  if (model.uses_continuum()) continuum_ = continuum_arrays(*model.continuum);
  springs_ = spring_rows(springs, n);
  build_coarse_system(model);
  const auto colors = color_particles(model);
  color_offsets_.assign(1, 0);
  color_of_.assign(static_cast<std::size_t>(n), 0);
  for (const auto& members : colors) {
    for (const std::int32_t i : members)
      color_of_[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(color_offsets_.size() - 1);
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
  plane_load_.resize(slots);
  start_.resize(3, n);
  inertia_.resize(3, n);
  sweep_start_.resize(3, n);
  previous_v_.resize(3, n);
  previous_x_.resize(3, n);
  end_v_.resize(3, n);
  const Eigen::Vector3d extent =
      model.rest_positions.rowwise().maxCoeff() - model.rest_positions.rowwise().minCoeff();
  weight_height_ = model.mass.sum() * extent.norm();
  base_v_.resize(3, n);
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
  const bool featured = input.features && input.contacts && !input.contacts->empty();
  if (featured) find_features(n, input, h, x, v);
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
  problem.springs = springs_.view();
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
                      plane_load_.data(),
                      input.contacts->query().radius(),
                      k.stiffness,
                      k.damping};
    if (featured)
      problem.features = feature_view(input.contacts->query().radius(), k.stiffness, k.damping);
  }
  if (coupled)
    problem.couplings = {
        coupling_offsets_.data(),   coupling_contact_.data(),   coupling_slot_.data(),
        coupling_particle_.data(),  coupling_weight_.data(),    coupling_normal_.data(),
        coupling_depth_.data(),     coupling_stiffness_.data(), coupling_damping_.data(),
        coupling_two_sided_.data(), coupling_end_rate_.data()};
  problem.color_offsets = color_offsets_.data();
  problem.color_particles = color_particles_.data();
  problem.color_of = color_of_.data();
  problem.colors = static_cast<int>(color_offsets_.size()) - 1;

  // Chebyshev semi-iteration: x(k) = w_k (sweep(x(k-1)) - x(k-2)) + x(k-2), with w_1 = 1,
  // w_2 = 2 / (2 - rho^2), w_k = 4 / (4 - rho^2 w_(k-1)).
  const double rho = settings_.chebyshev_rho;
  const bool accelerate = rho > 0.0;
  OffsetContacts* self = input.self_contacts;
  std::int64_t truncated = self ? detect_self_contacts(model, *self, problem, x) : 0;
  std::int64_t truncated_total = truncated;
  int detections = self ? 1 : 0;
  // The start's energy, with the step's contacts (found at the start).
  const bool passive = passive_step(model, input);
  const double start_energy =
      passive ? mechanical_energy(problem, input.gravity, previous_x_, v, self) : 0.0;
  if (accelerate) before_last_ = x;
  double omega = 1.0, last_move = 0.0;
  const auto iterate = [&](int k) {
    // Moves were cut short: look again from here, where the bounds are known to hold.
    if (self && truncated > cut_moves_tolerated(n) && detections < kMostDetections) {
      self->detect(x, Eigen::Vector3d::Zero());
      problem.self_contacts = self->arrays();
      ++detections;
    }
    truncated = 0;
    if (accelerate) iteration_start_ = x;
    // The contacts' partners of a particle's own colour are read at sweep_start_ (the coarse
    // step's terms too, which must see x).
    if (coupled || self || featured) sweep_start_ = x;
    // The coarse step first, so that the sweep after it settles what it moved into contact.
    if (settings_.coarse_correction && k % kCoarseEvery == 0) {
      coarse_step(problem, k == 0, x);
      truncated += kernels::vbd_keep_within_bounds(problem, x.data());
      if (coupled || self || featured) sweep_start_ = x;
    }
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
  };
  int k = 0;
  // The sweeps asked for, and more while moves are still cut short at their bounds: a part of the
  // cloth that moves fast against its neighbours (an impact, a whip) gets there a bound at a time.
  const std::int64_t tolerated = cut_moves_tolerated(n);
  for (; k < settings_.iterations || (truncated > tolerated && detections < kMostDetections); ++k)
    iterate(k);
  // A passive step's exact solution ends with no more energy than it started with (backward
  // Euler dissipates): while the iterate holds more, it is not the solution yet, and the sweeps
  // go on. On a cotton sheet settling over a cylinder's sharp rim, 10 sweeps left residual forces
  // that did 0.004 J of work over 0.15 s, which 30 sweeps did not.
  if (passive) {
    const double allowed = start_energy + energy_slack(input.gravity, start_energy);
    for (int extra = 0; extra < kMostEnergySweeps; ++extra, ++k) {
      end_v_ = (x - start_) / h;
      if (mechanical_energy(problem, input.gravity, x, end_v_, self) <= allowed) break;
      iterate(k);
      ++stats_.energy_sweeps;
    }
  }
  previous_v_ = v;
  history_step_ = input.h;
  v = (x - start_) / h;
  ++stats_.steps;
  stats_.iterations_total += k;
  stats_.last_sweep_move = last_move;
  stats_.last_sweep_move_max = std::max(stats_.last_sweep_move_max, last_move);
  record_contact_totals(x, h, totals);
  if (featured) record_feature_totals(x, h, totals);
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

}  // namespace drapelab
