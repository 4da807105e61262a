// Bullet's classic cloth built from our model: node order, masses, pins, rest lengths, links; the
// collider conversion against FCL; free fall, the hanging chain, rest on a sphere at the margin,
// and kinematic colliders posed exactly as every other solver sees them.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "drapelab/bullet/bullet_deformable_solver.hpp"
#include "drapelab/bullet/bullet_diagnostics.hpp"
#include "drapelab/bullet/bullet_softbody_solver.hpp"
#include "drapelab/collision_metrics.hpp"
#include "drapelab/contact_fcl.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "fixtures/chains.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

using bullet::BulletSoftBodyOptions;

BulletSoftBodyOptions options_for(double dt, double margin) {
  BulletSoftBodyOptions options;
  options.dt = dt;
  options.margin = margin;
  options.voxel_size = margin;
  return options;
}

// docs/bullet.md, "Masses, pins and rest lengths": our rest lengths, not the start's, and mass-0
// pins.
TEST(BulletBridge, ClothHasOurNodesMassesPinsRestLengthsAndLinks) {
  GridClothSpec spec = fixtures::bullet_test_sheet(7, 0.6, {0, 1, 0}, 0.49);
  spec.pins = {PinNamed{"corners"}};
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const ClothState initial = initial_grid_state(*model, spec, 0.003, 5);  // perturbed start
  const double dt = 1e-3;
  const auto solver =
      bullet::make_bullet_softbody_solver("b", model, initial, {}, options_for(dt, 0.01));
  const auto layout = bullet::bullet_cloth_layout(*solver);
  ASSERT_TRUE(layout.has_value());
  ASSERT_EQ(layout->positions.cols(), model->particle_count());
  EXPECT_EQ(layout->positions, initial.x);  // node i is particle i, at its start position
  for (int i = 0; i < model->particle_count(); ++i)
    EXPECT_DOUBLE_EQ(layout->inverse_mass[i], model->is_pinned(i) ? 0.0 : 1.0 / model->mass[i])
        << i;
  const SpringSet& s = model->springs;
  ASSERT_EQ(layout->link_v0.size(), s.size());
  for (std::size_t e = 0; e < s.size(); ++e) {
    EXPECT_EQ(layout->link_v0[e], s.v0[e]);
    EXPECT_EQ(layout->link_v1[e], s.v1[e]);
    EXPECT_EQ(layout->rest_length[e], s.rest_length[e]);  // ours, not the perturbed start's
    EXPECT_EQ(layout->bending[e], s.kind[e] == SpringKind::bend);
    const double w = model->inverse_mass[s.v0[e]] + model->inverse_mass[s.v1[e]];
    EXPECT_NEAR(layout->link_stiffness[e], bullet::mapped_link_stiffness(s.ks[e], w, dt, 1), 1e-15);
  }
  EXPECT_EQ(layout->faces, model->triangles.cols());
  EXPECT_DOUBLE_EQ(layout->margin, 0.01);
}

// docs/bullet.md, "Mapping our parameters to the classic cloth".
TEST(BulletBridge, StiffnessMappingMatchesItsClosedForm) {
  // One sweep: kLST = x / (1 + x) with x = ks w h^2; n sweeps compound to the same total move.
  const double x = 200.0 * 100.0 * 1e-6;  // ks 200 N/m, w 100 /kg, h 1 ms
  EXPECT_NEAR(bullet::mapped_link_stiffness(200.0, 100.0, 1e-3, 1), x / (1 + x), 1e-15);
  const double k4 = bullet::mapped_link_stiffness(200.0, 100.0, 1e-3, 4);
  EXPECT_NEAR(1.0 - std::pow(1.0 - k4, 4), x / (1 + x), 1e-15);
  EXPECT_EQ(bullet::mapped_link_stiffness(200.0, 0.0, 1e-3, 1), 0.0);  // both ends pinned
}

// Bullet's signed distance to each shape (with our small edge margin) agrees with FCL's exact one.
TEST(BulletBridge, ColliderSignedDistanceAgreesWithFcl) {
  const double edge_margin = 1e-3;
  std::vector<Collider> shapes(5);
  shapes[0].shape = ColliderShape::sphere;
  shapes[0].radius = 0.3;
  shapes[1].shape = ColliderShape::cylinder;
  shapes[1].radius = 0.4;
  shapes[1].height = 0.6;
  shapes[1].axis = Eigen::Vector3d(0.3, 1, 0.1).normalized();
  shapes[2].shape = ColliderShape::capsule;
  shapes[2].radius = 0.1;
  shapes[2].height = 0.5;
  shapes[2].axis = Eigen::Vector3d::UnitX();
  shapes[3].shape = ColliderShape::box;
  shapes[3].half_extents = {0.5, 0.2, 0.3};
  shapes[4].shape = ColliderShape::plane;
  shapes[4].normal = Eigen::Vector3d(0.2, 1, 0).normalized();
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double r = 0.005;  // the FCL query sphere's radius
  const ParticleContactQuery query(r);
  for (Collider& c : shapes) {
    SCOPED_TRACE(collider_shape_name(c.shape));
    c.center = {0.1, 0.7, -0.2};
    c.rotation = {20, 35, -10};
    const FclCollider fcl = make_fcl_collider(c);
    const Eigen::Isometry3d pose = collider_pose(c, 0.0) * fcl.shape_in_collider;
    // Rounded edges (boxes, cylinders) move the surface by at most the margin's corner cut.
    const bool rounded = c.shape == ColliderShape::box || c.shape == ColliderShape::cylinder;
    const double tolerance = rounded ? 1.5 * edge_margin : 1e-6;
    int compared = 0;
    for (int trial = 0; trial < 100000 && compared < 300; ++trial) {
      const Eigen::Vector3d p = c.center + 0.8 * Eigen::Vector3d(u(random), u(random), u(random));
      const double fcl_distance =
          query.clearance(fcl, pose, p) + r;        // signed distance of the point
      if (std::abs(fcl_distance) > 0.05) continue;  // near the surface only
      EXPECT_NEAR(bullet::bullet_signed_distance(c, 0.0, p, edge_margin), fcl_distance, tolerance)
          << p.transpose();
      ++compared;
    }
    EXPECT_GT(compared, 100);
  }
}

TEST(BulletBridge, FreeFallFollowsSymplecticEulerLikeOurs) {
  GridClothSpec spec = fixtures::bullet_test_sheet(5, 0.4, {0, 2, 0}, 0.1);
  spec.stretch = spec.shear = spec.bend = {0.0, 0.0};  // no spring acts: a free fall
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const ClothState initial = initial_grid_state(*model, spec, 0.0, 0);
  const double h = 1.0 / 600;  // s, exactly representable as a float? no: Bullet rounds h to float
  auto bullet_solver =
      bullet::make_bullet_softbody_solver("b", model, initial, {}, options_for(h, 0.01));
  SpringDamperSolver ours("s", model, initial, {});
  const int n = 300;
  for (int k = 0; k < n; ++k) {
    bullet_solver->step(h);
    ours.step(h);
  }
  const double expected = 9.81 * h * h * n * (n + 1) / 2.0;  // V1, symplectic Euler
  for (int i = 0; i < model->particle_count(); ++i) {
    const double bullet_drop = initial.x(1, i) - bullet_solver->state().x(1, i);
    const double our_drop = initial.x(1, i) - ours.state().x(1, i);
    // Bullet hands the soft-body solver float(h): a relative error of about 1e-8 in h.
    EXPECT_NEAR(bullet_drop, expected, 1e-6 * expected);
    EXPECT_NEAR(our_drop, expected, 1e-12 * expected);
    EXPECT_NEAR(bullet_drop, our_drop, 1e-6 * expected);
  }
}

// V2 for Bullet's position solver: it has no spring constant, so the chain's extension measures how
// far the mapped link stiffness is from Hooke's law. Within 5 % where ks w h^2 <= 0.1.
TEST(BulletBridge, HangingChainStaysWithinFivePercentOfHookeWhereTheMappingHolds) {
  const GridClothSpec spec = fixtures::hanging_chain(0.0);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const double w = 2.0 / 0.01;        // 1/kg, two free particles of 10 g
  for (double ratio : {0.01, 0.1}) {  // ks w h^2
    const double h = std::sqrt(ratio / (100.0 * w));
    BulletSoftBodyOptions options = options_for(h, 0.01);
    options.air_damping = 3.0;  // 1/s, to settle
    auto solver = bullet::make_bullet_softbody_solver(
        "b", model, initial_grid_state(*model, spec, 0.0, 0), {}, options);
    for (int k = 0; k < static_cast<int>(20.0 / h); ++k) solver->step(h);
    const auto& x = solver->state().x;
    double extension = 0.0;
    for (int j = 0; j < 10; ++j) extension += (x.col(j + 1) - x.col(j)).norm() - 0.05;
    const double hooke = 0.053955;  // (m g / k) N (N + 1) / 2
    const double departure = extension / hooke;
    RecordProperty("bullet_over_hooke_at_" + std::to_string(ratio), std::to_string(departure));
    std::printf("ks w h^2 = %.2f: Bullet's chain stretches %.4f of Hooke's law\n", ratio,
                departure);
    EXPECT_NEAR(departure, 1.0, 0.05) << ratio;
  }
}

// docs/bullet.md, "Soft-rigid contact through the signed-distance cache": the cloth rests one
// margin off the surface.
TEST(BulletBridge, ClothRestsOnASphereOneMarginOff) {
  const double radius = 0.2, margin = 0.01;
  GridClothSpec spec = fixtures::bullet_test_sheet(15, 0.5, {0, 0.5 + radius + 0.05, 0}, 0.05);
  spec.stretch = {200.0, 0.0};
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  Collider ball;
  ball.shape = ColliderShape::sphere;
  ball.center = {0, 0.5, 0};
  ball.radius = radius;
  BulletSoftBodyOptions options = options_for(1.0 / 1200, margin);
  options.voxel_size = 0.005;
  options.air_damping = 2.0;
  auto solver = bullet::make_bullet_softbody_solver(
      "b", model, initial_grid_state(*model, spec, 0.0, 0), {ball}, options);
  for (int k = 0; k < 2400; ++k) solver->step(1.0 / 1200);
  ASSERT_EQ(solver->status(), SolverStatus::ok) << solver->message();
  // Every node keeps at least the margin from the sphere (to the SDF cell's accuracy), and the cap
  // of nodes on top, where the cloth lies on the sphere, sits at the margin.
  int on_top = 0;
  for (int i = 0; i < model->particle_count(); ++i) {
    const Eigen::Vector3d offset = solver->state().x.col(i) - ball.center;
    const double distance = offset.norm();
    EXPECT_GT(distance, radius + margin - options.voxel_size) << i;
    if (std::hypot(offset.x(), offset.z()) > 0.08 || offset.y() < 0.0) continue;
    EXPECT_NEAR(distance, radius + margin, 0.2 * margin) << i;
    ++on_top;
  }
  EXPECT_GT(on_top, 10);
}

TEST(BulletBridge, KinematicCollidersArePosedLikeEverySolverSeesThem) {
  Collider arm;
  arm.shape = ColliderShape::capsule;
  arm.center = {0, 0.5, 0};
  arm.axis = Eigen::Vector3d::UnitX();
  arm.motion.keyframes = {{0.0, {0, 0.5, 0}, {0, 0, 0}}, {0.05, {0.1, 0.6, 0}, {0, 45, 10}}};
  Collider ball;
  ball.shape = ColliderShape::sphere;
  ball.center = {0.5, 0.2, 0};
  ball.motion.velocity = {0, 1, 0};
  ball.motion.angular_velocity = {0, 90, 0};
  GridClothSpec spec = fixtures::bullet_test_sheet(5, 0.2, {0, 2, 0}, 0.01);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const double h = 1e-3;
  bullet::BulletDeformableOptions deformable_options;
  deformable_options.dt = h;
  deformable_options.margin = deformable_options.voxel_size = 0.01;
  std::unique_ptr<Solver> solvers[] = {
      bullet::make_bullet_softbody_solver("b", model, initial_grid_state(*model, spec, 0.0, 0),
                                          {arm, ball}, options_for(h, 0.01)),
      bullet::make_bullet_deformable_solver("d", model, initial_grid_state(*model, spec, 0.0, 0),
                                            {arm, ball}, deformable_options)};
  for (auto& solver : solvers) {
    for (int k = 1; k <= 80; ++k) {
      solver->step(h);
      const double t = k * h;  // the end of the substep just taken
      const auto poses = bullet::bullet_collider_poses(*solver);
      ASSERT_EQ(poses.size(), 2u);
      EXPECT_LT((poses[0].matrix() - collider_pose(arm, t).matrix()).cwiseAbs().maxCoeff(), 1e-12)
          << t;
      EXPECT_LT((poses[1].matrix() - collider_pose(ball, t).matrix()).cwiseAbs().maxCoeff(), 1e-12)
          << t;
    }
  }
}

}  // namespace
}  // namespace drapelab
