// Implicit Euler's matrix-free solve on spring families (family_implicit.hpp) against the assembled
// sparse system (implicit_euler.hpp): the same matrix and right-hand side to rounding, the same
// solution to the CG tolerance, bitwise the same results for one and two threads, pins held.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "drapelab/grid_cloth.hpp"
#include "drapelab/implicit_euler.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "fixtures/colliders.hpp"
#include "fixtures/sheets.hpp"
#include "forces/spring_families.hpp"
#include "forces/spring_family_loops.hpp"
#include "integrators/family_implicit.hpp"

namespace drapelab {
namespace {

Eigen::Matrix3Xd random_field(int n, double scale, unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::Matrix3Xd field(3, n);
  for (int i = 0; i < n; ++i) field.col(i) = Eigen::Vector3d(u(random), u(random), u(random));
  return field;
}

double max_abs(const Eigen::Matrix3Xd& m) { return m.cwiseAbs().maxCoeff(); }

// One system, built both ways from the same state, force and contacts.
struct BothSystems {
  // 11 x 8 by default: offsets 11 + 1 and 2 x 11, rows shorter than the columns.
  explicit BothSystems(int nx = 11, int ny = 8) {
    spec = fixtures::stiff_sheet(nx, ny);
    model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
    families = SpringFamilies::build(*model);
    const int n = model->particle_count();
    // Stretched and compressed springs both: positions perturbed by up to 40 % of the spacing.
    state = initial_grid_state(*model, spec, 0.0, 1);
    state.x += random_field(n, 0.04, 3);
    for (int i = 0; i < n; ++i)
      if (model->is_pinned(i)) state.x.col(i) = model->rest_positions.col(i);
    state.v = random_field(n, 0.5, 4);
    for (int i = 0; i < n; ++i)
      if (model->is_pinned(i)) state.v.col(i).setZero();
    force = random_field(n, 0.01, 5);
    std::mt19937_64 random(6);
    for (int i = 3; i < n; i += 7) {
      if (model->is_pinned(i)) continue;
      const Eigen::Vector3d normal =
          random_field(1, 1.0, static_cast<unsigned>(100 + i)).col(0).normalized();
      contacts.push_back({i, normal});
    }
  }
  GridClothSpec spec;
  std::shared_ptr<const ClothModel> model;
  std::unique_ptr<SpringFamilies> families;
  ClothState state;
  Eigen::Matrix3Xd force;
  std::vector<ActiveContact> contacts;
  ContactParameters contact{1000.0, 0.2};
  double h = 1.0 / 240.0;  // s
  double air = 0.3;        // 1/s
};

// Both systems solved once from the same inputs, and the checks that they are one system: the same
// right-hand side, and A p equal on the moving particles (p zero on the pins, whose rows the
// assembled matrix keeps as I) while the matrix-free product is zero on the pins.
struct SolvedBoth {
  SolvedBoth(const BothSystems& inputs, ImplicitSolveSettings settings)
      : both(inputs),
        assembled(*inputs.model, settings),
        matrix_free(*inputs.model, *inputs.families, settings) {
    const int n = both.model->particle_count();
    dv_assembled.resize(3, n);
    dv_free.resize(3, n);
    assembled.solve(*both.model, both.state.x, both.state.v, both.force, both.h, both.air,
                    both.contact, both.contacts, {}, dv_assembled);
    matrix_free.solve(*both.model, both.state.x, both.state.v, both.force, both.h, both.air,
                      both.contact, both.contacts, {}, dv_free);
  }
  void expect_same_system(unsigned seed) {
    const int n = both.model->particle_count();
    const Eigen::Matrix3Xd rhs =
        Eigen::Map<const Eigen::Matrix3Xd>(assembled.right_hand_side().data(), 3, n);
    EXPECT_LT(max_abs(matrix_free.right_hand_side() - rhs), 1e-12 * max_abs(rhs));
    Eigen::Matrix3Xd p = random_field(n, 1.0, seed);
    for (int i = 0; i < n; ++i)
      if (both.model->is_pinned(i)) p.col(i).setZero();
    const Eigen::Matrix3Xd ap_free = matrix_free.apply(p);  // on the current thread count
    const Eigen::VectorXd ap_flat =
        assembled.matrix() * Eigen::Map<const Eigen::VectorXd>(p.data(), 3 * n);
    const Eigen::Matrix3Xd ap_assembled = Eigen::Map<const Eigen::Matrix3Xd>(ap_flat.data(), 3, n);
    double worst = 0.0;  // over the moving particles
    for (int i = 0; i < n; ++i) {
      if (both.model->is_pinned(i))
        EXPECT_EQ(ap_free.col(i).norm(), 0.0) << "a pinned row acts as zero";
      else
        worst = std::max(worst, (ap_free.col(i) - ap_assembled.col(i)).cwiseAbs().maxCoeff());
    }
    EXPECT_LT(worst, 1e-12 * max_abs(ap_assembled));
  }
  const BothSystems& both;
  ImplicitEulerSystem assembled;
  FamilyImplicitSystem matrix_free;
  Eigen::Matrix3Xd dv_assembled, dv_free;
};

TEST(FamilyImplicit, SameMatrixRightHandSideAndSolutionAsTheAssembledSystem) {
  BothSystems both;
  ASSERT_NE(both.families, nullptr);
  SolvedBoth solved(both, {1e-12, 5000});
  solved.expect_same_system(9);
  EXPECT_LT(max_abs(solved.dv_free - solved.dv_assembled), 1e-9 * max_abs(solved.dv_assembled));
  EXPECT_EQ(solved.matrix_free.stats().unconverged, 0);
  EXPECT_LE(solved.matrix_free.stats().residual_last, 1e-12);
}

// A sheet large enough for many 512-particle blocks and both threads (above the 4096-particle
// threshold): the products cross block and thread boundaries, where slot terms come from the block
// before and a run's first particles wait for the other thread.
TEST(FamilyImplicit, ManyBlocksOnTwoThreadsApplyTheAssembledMatrix) {
  BothSystems both(97, 97);
  ASSERT_GT(both.model->particle_count(), 4096);
  kernels::set_thread_count(2);
  SolvedBoth solved(both, {1e-3, 500});
  solved.expect_same_system(11);
  kernels::set_thread_count(1);
  EXPECT_EQ(solved.matrix_free.stats().unconverged, 0);
}

TEST(FamilyImplicit, StopsAtItsToleranceAndCountsLikeEigen) {
  BothSystems both;
  const int n = both.model->particle_count();
  for (double tolerance : {1e-3, 1e-8}) {
    FamilyImplicitSystem system(*both.model, *both.families, {tolerance, 1000});
    Eigen::Matrix3Xd dv(3, n);
    system.solve(*both.model, both.state.x, both.state.v, both.force, both.h, both.air,
                 both.contact, both.contacts, {}, dv);
    const double residual =
        (system.apply(dv) - system.right_hand_side()).norm() / system.right_hand_side().norm();
    EXPECT_LE(residual, tolerance * 1.0001);
    // The CG's updated residual drifts from the true one by rounding only.
    EXPECT_NEAR(residual, system.stats().residual_last, 1e-3 * tolerance);
    EXPECT_GT(system.stats().iterations_last, 0);
    // Started from the last solution, a second solve of the same system is already converged.
    system.solve(*both.model, both.state.x, both.state.v, both.force, both.h, both.air,
                 both.contact, both.contacts, {}, dv);
    EXPECT_EQ(system.stats().iterations_last, 0);
    EXPECT_EQ(system.stats().solves, 2);
  }
  // An iteration cap below what the tolerance needs is counted as unconverged.
  FamilyImplicitSystem capped(*both.model, *both.families, {1e-12, 2});
  Eigen::Matrix3Xd dv(3, n);
  capped.solve(*both.model, both.state.x, both.state.v, both.force, both.h, both.air, both.contact,
               both.contacts, {}, dv);
  EXPECT_EQ(capped.stats().unconverged, 1);
  EXPECT_EQ(capped.stats().iterations_last, 2);
  EXPECT_GT(capped.stats().residual_last, 1e-12);
}

// The solver picks the matrix-free solve on a grid and the assembled one without the fast path;
// both runs of a stiff sheet swinging from its pins at 1/60 s agree to the CG tolerance.
TEST(FamilyImplicit, SolverRunsAgreeWithTheAssembledPath) {
  GridClothSpec spec = fixtures::stiff_sheet(15, 15);
  spec.plane = GridPlane::xz;  // horizontal, held at two corners: it swings down like a pendulum
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  auto run = [&](bool fast) {
    SpringDamperSettings settings;
    settings.integrator = Integrator::implicit_euler;
    settings.implicit = {1e-11, 5000};
    settings.air_damping = 0.3;
    settings.fast_springs = fast;
    SpringDamperSolver solver("s", model, initial_grid_state(*model, spec, 1e-2, 3), settings);
    EXPECT_EQ(solver.family_implicit_system() != nullptr, fast);
    EXPECT_EQ(solver.implicit_system() != nullptr, !fast);
    for (int k = 0; k < 30; ++k) solver.step(1.0 / 60.0);
    EXPECT_EQ(solver.status(), SolverStatus::ok) << solver.message();
    EXPECT_EQ(solver.implicit_stats()->solves, 30);
    for (int i = 0; i < model->particle_count(); ++i)
      if (model->is_pinned(i)) {
        EXPECT_EQ(solver.state().x.col(i), model->rest_positions.col(i));
        EXPECT_EQ(solver.state().v.col(i).norm(), 0.0);
      }
    return solver.state();
  };
  const ClothState fast = run(true), assembled = run(false);
  const double swing = (assembled.x - model->rest_positions).cwiseAbs().maxCoeff();
  EXPECT_GT(swing, 0.05);  // m: it fell and swung
  EXPECT_LT((fast.x - assembled.x).cwiseAbs().maxCoeff(), 1e-7 * swing);
  EXPECT_LT((fast.v - assembled.v).cwiseAbs().maxCoeff(), 1e-6);
}

// A 97 x 97 sheet (above the threading threshold) pressed onto a sphere: implicit steps with
// contacts give the same bits on one and two threads.
TEST(FamilyImplicit, OneAndTwoThreadsGiveIdenticalBits) {
  const GridClothSpec spec =
      fixtures::flat_sheet(97, 1.0, {0.0, 0.79, 0.0}, 0.25);  // 1 cm into the top of the ball
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const Collider ball = fixtures::ball_collider();
  SpringDamperSettings settings;
  settings.integrator = Integrator::implicit_euler;
  settings.implicit = {1e-6, 500};
  settings.air_damping = 0.1;
  settings.contacts = std::make_shared<const ContactModel>(
      std::vector<Collider>{ball}, ContactParameters{1000.0, 0.2}, spec.thickness);
  auto run = [&](int threads) {
    kernels::set_thread_count(threads);
    SpringDamperSolver solver("s", model, initial_grid_state(*model, spec, 0.002, 3), settings);
    for (int k = 0; k < 4; ++k) solver.step(1.0 / 240.0);
    kernels::set_thread_count(1);
    EXPECT_EQ(solver.status(), SolverStatus::ok) << solver.message();
    EXPECT_GT(solver.implicit_stats()->iterations_total, 4);
    return solver.state();
  };
  const ClothState one = run(1), two = run(2);
  EXPECT_TRUE((one.x.array() == two.x.array()).all()) << "thread count changed the positions";
  EXPECT_TRUE((one.v.array() == two.v.array()).all()) << "thread count changed the velocities";
}

}  // namespace
}  // namespace drapelab
