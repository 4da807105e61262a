// Bullet's deformable world as a drapelab Solver (see bullet_deformable_solver.hpp).
#include "drapelab/bullet/bullet_deformable_solver.hpp"

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletSoftBody/btDeformableBodySolver.h>
#include <BulletSoftBody/btDeformableGravityForce.h>
#include <BulletSoftBody/btDeformableMultiBodyConstraintSolver.h>
#include <BulletSoftBody/btDeformableMultiBodyDynamicsWorld.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>

#include <cmath>

#include "bullet_cloth_solver.hpp"
#include "bullet_colliders.hpp"
#include "bullet_math.hpp"
#include "deformable_contact_forces.hpp"
#include "deformable_self_collision.hpp"
#include "drapelab/bullet/parameter_mapping.hpp"
#include "drapelab/runaway_check.hpp"
#include "per_link_spring_force.hpp"
#include "soft_body_cloth.hpp"

namespace drapelab::bullet {
namespace {

class BulletDeformableSolver final : public BulletClothSolver {
 public:
  BulletDeformableSolver(std::string name, std::shared_ptr<const ClothModel> model,
                         const ClothState& initial, std::vector<Collider> colliders,
                         BulletDeformableOptions options)
      : name_(std::move(name)),
        model_(std::move(model)),
        options_(std::move(options)),
        state_(initial) {
    // As in Bullet's examples/DeformableDemo: the deformable solver inside the constraint solver.
    constraint_solver_.setDeformableSolver(&deformable_solver_);
    world_ = std::make_unique<btDeformableMultiBodyDynamicsWorld>(
        &dispatcher_, &broadphase_, &constraint_solver_, &configuration_, &deformable_solver_);
    world_->setGravity(to_bullet(options_.gravity));  // rigid bodies only; the cloth gets a force
    world_->setInternalTickCallback(&BulletDeformableSolver::before_substep, this,
                                    /*isPreTick=*/true);
    btSoftBodyWorldInfo& info = world_->getWorldInfo();
    info.m_gravity = to_bullet(options_.gravity);
    info.m_sparsesdf.Initialize();
    info.m_sparsesdf.setDefaultVoxelsz(options_.voxel_size);
    info.m_sparsesdf.Reset();
    // Self-collision scales the cloth's kDF; the colliders' friction is divided by it to keep
    // kDF x friction at the scene's (deformable_self_collision.hpp).
    const bool self_collision = options_.self_collision.enabled;
    const double friction_factor =
        self_collision ? deformable_self_friction_factor(options_.self_collision) : 1.0;
    // A concave mesh collider is given as its triangles, met by face contacts
    // (bullet_colliders.hpp).
    const bool triangles = deformable_meets_mesh_triangles(colliders);
    if (triangles) btGImpactCollisionAlgorithm::registerAlgorithm(&dispatcher_);
    colliders_ = std::make_unique<KinematicColliders>(
        colliders, options_.collider_margin, *world_, friction_factor,
        triangles ? BulletMeshShape::triangles : BulletMeshShape::convex_parts);
    // Soft constraints ending on a dynamic collider follow this world's body.
    body_poses_ = follow_own_bodies(options_.constraints, colliders.size());

    cloth_ = make_soft_body(
        info, *model_, initial, [](std::size_t) { return 1.0; },  // kLST unused here
        options_.attachments.get());
    btSoftBody::Config& cfg = cloth_->m_cfg;
    cfg.collisions =
        btSoftBody::fCollision::SDF_RD | btSoftBody::fCollision::SDF_RDN;  // node contacts
    // GImpact hands each triangle over as one reused shape, whose signed-distance cells the node
    // contacts would mix up: with a concave mesh in the scene, faces meet every collider instead.
    if (triangles)
      cfg.collisions = btSoftBody::fCollision::SDF_RD | btSoftBody::fCollision::SDF_RDF;
    cfg.kDF = 1.0;  // friction = collider friction
    cfg.kCHR = cfg.kKHR = 1.0;
    cfg.drag = 1.0 - std::exp(-options_.air_damping * options_.dt);
    cloth_->getCollisionShape()->setMargin(options_.margin);
    if (self_collision)
      enable_deformable_self_collision(*cloth_, options_.self_collision, options_.dt);
    else if (triangles)
      build_face_tree(*cloth_);  // the face contacts search it
    world_->addSoftBody(cloth_.get());
    if (options_.attachments)
      anchor_attached_nodes(
          *options_.attachments, [this](std::size_t c) { return colliders_->rigid_body(c); },
          *cloth_);
    springs_ = std::make_unique<PerLinkSpringForce>(model_->springs.ks, model_->springs.kd);
    gravity_ = std::make_unique<btDeformableGravityForce>(to_bullet(options_.gravity));
    world_->addForce(cloth_.get(), springs_.get());
    world_->addForce(cloth_.get(), gravity_.get());
    // Explicit elastic force, implicit damping
    // (docs/bullet.md, "What the deformable world computes").
    world_->setImplicit(false);
    forces_.assign(colliders.size(), ColliderForce{});
  }

  ~BulletDeformableSolver() override {
    world_->removeSoftBody(cloth_.get());
    colliders_.reset();
  }

  void step(double h) override {
    if (status_ != SolverStatus::ok) return;
    substep_start_ = state_.time;
    world_->stepSimulation(h, 0);
    if (options_.attachments) place_attached_nodes(*options_.attachments, state_.time + h, *cloth_);
    if (options_.constraints && options_.constraints->has_hard())
      project_node_constraints(*options_.constraints, *model_, state_.time + h, h, *cloth_, state_);
    state_.time += h;
    ++state_.step_count;
    read_soft_body_state(*cloth_, state_);
    deformable_contact_forces(deformable_solver_, *cloth_, *colliders_, h, forces_);
    if (const auto message =
            runaway_message(*model_, state_, options_.max_speed, h,
                            "a smaller dt (its elastic force is explicit: the same step bound "
                            "as our symplectic Euler holds), or softer springs.")) {
      status_ = SolverStatus::unstable;
      message_ = *message;
    }
  }

  const ClothState& state() const override { return state_; }
  const std::string& name() const override { return name_; }
  SolverType type() const override { return SolverType::bullet_deformable; }
  SolverStatus status() const override { return status_; }
  const std::string& message() const override { return message_; }
  std::vector<ColliderForce> collider_forces() const override { return forces_; }
  const btSoftBody& cloth() const override { return *cloth_; }
  const KinematicColliders& colliders() const override { return *colliders_; }

 private:
  static void before_substep(btDynamicsWorld* world, btScalar h) {
    auto* self = static_cast<BulletDeformableSolver*>(world->getWorldUserInfo());
    self->colliders_->move_to(self->substep_start_, self->substep_start_ + h);
    if (self->body_poses_)
      self->colliders_->write_substep(self->substep_start_, h, *self->body_poses_);
    if (self->options_.attachments)
      place_attached_nodes(*self->options_.attachments, self->substep_start_, *self->cloth_);
    if (self->options_.constraints && self->options_.constraints->has_soft())
      kick_soft_constraints(*self->options_.constraints, *self->model_, self->substep_start_, h,
                            *self->cloth_, self->state_, *self->colliders_);
    if (self->options_.air.enabled)
      kick_air(self->options_.air, self->wind_, *self->model_, self->substep_start_, h,
               *self->cloth_, self->state_);
  }

  std::string name_;
  std::shared_ptr<const ClothModel> model_;
  BulletDeformableOptions options_;
  ClothState state_;
  std::vector<ColliderForce> forces_;
  std::shared_ptr<ColliderPoseTable> body_poses_;  // this world's dynamic bodies, for constraints
  SolverStatus status_ = SolverStatus::ok;
  std::string message_;
  double substep_start_ = 0.0;  // s
  Wind wind_{options_.air};     // the air's wind over time

  btSoftBodyRigidBodyCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_{&configuration_};
  btDbvtBroadphase broadphase_;
  btDeformableBodySolver deformable_solver_;
  btDeformableMultiBodyConstraintSolver constraint_solver_;
  std::unique_ptr<btDeformableMultiBodyDynamicsWorld> world_;
  std::unique_ptr<KinematicColliders> colliders_;
  std::unique_ptr<PerLinkSpringForce> springs_;
  std::unique_ptr<btDeformableGravityForce> gravity_;
  std::unique_ptr<btSoftBody> cloth_;
};

}  // namespace

std::unique_ptr<Solver> make_bullet_deformable_solver(std::string name,
                                                      std::shared_ptr<const ClothModel> model,
                                                      const ClothState& initial,
                                                      std::vector<Collider> colliders,
                                                      BulletDeformableOptions options) {
  return std::make_unique<BulletDeformableSolver>(std::move(name), std::move(model), initial,
                                                  std::move(colliders), std::move(options));
}

}  // namespace drapelab::bullet
