// Self-collision's kernels alone: closest points, the penalty force and its Jacobian against finite
// differences, momentum kept by the self-contact forces, and the implicit solves with contacts
// between particles (the assembled and the matrix-free system give the same step).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "core/pair_penalty.hpp"
#include "core/proximity.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/implicit_euler.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "forces/spring_families.hpp"
#include "integrators/family_implicit.hpp"
#include "layered_cloth.hpp"
#include "self_collision/self_contact.hpp"

namespace drapelab {
namespace {

const Eigen::Vector3d kA(0, 0, 0), kB(1, 0, 0), kC(0, 0, 1);

TEST(Proximity, APointAboveTheInsideOfATriangleIsNearestItsFace) {
  const PointTriangleProximity near =
      closest_point_on_triangle(Eigen::Vector3d(0.2, 0.3, 0.25), kA, kB, kC);
  EXPECT_EQ(near.region, TriangleRegion::face);
  EXPECT_TRUE(near.closest.isApprox(Eigen::Vector3d(0.2, 0, 0.25)));
  EXPECT_NEAR(near.weights.sum(), 1.0, 1e-15);
  EXPECT_TRUE(
      (near.weights[0] * kA + near.weights[1] * kB + near.weights[2] * kC).isApprox(near.closest));
}

TEST(Proximity, APointBeyondAnEdgeOrACornerIsNearestThat) {
  const PointTriangleProximity edge =
      closest_point_on_triangle(Eigen::Vector3d(0.5, 0.1, -0.3), kA, kB, kC);
  EXPECT_EQ(edge.region, TriangleRegion::edge);
  EXPECT_EQ(edge.feature, 2);  // edge a-b, opposite corner c
  EXPECT_TRUE(edge.closest.isApprox(Eigen::Vector3d(0.5, 0, 0)));
  const PointTriangleProximity corner =
      closest_point_on_triangle(Eigen::Vector3d(1.5, 0.2, -0.5), kA, kB, kC);
  EXPECT_EQ(corner.region, TriangleRegion::corner);
  EXPECT_EQ(corner.feature, 1);
  EXPECT_TRUE(corner.closest.isApprox(kB));
}

TEST(Proximity, CrossedSegmentsAreNearestAtTheirCrossing) {
  const SegmentProximity near =
      closest_points_of_segments(Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(1, 0, 0),
                                 Eigen::Vector3d(0.5, 0.01, -1), Eigen::Vector3d(0.5, 0.01, 1));
  EXPECT_NEAR(near.s, 0.75, 1e-12);
  EXPECT_NEAR(near.t, 0.5, 1e-12);
  EXPECT_NEAR((near.on_first - near.on_second).norm(), 0.01, 1e-12);
  // Parallel segments: the pair lies at an end of one of them.
  const SegmentProximity parallel =
      closest_points_of_segments(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                 Eigen::Vector3d(0.2, 0.01, 0), Eigen::Vector3d(1.4, 0.01, 0));
  EXPECT_NEAR((parallel.on_first - parallel.on_second).norm(), 0.01, 1e-12);
  EXPECT_TRUE(parallel.s == 0.0 || parallel.s == 1.0 || parallel.t == 0.0 || parallel.t == 1.0);
}

TEST(PairPenalty, PushesWithinTheThicknessAndNeverPulls) {
  const double k = 2000.0, c = 0.5, h = 0.004;
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  const PairPenalty inside = pair_penalty(0.001 * up, Eigen::Vector3d::Zero(), up, h, k, c);
  EXPECT_NEAR(inside.force, k * 0.003, 1e-12);
  EXPECT_TRUE(inside.normal.isApprox(up));
  // Closing at 1 cm/s adds c * 0.01; separating fast enough would pull: clamped at zero.
  EXPECT_NEAR(pair_penalty(0.001 * up, -0.01 * up, up, h, k, c).force, k * 0.003 + c * 0.01, 1e-12);
  EXPECT_EQ(pair_penalty(0.001 * up, 100.0 * up, up, h, k, c).force, 0.0);
  EXPECT_EQ(pair_penalty(0.005 * up, Eigen::Vector3d::Zero(), up, h, k, c).force, 0.0);
}

// dF/dr of F(r) = fn(r, u) n(r) against central differences, at several separations and
// relative velocities.
TEST(PairPenalty, ItsJacobianMatchesFiniteDifferences) {
  const double k = 1500.0, c = 0.8, h = 0.005;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d r =
        Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized() *
        (0.001 + 0.003 * std::abs(unit(random)));
    const Eigen::Vector3d u = 0.01 * Eigen::Vector3d(unit(random), unit(random), unit(random));
    const PairPenalty at = pair_penalty(r, u, Eigen::Vector3d::UnitY(), h, k, c);
    if (at.force <= 0.0) continue;
    const Eigen::Matrix3d analytic = pair_force_position_derivative(at, u, k, c);
    Eigen::Matrix3d numeric;
    const double step = 1e-8;  // m
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d d = step * Eigen::Vector3d::Unit(j);
      const PairPenalty plus = pair_penalty(r + d, u, Eigen::Vector3d::UnitY(), h, k, c);
      const PairPenalty minus = pair_penalty(r - d, u, Eigen::Vector3d::UnitY(), h, k, c);
      numeric.col(j) = (plus.force * plus.normal - minus.force * minus.normal) / (2.0 * step);
    }
    EXPECT_LT((analytic - numeric).norm(), 1e-5 * analytic.norm()) << "trial " << trial;
    // The solve's Jacobian is the normal part: symmetric and negative semi-definite.
    const Eigen::Matrix3d solve = pair_jacobian_for_solve(at, k);
    EXPECT_TRUE(solve.isApprox(solve.transpose()));
    EXPECT_LE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(solve).eigenvalues().maxCoeff(), 1e-9);
  }
}

// A sheet crumpled at random: every self-contact force comes with its opposite, so the forces (and
// with friction, the frictions) sum to zero.
TEST(SelfContact, ForcesBetweenLayersSumToZero) {
  GridClothSpec spec;
  spec.nx = spec.ny = 15;
  spec.size = {0.3, 0.3};
  spec.thickness = 0.01;
  spec.mass = 0.05;
  const ClothModel model = build_grid_cloth(spec);
  Eigen::Matrix3Xd x = model.rest_positions;
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Fold it in three along x (0.1 m wide, 7 mm apart), with a few millimetres of noise.
  for (int i = 0; i < x.cols(); ++i) {
    const double along = x(0, i) + 0.15;  // m, 0 .. 0.3
    const int layer = std::min(2, static_cast<int>(along / 0.1));
    const double within = along - 0.1 * layer;
    x(0, i) = layer == 1 ? 0.1 - within : within;
    x(1, i) = 0.007 * layer + 0.002 * unit(random);
  }
  Eigen::Matrix3Xd v = 0.05 * Eigen::Matrix3Xd::Random(3, x.cols());
  SelfCollisionSettings settings;
  settings.enabled = true;
  settings.friction = 0.4;
  SelfContact contact(model, settings);
  Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Zero(3, x.cols());
  std::vector<WeightedContact> active;
  contact.add_forces(x, v, 1e-3, model.inverse_mass, force, &active);
  ASSERT_GT(contact.stats().contacts_last, 50);
  EXPECT_GT(contact.stats().friction_force_last, 0.0);
  EXPECT_LT(force.rowwise().sum().norm(), 1e-12 * force.colwise().norm().sum());
  EXPECT_EQ(static_cast<std::int64_t>(active.size()), contact.stats().contacts_last);
  for (const WeightedContact& w : active) {
    double sum = 0.0;
    for (int s = 0; s < 4; ++s) sum += w.particle[s] >= 0 ? w.weight[s] : 0.0;
    EXPECT_NEAR(sum, 0.0, 1e-12);
  }
}

// A flat sheet at rest touches nothing of itself.
TEST(SelfContact, AFlatSheetHasNoContacts) {
  GridClothSpec spec;
  spec.nx = spec.ny = 21;
  spec.thickness = 0.01;
  spec.mass = 0.1;
  const ClothModel model = build_grid_cloth(spec);
  SelfCollisionSettings settings;
  settings.enabled = true;
  SelfContact contact(model, settings);
  Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  contact.add_forces(model.rest_positions, Eigen::Matrix3Xd::Zero(3, model.particle_count()), 1e-3,
                     model.inverse_mass, force, nullptr);
  EXPECT_EQ(contact.stats().contacts_last, 0);
  EXPECT_EQ(force.norm(), 0.0);
}

// A sheet folded over itself, stepped once by implicit Euler through the assembled system and
// through the matrix-free one: both solve the same system with the same couplings.
TEST(SelfContactImplicit, AssembledAndMatrixFreeSolvesAgree) {
  GridClothSpec spec;
  spec.nx = spec.ny = 13;
  spec.size = {0.24, 0.24};
  spec.thickness = 0.008;
  spec.mass = 0.05;
  const ClothModel base = build_grid_cloth(spec);
  auto model = std::make_shared<ClothModel>(base);
  ClothState state{model->rest_positions, Eigen::Matrix3Xd::Zero(3, model->particle_count())};
  // Fold the half x > 0 back over the other, 5 mm above it.
  for (int i = 0; i < state.x.cols(); ++i)
    if (state.x(0, i) > 0.0) {
      state.x(0, i) = -state.x(0, i);
      state.x(1, i) += 0.005;
    }
  state.v.row(1).setConstant(-0.1);
  SpringDamperSettings settings;
  settings.integrator = Integrator::implicit_euler;
  settings.implicit.tolerance = 1e-10;
  settings.self_collision.enabled = true;
  settings.self_collision.stiffness = 500.0;
  settings.self_collision.damping = 0.05;
  settings.self_collision.friction = 0.0;
  Eigen::Matrix3Xd x_out[2];
  for (const bool fast : {true, false}) {
    settings.fast_springs = fast;
    SpringDamperSolver solver("ours", model, state, settings);
    EXPECT_EQ(solver.uses_fast_springs(), fast);
    solver.step(2e-3);
    ASSERT_EQ(solver.status(), SolverStatus::ok);
    EXPECT_GT(solver.self_contact_stats()->contacts_total, 100);
    x_out[fast ? 0 : 1] = solver.state().x;
  }
  const double moved = (x_out[0] - state.x).norm();
  EXPECT_LT((x_out[0] - x_out[1]).norm(), 1e-6 * moved);
}

// Random couplings (one with a pinned particle) in both systems: the same dv, and the matrix-free
// operator stays symmetric and positive: q . A p = p . A q, p . A p > 0.
TEST(SelfContactImplicit, CoupledSystemsAgreeAndStaySymmetric) {
  GridClothSpec spec;
  spec.nx = 11;
  spec.ny = 9;
  spec.mass = 0.1;
  spec.pins = {PinNamed{"corners"}};
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const auto families = SpringFamilies::build(*model);
  const int n = model->particle_count();
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> particle(0, n - 1);
  std::vector<WeightedContact> couplings;
  for (int e = 0; e < 25; ++e) {
    WeightedContact w;
    const double a = std::abs(unit(random)), b = (1.0 - a) * std::abs(unit(random));
    w.particle = {particle(random), particle(random), particle(random), particle(random)};
    if (e == 0) w.particle[1] = 0;  // a pinned corner
    w.weight = {1.0, -a, -b, -(1.0 - a - b)};
    w.normal = Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized();
    w.stiffness = 800.0;
    w.damping = 0.1;
    couplings.push_back(w);
  }
  const Eigen::Matrix3Xd x = model->rest_positions;
  const Eigen::Matrix3Xd v = 0.1 * Eigen::Matrix3Xd::Random(3, n);
  const Eigen::Matrix3Xd force = 0.01 * Eigen::Matrix3Xd::Random(3, n);
  const ImplicitSolveSettings tight{1e-12, 2000};
  ImplicitEulerSystem assembled(*model, tight);
  FamilyImplicitSystem matrix_free(*model, *families, tight);
  Eigen::Matrix3Xd dv_assembled(3, n), dv_free(3, n);
  assembled.solve(*model, x, v, force, 1e-3, 0.0, {}, {}, couplings, dv_assembled);
  matrix_free.solve(*model, x, v, force, 1e-3, 0.0, {}, {}, couplings, dv_free);
  EXPECT_LT((dv_assembled - dv_free).norm(), 1e-8 * dv_free.norm());
  EXPECT_EQ(dv_free.col(0).norm(), 0.0);  // pinned
  Eigen::Matrix3Xd p = Eigen::Matrix3Xd::Random(3, n), q = Eigen::Matrix3Xd::Random(3, n);
  for (int i = 0; i < n; ++i)
    if (model->is_pinned(i)) p.col(i).setZero(), q.col(i).setZero();
  const double qap = (q.array() * matrix_free.apply(p).array()).sum();
  const double paq = (p.array() * matrix_free.apply(q).array()).sum();
  EXPECT_NEAR(qap, paq, 1e-10 * std::abs(qap));
  EXPECT_GT((p.array() * matrix_free.apply(p).array()).sum(), 0.0);
}

}  // namespace
}  // namespace drapelab
