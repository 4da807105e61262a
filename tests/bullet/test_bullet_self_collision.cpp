// Bullet's self-collision switched on from cloth.self_collision (docs/bullet.md,
// "Self-collision"): two small sheets stacked in one cloth drop onto a floor. The deformable
// cloth keeps a turned-over top sheet 2 x margin above the bottom one and lets it through without
// self-collision; Bullet 3.24 culls layers that face the same way, and its classic cloth has no
// self-collision at all, so there the layers end in one plane either way.
#include <gtest/gtest.h>

#include <cstdio>

#include "drapelab/bullet/bullet_deformable_solver.hpp"
#include "drapelab/bullet/bullet_softbody_solver.hpp"
#include "fixtures/colliders.hpp"
#include "stacked_sheets.hpp"

namespace drapelab {
namespace {

constexpr double kMargin = 0.005;       // m, the soft bodies' margin (the cloth's thickness)
constexpr double kStep = 5e-4;          // s
constexpr double kSettleTime = 0.6;     // s: the sheets fall 3 and 6 cm and come to rest
constexpr double kAirDamping = 4.0;     // 1/s, so that the undamped sheets settle
constexpr double kBottomHeight = 0.03;  // m above the floor
constexpr double kGap = 0.03;           // m between the sheets at the start

fixtures::StackedSheets sheets(bool top_upside_down) {
  return fixtures::stacked_sheets(9, 0.3, 0.05, kBottomHeight, kGap, top_upside_down);
}

SelfCollisionSettings self_collision(bool enabled) {
  SelfCollisionSettings settings;
  settings.enabled = enabled;
  settings.thickness = kMargin;
  return settings;
}

ClothState settle(Solver& solver) {
  for (int k = 0; k < static_cast<int>(kSettleTime / kStep); ++k) solver.step(kStep);
  EXPECT_EQ(solver.status(), SolverStatus::ok) << solver.message();
  return solver.state();
}

ClothState settle_deformable(const fixtures::StackedSheets& s, bool enabled) {
  bullet::BulletDeformableOptions options;
  options.dt = kStep;
  options.margin = options.voxel_size = kMargin;
  options.air_damping = kAirDamping;
  options.self_collision = self_collision(enabled);
  auto solver = bullet::make_bullet_deformable_solver("d", s.model, s.initial,
                                                      {fixtures::floor_collider()}, options);
  return settle(*solver);
}

ClothState settle_classic(const fixtures::StackedSheets& s, bool enabled) {
  bullet::BulletSoftBodyOptions options;
  options.dt = kStep;
  options.iterations = 4;
  options.margin = options.voxel_size = kMargin;
  options.air_damping = kAirDamping;
  options.self_collision = self_collision(enabled);
  auto solver = bullet::make_bullet_softbody_solver("c", s.model, s.initial,
                                                    {fixtures::floor_collider()}, options);
  return settle(*solver);
}

void print(const char* what, const fixtures::StackedSheets& s, const ClothState& state) {
  std::printf("%s: mean gap %.5f m, lowest top above highest bottom %.5f m\n", what,
              fixtures::mean_layer_gap(s, state),
              fixtures::lowest_top_above_highest_bottom(s, state));
}

TEST(BulletSelfCollision, DeformableKeepsATurnedOverSheetTwoMarginsAboveTheOther) {
  const auto s = sheets(/*top_upside_down=*/true);
  const ClothState on = settle_deformable(s, true);
  print("deformable, on", s, on);
  // Measured: mean gap 2.29 margins (the top sheet is not quite flat), lowest 1.99 margins.
  EXPECT_NEAR(fixtures::mean_layer_gap(s, on), 2.0 * kMargin, 0.5 * kMargin);
  EXPECT_GT(fixtures::lowest_top_above_highest_bottom(s, on), 1.5 * kMargin);
}

TEST(BulletSelfCollision, DeformableLetsTheSheetThroughWithoutSelfCollision) {
  const auto s = sheets(/*top_upside_down=*/true);
  const ClothState off = settle_deformable(s, false);
  print("deformable, off", s, off);
  EXPECT_NEAR(fixtures::mean_layer_gap(s, off), 0.0, 0.1 * kMargin);
}

// Bullet tests a group of faces against itself only when their normals spread over more than a
// half-space (its normal-cone culling), so two layers facing the same way are never tested.
TEST(BulletSelfCollision, DeformableCullsLayersThatFaceTheSameWay) {
  const auto s = sheets(/*top_upside_down=*/false);
  const ClothState on = settle_deformable(s, true);
  print("deformable, on, same way up", s, on);
  EXPECT_NEAR(fixtures::mean_layer_gap(s, on), 0.0, 0.1 * kMargin);
}

TEST(BulletSelfCollision, ClassicClothHasNoSelfCollision) {
  const auto s = sheets(/*top_upside_down=*/true);
  const ClothState on = settle_classic(s, true);
  const ClothState off = settle_classic(s, false);
  print("classic, on", s, on);
  print("classic, off", s, off);
  EXPECT_NEAR(fixtures::mean_layer_gap(s, on), 0.0, 0.1 * kMargin);
  EXPECT_EQ(on.x, off.x);  // the switch changes nothing
}

}  // namespace
}  // namespace drapelab
