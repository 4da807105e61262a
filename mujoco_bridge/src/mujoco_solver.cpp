// MuJoCo's cloth as a drapelab Solver (mujoco_solver.hpp; docs/mujoco.md).
#include "drapelab/mujoco/mujoco_solver.hpp"

#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "drapelab/runaway_check.hpp"
#include "drapelab/spring_forces.hpp"
#include "mjcf_writer.hpp"
#include "mujoco_layout.hpp"
#include "mujoco_model.hpp"

namespace drapelab::mujoco {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// What the mapping does not carry, refused before any model is built (the scene loader refuses
// the same with the scene file's line).
void check_supported(const std::vector<Collider>& colliders) {
  for (const Collider& collider : colliders) {
    if (collider.shape == ColliderShape::mesh)
      throw std::invalid_argument("collider '" + collider.name +
                                  "' is a mesh, which the MuJoCo solver does not carry");
    if (collider.dynamic())
      throw std::invalid_argument("collider '" + collider.name +
                                  "' is dynamic, which the MuJoCo solver does not carry");
  }
}

class MujocoSolver final : public Solver {
 public:
  MujocoSolver(std::string name, std::shared_ptr<const ClothModel> model, const ClothState& initial,
               std::vector<Collider> colliders, MujocoOptions options)
      : name_(std::move(name)),
        model_(std::move(model)),
        colliders_(std::move(colliders)),
        options_(std::move(options)),
        state_(initial) {
    check_supported(colliders_);
    const int n = model_->particle_count();
    std::int64_t free_particles = 0;
    for (int i = 0; i < n; ++i)
      if (!model_->is_pinned(i)) ++free_particles;
    std::int64_t dofs = 3 * free_particles;
    for (const Collider& collider : colliders_)
      if (collider_is_body(collider)) dofs += 6;
    MjcfInputs in;
    in.model = model_.get();
    in.colliders = &colliders_;
    in.gravity = options_.gravity;
    in.dt = options_.dt;
    in.air_damping = options_.air_damping;
    in.particle_radius = options_.particle_radius;
    if (options_.contacts) {
      in.contact_stiffness = options_.contacts->parameters().stiffness;
      in.contact_damping = options_.contacts->parameters().damping;
    }
    in.self_collision = options_.self_collision;
    in.numerics = options_.numerics;
    in.solver = chosen_solver(options_.numerics.constraint_solver, static_cast<int>(dofs));
    in.contacts = contact_capacity(options_.numerics.max_contacts, free_particles, dofs);
    contact_capacity_ = in.contacts;
    in.impratio = options_.numerics.impratio > 0.0
                      ? options_.numerics.impratio
                      : friction_impratio(in.contact_damping, mean_free_mass(*model_), in.dt);
    mj_model_ = compile_mjcf(write_mjcf(in));
    mj_data_ = DataPointer(mj_makeData(mj_model_.get()));
    if (!mj_data_) throw std::runtime_error("MuJoCo could not allocate its data for this cloth");
    layout_ = layout_of(*mj_model_, *model_, colliders_);
    write_state(state_);
    const double t0 = state_.time;
    for (std::size_t c = 0; c < colliders_.size(); ++c)
      if (layout_.body_of_collider[c] > 0) set_body_pose(c, collider_pose(colliders_[c], t0));
    forces_.assign(colliders_.size(), ColliderForce{});
    force_ = Eigen::Matrix3Xd::Zero(3, n);
  }

  void step(double h) override {
    if (status_ != SolverStatus::ok) return;
    const double t0 = state_.time;
    const double t1 = t0 + h;
    mjModel* m = mj_model_.get();
    mjData* d = mj_data_.get();
    m->opt.timestep = h;
    Clock::time_point start = Clock::now();
    drive_colliders(t0, t1, h);
    apply_cloth_forces(t0);
    forces_seconds_ += seconds_since(start);
    start = Clock::now();
    mj_step(m, d);
    step_seconds_ += seconds_since(start);
    contacts_sum_ += d->ncon;
    iterations_sum_ += d->solver_iter;
    if (stopped_by_warning(h)) return;
    read_state(t1, h);
    for (std::size_t c = 0; c < colliders_.size(); ++c)
      if (layout_.body_of_collider[c] > 0) set_body_pose(c, collider_pose(colliders_[c], t1));
    collect_collider_forces(*mj_model_, *mj_data_, layout_, forces_);
    if (const auto message = runaway_message(
            *model_, state_, options_.max_speed, h,
            "a smaller dt (MuJoCo takes our springs and its contact springs explicitly: the "
            "stable step is symplectic Euler's with the contact), or softer springs.")) {
      status_ = SolverStatus::unstable;
      message_ = *message;
    }
  }

  const ClothState& state() const override { return state_; }
  const std::string& name() const override { return name_; }
  SolverType type() const override { return SolverType::mujoco; }
  SolverStatus status() const override { return status_; }
  const std::string& message() const override { return message_; }
  std::vector<ColliderForce> collider_forces() const override { return forces_; }

  std::vector<std::pair<std::string, double>> phase_seconds() const override {
    return {{"cloth_forces", forces_seconds_}, {"mj_step", step_seconds_}};
  }

  std::vector<std::pair<std::string, double>> counters() const override {
    const double steps = std::max<double>(1.0, static_cast<double>(state_.step_count));
    return {{"mujoco_contacts_mean", static_cast<double>(contacts_sum_) / steps},
            {"mujoco_contact_capacity", static_cast<double>(contact_capacity_)},
            {"mujoco_solver_iterations_mean", static_cast<double>(iterations_sum_) / steps},
            {"mujoco_stack_peak", static_cast<double>(mj_data_->maxuse_stack)},
            {"mujoco_constraint_rows_peak", static_cast<double>(mj_data_->maxuse_efc)}};
  }

 private:
  // The free particles' slides from x, v (our state).
  void write_state(const ClothState& state) {
    const mjModel* m = mj_model_.get();
    mjData* d = mj_data_.get();
    for (std::size_t i = 0; i < layout_.particle_body.size(); ++i) {
      const int b = layout_.particle_body[i];
      if (b < 0) continue;
      mjtNum* q = d->qpos + m->jnt_qposadr[m->body_jntadr[b]];
      mjtNum* u = d->qvel + m->body_dofadr[b];
      const auto p = static_cast<Eigen::Index>(i);
      for (int k = 0; k < 3; ++k) {
        q[k] = state.x(k, p);
        u[k] = state.v(k, p);
      }
    }
  }

  void set_body_pose(std::size_t c, const Eigen::Isometry3d& pose) {
    const mjModel* m = mj_model_.get();
    mjtNum* q = mj_data_->qpos + m->jnt_qposadr[m->body_jntadr[layout_.body_of_collider[c]]];
    const Eigen::Quaterniond rotation(pose.linear());
    for (int k = 0; k < 3; ++k) q[k] = pose.translation()[k];
    q[3] = rotation.w();
    q[4] = rotation.x();
    q[5] = rotation.y();
    q[6] = rotation.z();
  }

  // Every kinematic collider at its pose at t0, with the constant velocities that carry it to its
  // pose at t1 (the contacts' relative velocity and friction need them), and gravity cancelled.
  void drive_colliders(double t0, double t1, double h) {
    const mjModel* m = mj_model_.get();
    mjData* d = mj_data_.get();
    for (std::size_t c = 0; c < colliders_.size(); ++c) {
      const int b = layout_.body_of_collider[c];
      if (b <= 0) continue;
      const Eigen::Isometry3d before = collider_pose(colliders_[c], t0);
      const Eigen::Isometry3d after = collider_pose(colliders_[c], t1);
      set_body_pose(c, before);
      const Eigen::AngleAxisd turn(after.linear() * before.linear().transpose());
      const Eigen::Vector3d angular = turn.axis() * turn.angle() / h;  // rad/s, world axes
      const Eigen::Vector3d linear = (after.translation() - before.translation()) / h;
      const Eigen::Vector3d body_angular = before.linear().transpose() * angular;
      mjtNum* u = d->qvel + m->body_dofadr[b];
      for (int k = 0; k < 3; ++k) {
        u[k] = linear[k];
        u[3 + k] = body_angular[k];
      }
      mjtNum* load = d->xfrc_applied + 6 * b;
      for (int k = 0; k < 3; ++k) {
        load[k] = -kKinematicMass * options_.gravity[k];
        load[3 + k] = 0.0;
      }
    }
  }

  // Our springs, and the air and soft constraints when the scene has them, at the step's start, as
  // MuJoCo's applied forces on the free particles.
  void apply_cloth_forces(double t0) {
    force_.setZero();
    add_spring_forces(*model_, state_.x, state_.v, force_);
    if (options_.air.enabled)
      add_air_forces(*model_, options_.air, wind_, t0, state_.x, state_.v, force_);
    if (options_.constraints && options_.constraints->has_soft())
      options_.constraints->add_soft_forces(t0, state_.x, state_.v, force_, nullptr);
    const mjModel* m = mj_model_.get();
    mjData* d = mj_data_.get();
    for (std::size_t i = 0; i < layout_.particle_body.size(); ++i) {
      const int b = layout_.particle_body[i];
      if (b < 0) continue;
      mjtNum* f = d->qfrc_applied + m->body_dofadr[b];
      for (int k = 0; k < 3; ++k) f[k] = force_(k, static_cast<Eigen::Index>(i));
    }
  }

  // The free particles from MuJoCo, the attached ones placed at t1, then the hard and rope
  // constraints projected (and written back to MuJoCo).
  void read_state(double t1, double h) {
    const mjModel* m = mj_model_.get();
    const mjData* d = mj_data_.get();
    for (std::size_t i = 0; i < layout_.particle_body.size(); ++i) {
      const int b = layout_.particle_body[i];
      if (b < 0) continue;
      const mjtNum* q = d->qpos + m->jnt_qposadr[m->body_jntadr[b]];
      const mjtNum* u = d->qvel + m->body_dofadr[b];
      const auto p = static_cast<Eigen::Index>(i);
      for (int k = 0; k < 3; ++k) {
        state_.x(k, p) = q[k];
        state_.v(k, p) = u[k];
      }
    }
    state_.time = t1;
    ++state_.step_count;
    if (options_.attachments) options_.attachments->place(t1, state_.x, state_.v);
    if (options_.constraints && options_.constraints->has_hard()) {
      ConstraintProjection projection =
          options_.constraints->project_positions(t1, model_->inverse_mass, state_.x);
      options_.constraints->project_velocities(t1, h, model_->inverse_mass, state_.x, state_.v,
                                               projection);
      write_state(state_);
    }
  }

  // MuJoCo's own checks: a full contact or constraint buffer drops contacts silently; a bad
  // position, velocity or acceleration makes it reset its state.
  bool stopped_by_warning(double h) {
    mjData* d = mj_data_.get();
    const bool full =
        d->warning[mjWARN_CONTACTFULL].number > 0 || d->warning[mjWARN_CNSTRFULL].number > 0;
    const bool bad = d->warning[mjWARN_BADQPOS].number > 0 ||
                     d->warning[mjWARN_BADQVEL].number > 0 || d->warning[mjWARN_BADQACC].number > 0;
    if (!full && !bad) return false;
    std::ostringstream text;
    text.precision(4);
    const std::int64_t step = state_.step_count + 1;
    if (full) {
      status_ = SolverStatus::error;
      text << "MuJoCo's contact buffer of " << contact_capacity_ << " contacts is full at step "
           << step << " (t = " << state_.time + h
           << " s): it drops the contacts beyond it. Try: max_contacts above " << contact_capacity_
           << " on this solver (MuJoCo 2.2 keeps all its data in one buffer under 2 GB, and each "
              "contact takes about 72 x the cloth's degrees of freedom bytes), or fewer particles.";
    } else {
      status_ = SolverStatus::unstable;
      int fastest = 0;
      double top = -1.0;
      for (int i = 0; i < model_->particle_count(); ++i)
        if (state_.v.col(i).norm() > top) {
          top = state_.v.col(i).norm();
          fastest = i;
        }
      text << "MuJoCo found a non-finite state in step " << step << " (t = " << state_.time + h
           << " s, dt = " << h << " s); the fastest particle before it was " << fastest << " ("
           << model_->describe_particle(fastest) << ") at " << top
           << " m/s. Try: a smaller dt (MuJoCo takes our springs and its contact springs "
              "explicitly), or softer springs.";
    }
    message_ = text.str();
    return true;
  }

  std::string name_;
  std::shared_ptr<const ClothModel> model_;
  std::vector<Collider> colliders_;
  MujocoOptions options_;
  ClothState state_;
  Eigen::Matrix3Xd force_;  // N, the applied forces of the current step
  Wind wind_{options_.air};
  std::vector<ColliderForce> forces_;
  SolverStatus status_ = SolverStatus::ok;
  std::string message_;
  std::int64_t contact_capacity_ = 0;
  std::int64_t contacts_sum_ = 0, iterations_sum_ = 0;
  double forces_seconds_ = 0.0, step_seconds_ = 0.0;  // s

  ModelPointer mj_model_;
  DataPointer mj_data_;
  MujocoLayout layout_;
};

}  // namespace

std::unique_ptr<Solver> make_mujoco_solver(std::string name,
                                           std::shared_ptr<const ClothModel> model,
                                           const ClothState& initial,
                                           std::vector<Collider> colliders, MujocoOptions options) {
  return std::make_unique<MujocoSolver>(std::move(name), std::move(model), initial,
                                        std::move(colliders), std::move(options));
}

}  // namespace drapelab::mujoco
