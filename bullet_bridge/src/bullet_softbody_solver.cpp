// Bullet's classic cloth as a drapelab Solver (see bullet_softbody_solver.hpp).
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "bullet_math.hpp"
#include "classic_cloth_solver.hpp"
#include "drapelab/runaway_check.hpp"
#include "soft_body_cloth.hpp"

namespace drapelab::bullet {

BulletSoftBodySolver::BulletSoftBodySolver(std::string name,
                                           std::shared_ptr<const ClothModel> model,
                                           const ClothState& initial,
                                           std::vector<Collider> colliders,
                                           BulletSoftBodyOptions options)
    : name_(std::move(name)),
      model_(std::move(model)),
      options_(std::move(options)),
      state_(initial) {
  // Its anchors hold a body only as hard as its links pull the anchored node: a 0.2 kg ball hung
  // from one node of a light sheet falls through and the run blows up within 0.05 s.
  if (options_.attachments && options_.attachments->any_on_dynamic())
    throw std::invalid_argument(
        "Bullet's classic cloth cannot carry pins attached to a dynamic collider (use "
        "bullet_deformable or spring_damper)");
  world_ = std::make_unique<btSoftRigidDynamicsWorld>(
      &dispatcher_, &broadphase_, &constraint_solver_, &configuration_, nullptr);
  world_->setInternalTickCallback(&BulletSoftBodySolver::before_substep, this, /*isPreTick=*/true);
  world_->setGravity(to_bullet(options_.gravity));
  btSoftBodyWorldInfo& info = world_->getWorldInfo();
  info.m_gravity = to_bullet(options_.gravity);  // soft bodies read this, not setGravity
  info.air_density = 0.0;
  info.m_sparsesdf.Initialize();
  info.m_sparsesdf.setDefaultVoxelsz(options_.voxel_size);
  info.m_sparsesdf.Reset();
  colliders_ = std::make_unique<KinematicColliders>(colliders, options_.collider_margin, *world_);
  // Soft constraints ending on a dynamic collider follow this world's body.
  body_poses_ = follow_own_bodies(options_.constraints, colliders.size());
  build_cloth(initial);
  previous_velocity_ = state_.v;
  forces_.assign(colliders.size(), ColliderForce{});
}

BulletSoftBodySolver::~BulletSoftBodySolver() {
  world_->removeSoftBody(cloth_.get());
  colliders_.reset();
}

void BulletSoftBodySolver::step(double h) {
  if (status_ != SolverStatus::ok) return;
  substep_start_ = state_.time;
  previous_velocity_ = state_.v;
  world_->stepSimulation(h, 0);  // exactly one substep of h
  if (options_.attachments) place_attached_nodes(*options_.attachments, state_.time + h, *cloth_);
  if (options_.constraints && options_.constraints->has_hard())
    project_node_constraints(*options_.constraints, *model_, state_.time + h, h, *cloth_, state_);
  state_.time += h;
  ++state_.step_count;
  read_state();
  estimate_contact_forces(h);
  check_health(h);
}

// Pre-tick: the kinematic colliders take their pose at the end of the substep [t, t + h].
void BulletSoftBodySolver::before_substep(btDynamicsWorld* world, btScalar h) {
  auto* self = static_cast<BulletSoftBodySolver*>(world->getWorldUserInfo());
  self->colliders_->move_to(self->substep_start_, self->substep_start_ + h);
  if (self->body_poses_)
    self->colliders_->write_substep(self->substep_start_, h, *self->body_poses_);
  if (self->options_.attachments)
    place_attached_nodes(*self->options_.attachments, self->substep_start_, *self->cloth_);
  if (self->options_.constraints && self->options_.constraints->has_soft())
    kick_soft_constraints(*self->options_.constraints, *self->model_, self->substep_start_, h,
                          *self->cloth_, self->state_, *self->colliders_);
  if (self->options_.air.enabled) {
    // One wind per soft body in Bullet: with turbulence, the wind at the cloth's centre.
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    if (self->wind_.varies_in_space()) {
      const btSoftBody::tNodeArray& nodes = self->cloth_->m_nodes;
      for (int i = 0; i < nodes.size(); ++i) centre += to_eigen(nodes[i].m_x);
      centre /= std::max(1, nodes.size());
    }
    self->cloth_->setWindVelocity(to_bullet(self->wind_.at(self->substep_start_, centre)));
  }
}

void BulletSoftBodySolver::build_cloth(const ClothState& initial) {
  const SpringSet& s = model_->springs;
  auto link_stiffness = [&](std::size_t e) {
    const auto& raw = options_.raw_link_stiffness[static_cast<int>(s.kind[e])];
    const double w = model_->inverse_mass[s.v0[e]] + model_->inverse_mass[s.v1[e]];
    return raw ? *raw : mapped_link_stiffness(s.ks[e], w, options_.dt, options_.iterations);
  };
  cloth_ = make_soft_body(world_->getWorldInfo(), *model_, initial, link_stiffness,
                          options_.attachments.get());
  btSoftBody::Config& cfg = cloth_->m_cfg;
  cfg.piterations = options_.iterations;
  cfg.kDP = 1.0 - std::exp(-options_.air_damping * options_.dt);  // global damping per substep
  cfg.kDG = cfg.kLF = 0.0;  // no aerodynamics, unless the scene has air:
  if (options_.air.enabled) {
    // Bullet's two-sided face model with lift and drag (docs/bullet.md, "Air"); the wind is set
    // before every substep.
    cfg.aeromodel = btSoftBody::eAeroModel::F_TwoSidedLiftDrag;
    cfg.kDG = options_.air.drag;
    cfg.kLF = options_.air.lift;
    world_->getWorldInfo().air_density = options_.air.density;
  }
  cfg.kDF = 1.0;              // friction = collider friction (Bullet's own model, not Coulomb)
  cfg.kCHR = cfg.kKHR = 1.0;  // full contact hardness, also against kinematic bodies
  cfg.collisions = btSoftBody::fCollision::SDF_RS;
  cloth_->getCollisionShape()->setMargin(options_.margin);
  world_->addSoftBody(cloth_.get());
}

void BulletSoftBodySolver::read_state() { read_soft_body_state(*cloth_, state_); }

void BulletSoftBodySolver::estimate_contact_forces(double h) {
  std::vector<NodeContact> contacts;
  for (int k = 0; k < cloth_->m_rcontacts.size(); ++k) {
    const btSoftBody::RContact& contact = cloth_->m_rcontacts[k];
    const int c = colliders_->index_of(contact.m_cti.m_colObj);
    if (c >= 0)
      contacts.push_back({static_cast<int>(contact.m_node - &cloth_->m_nodes[0]), c,
                          to_eigen(contact.m_cti.m_normal)});
  }
  bullet::estimate_contact_forces(*model_, contacts, previous_velocity_, state_.v, options_.gravity,
                                  h, forces_);
}

void BulletSoftBodySolver::check_health(double h) {
  if (const auto message =
          runaway_message(*model_, state_, options_.max_speed, h,
                          "a smaller dt, more iterations, or a smaller voxel_size if nodes "
                          "tunnel into a collider.")) {
    status_ = SolverStatus::unstable;
    message_ = *message;
  }
}

std::unique_ptr<Solver> make_bullet_softbody_solver(std::string name,
                                                    std::shared_ptr<const ClothModel> model,
                                                    const ClothState& initial,
                                                    std::vector<Collider> colliders,
                                                    BulletSoftBodyOptions options) {
  return std::make_unique<BulletSoftBodySolver>(std::move(name), std::move(model), initial,
                                                std::move(colliders), std::move(options));
}

}  // namespace drapelab::bullet
