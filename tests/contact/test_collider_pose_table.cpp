// Collider poses set from outside (a host world): the table's poses over a substep, and a contact
// model that pushes particles where the table puts the collider, not where collider_pose(t) does.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "core/penalty_contact.hpp"
#include "drapelab/collider_pose_table.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/grid_cloth.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

TEST(ColliderPoseTable, EndsAreExactAndBetweenThemTheMotionIsRigidWithConstantVelocities) {
  ColliderSubstepMotion m;
  m.start.translation() = Eigen::Vector3d(1.0, 2.0, 3.0);
  m.start.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()).toRotationMatrix();
  m.velocity = {0.5, 0.0, -1.0};         // m/s
  m.angular_velocity = {0.0, 2.0, 0.0};  // rad/s
  const double t0 = 0.25, h = 0.01;      // s
  m.end = m.start;
  m.end.translation() += h * m.velocity;
  m.end.linear() =
      Eigen::AngleAxisd(2.0 * h, Eigen::Vector3d::UnitY()).toRotationMatrix() * m.start.linear();
  ColliderPoseTable table(1);
  table.set_substep(t0, t0 + h);
  table.set(0, m);
  EXPECT_TRUE(table.at(0, t0).pose.isApprox(m.start, 0.0));  // the host's poses, bit for bit
  EXPECT_TRUE(table.at(0, t0 + h).pose.isApprox(m.end, 0.0));
  const ColliderKinematics middle = table.at(0, t0 + 0.5 * h);
  EXPECT_LT((middle.pose.translation() - (m.start.translation() + 0.5 * h * m.velocity)).norm(),
            1e-15);
  const Eigen::Matrix3d half_turn =
      Eigen::AngleAxisd(h, Eigen::Vector3d::UnitY()).toRotationMatrix();
  EXPECT_LT((middle.pose.linear() - half_turn * m.start.linear()).cwiseAbs().maxCoeff(), 1e-15);
  // A point 1 m along x from the collider's origin moves with v + w x r = (0.5, 0, -1) + (0, 0,
  // -2).
  const Eigen::Vector3d p = middle.pose.translation() + Eigen::Vector3d::UnitX();
  EXPECT_LT((middle.point_velocity(p) - Eigen::Vector3d(0.5, 0.0, -3.0)).norm(), 1e-15);
  EXPECT_TRUE(middle.moving());
  EXPECT_FALSE(ColliderKinematics{}.moving());
}

// Two particles: one touching the ball where the table puts it, one touching it where the scene's
// (static) definition puts it. Only the first is pushed, and the damper sees the table's velocity.
TEST(ColliderPoseTable, ContactModelPushesWhereTheTablePutsTheCollider) {
  GridClothSpec spec = fixtures::flat_sheet(2, 1.0, {0.0, 1.0, 0.0}, 0.004);
  spec.thickness = 0.01;
  const ClothModel model = build_grid_cloth(spec);
  Collider ball;
  ball.shape = ColliderShape::sphere;
  ball.radius = 0.1;
  ball.friction = ball.static_friction = 0.0;  // normal force only
  const ContactParameters parameters{1000.0, 2.0};
  auto table = std::make_shared<ColliderPoseTable>(1);
  ColliderSubstepMotion moved;
  moved.start.translation() = moved.end.translation() = Eigen::Vector3d(2.0, 0.0, 0.0);
  moved.velocity = {0.0, 0.5, 0.0};  // m/s, rising
  table->set_substep(0.0, 1e-3);
  table->set(0, moved);
  const double depth = 0.004;                                                        // m
  Eigen::Matrix3Xd x = Eigen::Matrix3Xd::Constant(3, model.particle_count(), 10.0);  // far from all
  x.col(0) =
      Eigen::Vector3d(2.0, ball.radius + spec.thickness - depth, 0.0);  // on the table's ball
  x.col(1) =
      Eigen::Vector3d(0.0, ball.radius + spec.thickness - depth, 0.0);  // on the scene's ball
  const Eigen::Matrix3Xd v = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  std::vector<ColliderContactTotals> totals;

  const ContactModel hosted({ball}, parameters, spec.thickness, table);
  Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  hosted.add_contact_forces(model, 0.0, 1e-3, x, v, force, totals);
  // The particle is at rest and the surface rises at 0.5 m/s: it approaches at 0.5 m/s.
  const double expected =
      penalty_normal_force(depth, -0.5, parameters.stiffness, parameters.damping);  // N
  EXPECT_NEAR(force(1, 0), expected, 1e-12);
  EXPECT_EQ(force.col(1), Eigen::Vector3d::Zero());
  EXPECT_EQ(totals.at(0).contact_count, 1);
  EXPECT_TRUE(hosted.pose(0, 0.0).isApprox(moved.start, 0.0));

  const ContactModel bare({ball}, parameters, spec.thickness);
  force.setZero();
  bare.add_contact_forces(model, 0.0, 1e-3, x, v, force, totals);
  EXPECT_EQ(force.col(0), Eigen::Vector3d::Zero());
  EXPECT_NEAR(force(1, 1), parameters.stiffness * depth, 1e-12);  // static: no damping at rest
}

TEST(ColliderPoseTable, ContactModelRefusesATableOfTheWrongSize) {
  EXPECT_THROW(
      ContactModel({Collider{}}, ContactParameters{}, 0.01, std::make_shared<ColliderPoseTable>(2)),
      std::invalid_argument);
}

}  // namespace
}  // namespace drapelab
