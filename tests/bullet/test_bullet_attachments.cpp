// Pinned nodes carried by a collider (cloth.pins[].attach) in Bullet's two cloths: kinematic nodes
// placed on their collider before and after every substep.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <string>

#include "drapelab/attachments.hpp"
#include "drapelab/bullet/bullet_deformable_solver.hpp"
#include "drapelab/bullet/bullet_softbody_solver.hpp"
#include "drapelab/grid_cloth.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

// A 6 x 6 sheet whose top corners are pinned and carried by a small capsule 15 cm above it that
// moves and turns about two axes.
struct CarriedSheet {
  GridClothSpec spec = fixtures::bullet_test_sheet(6, 0.3, {0.0, 1.0, 0.0}, 0.05);
  Collider bar;
  std::shared_ptr<const ClothModel> model;
  ClothState initial;
  std::shared_ptr<const Attachments> attachments;
  CarriedSheet() {
    spec.pins = {PinIndex{0}, PinIndex{5}};
    bar.name = "bar";
    bar.shape = ColliderShape::capsule;
    bar.radius = 0.02;
    bar.height = 0.1;
    bar.center = {0.0, 1.15, 0.0};
    bar.motion.velocity = {0.2, 0.1, 0.0};            // m/s
    bar.motion.angular_velocity = {20.0, 90.0, 0.0};  // deg/s
    model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
    initial = initial_grid_state(*model, spec, 0.0, 0);
    attachments = std::make_shared<const Attachments>(
        make_attachments({bar}, {{0, 0}, {5, 0}}, initial.x, 0.0));
  }
};

// Steps `solver` for 0.5 s at h; the carried nodes must sit at their offsets in the bar's frame
// with the bar's point velocity after every step.
void expect_carried(Solver& solver, const CarriedSheet& sheet, double h) {
  double worst_position = 0.0, worst_velocity = 0.0;
  const int steps = static_cast<int>(std::lround(0.5 / h));
  for (int k = 0; k < steps; ++k) {
    solver.step(h);
    const double t = solver.state().time;
    for (std::size_t a = 0; a < sheet.attachments->list.size(); ++a) {
      const auto [position, velocity] = sheet.attachments->placement(a, t);
      const int i = sheet.attachments->list[a].particle;
      worst_position = std::max(worst_position, (solver.state().x.col(i) - position).norm());
      worst_velocity = std::max(worst_velocity, (solver.state().v.col(i) - velocity).norm());
    }
  }
  ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
  EXPECT_LT(worst_position, 1e-9);  // m
  EXPECT_LT(worst_velocity, 1e-9);  // m/s
  // The cloth came along: its free edge hangs within the sheet's size of the carried corners,
  // which moved 10 cm and more.
  const Eigen::Vector3d carried = 0.5 * (solver.state().x.col(0) + solver.state().x.col(5));
  const Eigen::Vector3d far = 0.5 * (solver.state().x.col(30) + solver.state().x.col(35));
  EXPECT_LT((far - carried).norm(), 0.3 * 1.1);
  EXPECT_GT((carried - Eigen::Vector3d(sheet.initial.x.col(0))).norm(), 0.1);
}

TEST(BulletAttachments, TheClassicClothsCarriedNodesFollowTheirCollider) {
  const CarriedSheet sheet;
  bullet::BulletSoftBodyOptions options;
  options.dt = 1e-4;
  options.margin = options.voxel_size = 0.01;
  options.attachments = sheet.attachments;
  const auto solver = bullet::make_bullet_softbody_solver("classic", sheet.model, sheet.initial,
                                                          {sheet.bar}, options);
  expect_carried(*solver, sheet, options.dt);
}

TEST(BulletAttachments, TheDeformableClothsCarriedNodesFollowTheirCollider) {
  const CarriedSheet sheet;
  bullet::BulletDeformableOptions options;
  options.dt = 2e-4;
  options.margin = options.voxel_size = 0.01;
  options.attachments = sheet.attachments;
  const auto solver = bullet::make_bullet_deformable_solver("deformable", sheet.model,
                                                            sheet.initial, {sheet.bar}, options);
  expect_carried(*solver, sheet, options.dt);
}

}  // namespace
}  // namespace drapelab
