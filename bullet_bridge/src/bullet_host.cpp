// A solver stepped by a Bullet world as an action (see bullet_host.hpp).
#include "drapelab/bullet/bullet_host.hpp"

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h>
#include <BulletDynamics/Dynamics/btActionInterface.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>

#include "bullet_colliders.hpp"
#include "bullet_math.hpp"

namespace drapelab::bullet {
namespace {

// Bullet calls updateAction once per substep, after it has posed the colliders for [t, t + h].
class GuestAction final : public btActionInterface {
 public:
  explicit GuestAction(Solver& guest) : guest_(guest) {}
  void updateAction(btCollisionWorld*, btScalar h) override { guest_.step(h); }
  void debugDraw(btIDebugDraw*) override {}

 private:
  Solver& guest_;
};

class BulletHostedSolver final : public Solver {
 public:
  BulletHostedSolver(std::unique_ptr<Solver> guest, const std::vector<Collider>& colliders,
                     const Eigen::Vector3d& gravity, double collider_margin)
      : guest_(std::move(guest)), action_(*guest_) {
    world_ = std::make_unique<btSoftRigidDynamicsWorld>(&dispatcher_, &broadphase_, &constraint_solver_,
                                                        &configuration_, nullptr);
    world_->setGravity(to_bullet(gravity));
    world_->setInternalTickCallback(&BulletHostedSolver::before_substep, this, /*isPreTick=*/true);
    colliders_ = std::make_unique<KinematicColliders>(colliders, collider_margin, *world_);
    world_->addAction(&action_);
  }
  ~BulletHostedSolver() override {
    world_->removeAction(&action_);
    colliders_.reset();
  }

  void step(double h) override {
    if (guest_->status() != SolverStatus::ok) return;
    substep_start_ = guest_->state().time;
    world_->stepSimulation(h, 0);  // one substep: pre-tick poses the colliders, the action steps the guest
  }
  const ClothState& state() const override { return guest_->state(); }
  const std::string& name() const override { return guest_->name(); }
  const std::string& type() const override { return guest_->type(); }
  SolverStatus status() const override { return guest_->status(); }
  const std::string& message() const override { return guest_->message(); }
  std::vector<ColliderForce> collider_forces() const override { return guest_->collider_forces(); }
  std::vector<std::pair<std::string, double>> phase_seconds() const override { return guest_->phase_seconds(); }
  std::vector<std::pair<std::string, double>> counters() const override { return guest_->counters(); }

 private:
  static void before_substep(btDynamicsWorld* world, btScalar h) {
    auto* self = static_cast<BulletHostedSolver*>(world->getWorldUserInfo());
    self->colliders_->move_to(self->substep_start_, self->substep_start_ + h);
  }

  std::unique_ptr<Solver> guest_;
  GuestAction action_;
  double substep_start_ = 0.0;  // s
  btSoftBodyRigidBodyCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_{&configuration_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver constraint_solver_;
  std::unique_ptr<btSoftRigidDynamicsWorld> world_;
  std::unique_ptr<KinematicColliders> colliders_;
};

}  // namespace

std::unique_ptr<Solver> host_in_bullet_world(std::unique_ptr<Solver> guest, const std::vector<Collider>& colliders,
                                             const Eigen::Vector3d& gravity, double collider_margin) {
  return std::make_unique<BulletHostedSolver>(std::move(guest), colliders, gravity, collider_margin);
}

}  // namespace drapelab::bullet
