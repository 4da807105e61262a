// The classic cloth solver's class, shared by its implementation and the diagnostics that tests
// use.
#pragma once

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>

#include <memory>
#include <string>
#include <vector>

#include "bullet_cloth_solver.hpp"
#include "bullet_colliders.hpp"
#include "drapelab/bullet/bullet_softbody_solver.hpp"

namespace drapelab::bullet {

class BulletSoftBodySolver final : public BulletClothSolver {
 public:
  BulletSoftBodySolver(std::string name, std::shared_ptr<const ClothModel> model,
                       const ClothState& initial, std::vector<Collider> colliders,
                       BulletSoftBodyOptions options);
  ~BulletSoftBodySolver() override;

  void step(double h) override;
  const ClothState& state() const override { return state_; }
  const std::string& name() const override { return name_; }
  SolverType type() const override { return SolverType::bullet_softbody; }
  SolverStatus status() const override { return status_; }
  const std::string& message() const override { return message_; }
  std::vector<ColliderForce> collider_forces() const override { return forces_; }

  const btSoftBody& cloth() const override { return *cloth_; }
  const KinematicColliders& colliders() const override { return *colliders_; }

 private:
  static void before_substep(btDynamicsWorld* world, btScalar h);
  void build_cloth(const ClothState& initial);
  void read_state();
  void estimate_contact_forces(double h);
  void check_health(double h);

  std::string name_;
  std::shared_ptr<const ClothModel> model_;
  BulletSoftBodyOptions options_;
  ClothState state_;
  Eigen::Matrix3Xd previous_velocity_;
  std::vector<ColliderForce> forces_;
  std::shared_ptr<ColliderPoseTable> body_poses_;  // this world's dynamic bodies, for constraints
  SolverStatus status_ = SolverStatus::ok;
  std::string message_;
  double substep_start_ = 0.0;  // s
  Wind wind_{options_.air};     // the air's wind over time

  // Bullet's world and its parts; declared in construction order, destroyed in reverse.
  btSoftBodyRigidBodyCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_{&configuration_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver constraint_solver_;
  std::unique_ptr<btSoftRigidDynamicsWorld> world_;
  std::unique_ptr<KinematicColliders> colliders_;
  std::unique_ptr<btSoftBody> cloth_;
};

}  // namespace drapelab::bullet
