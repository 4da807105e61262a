// Bullet's classic cloth as a drapelab Solver (see bullet_softbody_solver.hpp).
#include <cmath>
#include <map>
#include <sstream>

#include "bullet_math.hpp"
#include "classic_cloth_solver.hpp"

namespace drapelab::bullet {

BulletSoftBodySolver::BulletSoftBodySolver(std::string name, std::shared_ptr<const ClothModel> model,
                                           const ClothState& initial, std::vector<Collider> colliders,
                                           BulletSoftBodyOptions options)
    : name_(std::move(name)), model_(std::move(model)), options_(std::move(options)), state_(initial) {
  world_ = std::make_unique<btSoftRigidDynamicsWorld>(&dispatcher_, &broadphase_, &constraint_solver_,
                                                      &configuration_, nullptr);
  world_->setInternalTickCallback(&BulletSoftBodySolver::before_substep, this, /*isPreTick=*/true);
  world_->setGravity(to_bullet(options_.gravity));
  btSoftBodyWorldInfo& info = world_->getWorldInfo();
  info.m_gravity = to_bullet(options_.gravity);  // soft bodies read this, not setGravity
  info.air_density = 0.0;
  info.m_sparsesdf.Initialize();
  info.m_sparsesdf.setDefaultVoxelsz(options_.voxel_size);
  info.m_sparsesdf.Reset();
  colliders_ = std::make_unique<KinematicColliders>(colliders, options_.collider_margin, *world_);
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
}

void BulletSoftBodySolver::build_cloth(const ClothState& initial) {
  const int n = model_->particle_count();
  // Built in the rest pose, so that Bullet's own rest lengths are ours (it recomputes them from the
  // current positions whenever masses or links change: bullet-notes 1.3); then moved to the start.
  std::vector<btVector3> rest(n);
  std::vector<btScalar> masses(n);
  for (int i = 0; i < n; ++i) {
    rest[i] = to_bullet(model_->rest_positions.col(i));
    masses[i] = model_->is_pinned(i) ? 0.0 : model_->mass[i];
  }
  btSoftBodyWorldInfo& info = world_->getWorldInfo();
  cloth_ = std::make_unique<btSoftBody>(&info, n, rest.data(), masses.data());
  const SpringSet& s = model_->springs;
  std::map<double, btSoftBody::Material*> materials;  // one material per distinct kLST
  for (std::size_t e = 0; e < s.size(); ++e) {
    const double w = model_->inverse_mass[s.v0[e]] + model_->inverse_mass[s.v1[e]];
    const auto& raw = options_.raw_link_stiffness[static_cast<int>(s.kind[e])];
    const double k = raw ? *raw : mapped_link_stiffness(s.ks[e], w, options_.dt, options_.iterations);
    btSoftBody::Material*& material = materials[k];
    if (!material) {
      material = cloth_->appendMaterial();
      material->m_kLST = k;
    }
    cloth_->appendLink(s.v0[e], s.v1[e], material);
    // m_bbending is a signed one-bit field (0 or -1); Bullet only tests it for non-zero.
    if (s.kind[e] == SpringKind::bend) cloth_->m_links[cloth_->m_links.size() - 1].m_bbending = -1;
  }
  for (Eigen::Index t = 0; t < model_->triangles.cols(); ++t)
    cloth_->appendFace(model_->triangles(0, t), model_->triangles(1, t), model_->triangles(2, t));
  cloth_->m_bUpdateRtCst = false;
  cloth_->updateConstants();
  for (std::size_t e = 0; e < s.size(); ++e) {  // our rest lengths, exactly
    btSoftBody::Link& link = cloth_->m_links[static_cast<int>(e)];
    link.m_rl = s.rest_length[e];
    link.m_c1 = link.m_rl * link.m_rl;
  }
  for (int i = 0; i < n; ++i) {
    btSoftBody::Node& node = cloth_->m_nodes[i];
    node.m_x = node.m_q = to_bullet(initial.x.col(i));
    node.m_v = to_bullet(initial.v.col(i));
  }
  btSoftBody::Config& cfg = cloth_->m_cfg;
  cfg.piterations = options_.iterations;
  cfg.kDP = 1.0 - std::exp(-options_.air_damping * options_.dt);  // global damping per substep
  cfg.kDG = cfg.kLF = 0.0;                                        // no aerodynamics
  cfg.kDF = 1.0;   // friction = collider friction (Bullet's own model, not Coulomb)
  cfg.kCHR = cfg.kKHR = 1.0;  // full contact hardness, also against kinematic bodies
  cfg.collisions = btSoftBody::fCollision::SDF_RS;
  cloth_->getCollisionShape()->setMargin(options_.margin);
  cloth_->setActivationState(DISABLE_DEACTIVATION);
  world_->addSoftBody(cloth_.get());
}

void BulletSoftBodySolver::read_state() {
  for (int i = 0; i < model_->particle_count(); ++i) {
    state_.x.col(i) = to_eigen(cloth_->m_nodes[i].m_x);
    state_.v.col(i) = to_eigen(cloth_->m_nodes[i].m_v);
  }
}

// Bullet's position solver stores no contact impulses. The force a collider exerted on a node in
// contact is estimated from the node's momentum change over the step beyond gravity,
// m ((v(n+1) - v(n)) / h - g), split along the contact normal and across it. It includes the
// node's link forces, so it is exact for a cloth resting flat and an estimate elsewhere.
void BulletSoftBodySolver::estimate_contact_forces(double h) {
  forces_.assign(forces_.size(), ColliderForce{});
  for (int k = 0; k < cloth_->m_rcontacts.size(); ++k) {
    const btSoftBody::RContact& contact = cloth_->m_rcontacts[k];
    const int c = colliders_->index_of(contact.m_cti.m_colObj);
    if (c < 0) continue;
    const int i = static_cast<int>(contact.m_node - &cloth_->m_nodes[0]);
    const Eigen::Vector3d force =
        model_->mass[i] * ((state_.v.col(i) - previous_velocity_.col(i)) / h - options_.gravity);
    const Eigen::Vector3d n = to_eigen(contact.m_cti.m_normal);
    const double normal = force.dot(n);
    forces_[c].normal += std::max(0.0, normal);
    forces_[c].friction += (force - normal * n).norm();
  }
}

void BulletSoftBodySolver::check_health(double h) {
  for (int i = 0; i < model_->particle_count(); ++i) {
    const bool finite = state_.x.col(i).allFinite() && state_.v.col(i).allFinite();
    if (finite && state_.v.col(i).norm() <= options_.max_speed) continue;
    std::ostringstream text;
    text.precision(4);
    text << "node " << i << " (" << model_->describe_particle(i) << ") "
         << (finite ? "moves faster than the runaway limit " + std::to_string(options_.max_speed) + " m/s"
                    : std::string("has a non-finite position or velocity"))
         << " after step " << state_.step_count << " (t = " << state_.time << " s, dt = " << h
         << " s). Try: a smaller dt, more iterations, or a larger voxel_size if the SDF cache is huge.";
    status_ = SolverStatus::unstable;
    message_ = text.str();
    return;
  }
}

std::unique_ptr<Solver> make_bullet_softbody_solver(std::string name, std::shared_ptr<const ClothModel> model,
                                                    const ClothState& initial, std::vector<Collider> colliders,
                                                    BulletSoftBodyOptions options) {
  return std::make_unique<BulletSoftBodySolver>(std::move(name), std::move(model), initial, std::move(colliders),
                                                std::move(options));
}

}  // namespace drapelab::bullet
