// The mapping from our parameters to MuJoCo's (docs/mujoco.md, "The mapping"), formula by formula,
// without MuJoCo: contact references, geoms, and the sizes that keep MuJoCo 2.2's buffer under
// 2 GB.
#include <gtest/gtest.h>

#include "drapelab/mujoco/mujoco_mapping.hpp"

namespace drapelab::mujoco {
namespace {

TEST(MujocoMapping, ContactReferenceIsStiffnessAndDampingPerMass) {
  const ContactReference r = contact_reference(1000.0, 0.2, 2.5e-4);
  EXPECT_DOUBLE_EQ(r.stiffness, 4.0e6);
  EXPECT_DOUBLE_EQ(r.damping, 800.0);
  // Between two particles of mass m the pair's mass is m / 2; the mean of the two references is
  // then 2 k / m, which gives the pair k.
  const ContactReference pair = pair_contact_reference(1000.0, 0.2, 2.5e-4);
  EXPECT_DOUBLE_EQ(pair.stiffness * 2.5e-4 / 2.0, 1000.0);
  EXPECT_DOUBLE_EQ(pair.damping * 2.5e-4 / 2.0, 0.2);
}

TEST(MujocoMapping, CylinderCapsuleAndPlaneLieAlongTheirOwnAxes) {
  Collider cylinder;
  cylinder.shape = ColliderShape::cylinder;
  cylinder.radius = 0.09;
  cylinder.height = 0.5;
  cylinder.axis = Eigen::Vector3d::UnitX();
  const GeomShape geom = geom_shape(cylinder);
  EXPECT_EQ(geom.type, "cylinder");
  EXPECT_DOUBLE_EQ(geom.size.x(), 0.09);
  EXPECT_DOUBLE_EQ(geom.size.y(), 0.25);  // MuJoCo's half-height
  EXPECT_TRUE((geom.local * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitX(), 1e-12));

  Collider capsule = cylinder;
  capsule.shape = ColliderShape::capsule;
  capsule.axis = Eigen::Vector3d(0.0, 1.0, 1.0);
  const GeomShape along = geom_shape(capsule);
  EXPECT_EQ(along.type, "capsule");
  EXPECT_TRUE((along.local * Eigen::Vector3d::UnitZ())
                  .isApprox(Eigen::Vector3d(0.0, 1.0, 1.0).normalized(), 1e-12));

  Collider plane;
  plane.shape = ColliderShape::plane;
  plane.normal = Eigen::Vector3d::UnitY();
  const GeomShape ground = geom_shape(plane);
  EXPECT_EQ(ground.type, "plane");
  EXPECT_TRUE((ground.local * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));

  Collider box;
  box.shape = ColliderShape::box;
  box.half_extents = {0.5, 0.02, 0.3};
  EXPECT_EQ(geom_shape(box).size, box.half_extents);
}

TEST(MujocoMapping, MeshIsRefused) {
  Collider mesh;
  mesh.name = "mannequin";
  mesh.shape = ColliderShape::mesh;
  EXPECT_THROW(geom_shape(mesh), std::invalid_argument);
}

TEST(MujocoMapping, ContactCapacityFitsTheBuffer) {
  // A small cloth gets one contact per particle and 64 more.
  EXPECT_EQ(contact_capacity(0, 441, 3 * 441), 441 + 64);
  // The user's number is kept.
  EXPECT_EQ(contact_capacity(5, 441, 3 * 441), 5);
  // 65 x 65 and 129 x 129: the most that fit, under 2 GB with the model's other arrays.
  for (const std::int64_t side : {65, 129}) {
    const std::int64_t particles = side * side, dofs = 3 * particles;
    const std::int64_t capacity = contact_capacity(0, particles, dofs);
    EXPECT_LT(capacity, particles);
    EXPECT_LT(constraint_buffer_bytes(capacity, dofs) + 1024.0 * static_cast<double>(dofs),
              kBufferLimitBytes);
    EXPECT_GT(constraint_buffer_bytes(capacity + capacity / 10, dofs), 0.9 * kBufferLimitBytes);
  }
}

TEST(MujocoMapping, NewtonUpToItsDenseLimitThenConjugateGradient) {
  EXPECT_EQ(chosen_solver(ConstraintSolver::automatic, 3 * 441), ConstraintSolver::newton);
  EXPECT_EQ(chosen_solver(ConstraintSolver::automatic, 3 * 1681), ConstraintSolver::cg);
  EXPECT_EQ(chosen_solver(ConstraintSolver::pgs, 3 * 1681), ConstraintSolver::pgs);
}

}  // namespace
}  // namespace drapelab::mujoco
