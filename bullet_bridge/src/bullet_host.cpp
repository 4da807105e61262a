// A solver stepped by a Bullet world as an action (see bullet_host.hpp).
#include "drapelab/bullet/bullet_host.hpp"

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>

#include <stdexcept>
#include <string>

#include "bullet_cloth_solver.hpp"
#include "bullet_math.hpp"

namespace drapelab::bullet {
namespace {

class BulletHostedSolver final : public BulletWorldSolver {
 public:
  BulletHostedSolver(std::unique_ptr<Solver> guest, std::shared_ptr<ColliderPoseTable> guest_poses,
                     const std::vector<Collider>& colliders, const Eigen::Vector3d& gravity,
                     double collider_margin)
      : guest_(std::move(guest)), guest_poses_(std::move(guest_poses)) {
    if (!guest_poses_ || guest_poses_->size() != colliders.size())
      throw std::invalid_argument("the hosted solver's pose table needs one entry per collider (" +
                                  std::to_string(colliders.size()) + ")");
    world_ = std::make_unique<btSoftRigidDynamicsWorld>(
        &dispatcher_, &broadphase_, &constraint_solver_, &configuration_, nullptr);
    world_->setGravity(to_bullet(gravity));
    world_->setInternalTickCallback(&BulletHostedSolver::before_substep, this, /*isPreTick=*/true);
    colliders_ = std::make_unique<KinematicColliders>(colliders, collider_margin, *world_);
  }
  ~BulletHostedSolver() override { colliders_.reset(); }

  void step(double h) override {
    if (guest_->status() != SolverStatus::ok) return;
    substep_start_ = guest_->state().time;
    world_->stepSimulation(h, 0);  // one substep: the pre-tick callback steps the guest
  }
  const ClothState& state() const override { return guest_->state(); }
  const std::string& name() const override { return guest_->name(); }
  SolverType type() const override { return guest_->type(); }
  SolverStatus status() const override { return guest_->status(); }
  const std::string& message() const override { return guest_->message(); }
  std::vector<ColliderForce> collider_forces() const override { return guest_->collider_forces(); }
  std::vector<std::pair<std::string, double>> phase_seconds() const override {
    return guest_->phase_seconds();
  }
  std::vector<std::pair<std::string, double>> counters() const override {
    return guest_->counters();
  }
  std::optional<EnergyLedger> energy_ledger() const override { return guest_->energy_ledger(); }
  std::optional<double> self_contact_energy() const override {
    return guest_->self_contact_energy();
  }

  const KinematicColliders& colliders() const override { return *colliders_; }

 private:
  // At the start of each substep [t, t + h], before the world moves its dynamic bodies: the
  // kinematic colliders take their poses, the guest steps against them (and against the dynamic
  // bodies moving at their present velocities), and the guest's loads go onto the dynamic bodies,
  // which the world then moves under gravity and those loads. Cloth and bodies thus exchange equal
  // and opposite impulses within the same substep.
  static void before_substep(btDynamicsWorld* world, btScalar h) {
    auto* self = static_cast<BulletHostedSolver*>(world->getWorldUserInfo());
    self->colliders_->move_to(self->substep_start_, self->substep_start_ + h);
    self->step_guest(h);
  }

  // Hands the guest the colliders as the world holds them over the substep, steps it, and puts its
  // loads on the dynamic bodies.
  void step_guest(double h) {
    colliders_->write_substep(substep_start_, h, *guest_poses_);
    guest_->step(h);
    colliders_->apply_loads(guest_->collider_forces());
  }

  std::unique_ptr<Solver> guest_;
  std::shared_ptr<ColliderPoseTable> guest_poses_;  // read by the guest's ContactModel
  double substep_start_ = 0.0;                      // s
  btSoftBodyRigidBodyCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_{&configuration_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver constraint_solver_;
  std::unique_ptr<btSoftRigidDynamicsWorld> world_;
  std::unique_ptr<KinematicColliders> colliders_;
};

}  // namespace

std::unique_ptr<Solver> host_in_bullet_world(std::unique_ptr<Solver> guest,
                                             std::shared_ptr<ColliderPoseTable> guest_poses,
                                             const std::vector<Collider>& colliders,
                                             const Eigen::Vector3d& gravity,
                                             double collider_margin) {
  return std::make_unique<BulletHostedSolver>(std::move(guest), std::move(guest_poses), colliders,
                                              gravity, collider_margin);
}

}  // namespace drapelab::bullet
