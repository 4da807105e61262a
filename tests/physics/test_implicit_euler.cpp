// Implicit Euler: the linear system and its conjugate-gradient solve, and the point of the scheme:
// a stiff cloth stays stable at h = 1/60 s where every explicit scheme explodes (the spring
// Jacobians it assembles: test_spring_jacobian.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "drapelab/grid_cloth.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

double max_strain(const ClothModel& model, const ClothState& state) {
  double worst = 0.0;
  const SpringSet& s = model.springs;
  for (std::size_t e = 0; e < s.size(); ++e)
    if (s.kind[e] == SpringKind::stretch)
      worst = std::max(
          worst, (state.x.col(s.v0[e]) - state.x.col(s.v1[e])).norm() / s.rest_length[e] - 1.0);
  return worst;
}

TEST(ImplicitEuler, StiffClothAtASixtiethOfASecondStaysFiniteAndSettles) {
  GridClothSpec spec = fixtures::stiff_sheet(15, 15);
  spec.plane = GridPlane::xz;  // horizontal, held at two corners: it swings down like a pendulum
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const double h = 1.0 / 60.0;
  SpringDamperSettings settings;
  settings.integrator = Integrator::implicit_euler;
  settings.implicit.max_iterations =
      3000;                    // h^2 k / m ~ 1e5: the Jacobi-preconditioned CG needs many
  settings.air_damping = 1.0;  // 1/s, so the pendulum swing dies out within the run
  SpringDamperSolver solver("stiff", model, initial_grid_state(*model, spec, 1e-3, 1), settings);
  double peak_speed = 0.0;
  for (int k = 0; k < 8 * 60; ++k) {  // 8 s
    solver.step(h);
    ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
    peak_speed = std::max(peak_speed, solver.state().v.colwise().norm().maxCoeff());
  }
  EXPECT_TRUE(solver.state().x.allFinite());
  EXPECT_GT(peak_speed, 1.0);                                                  // it swung ...
  EXPECT_LT(solver.state().v.colwise().norm().maxCoeff(), 0.01 * peak_speed);  // ... and settled
  EXPECT_LT(max_strain(*model, solver.state()), 0.02);  // stiff springs barely stretch
  EXPECT_LT(solver.state().x.row(1).mean(), 0.8);       // and it hangs below the pins
  EXPECT_EQ(solver.implicit_stats()->unconverged, 0);

  // Every explicit scheme explodes at that step on this cloth within a second. vbd is left out: it
  // is backward Euler too, unconditionally stable (test_vbd.cpp runs a stiff sheet at this step).
  for (Integrator integrator : all_integrators()) {
    if (integrator == Integrator::implicit_euler || integrator == Integrator::vbd) continue;
    SpringDamperSettings explicit_settings;
    explicit_settings.integrator = integrator;
    SpringDamperSolver explicit_solver("stiff", model, initial_grid_state(*model, spec, 1e-3, 1),
                                       explicit_settings);
    for (int k = 0; k < 60 && explicit_solver.status() == SolverStatus::ok; ++k)
      explicit_solver.step(h);
    EXPECT_EQ(explicit_solver.status(), SolverStatus::unstable) << integrator_name(integrator);
  }
}

TEST(ImplicitEuler, ConjugateGradientReachesItsToleranceOnTheAssembledSystem) {
  const GridClothSpec spec = fixtures::stiff_sheet(9, 9);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  for (double tolerance : {1e-4, 1e-8}) {
    SpringDamperSettings settings;
    settings.integrator = Integrator::implicit_euler;
    settings.implicit = {tolerance, 1000};
    settings.air_damping = 0.3;
    settings.fast_springs =
        false;  // the assembled matrix (the grid's matrix-free solve: test_family_implicit)
    SpringDamperSolver solver("cg", model, initial_grid_state(*model, spec, 1e-2, 3), settings);
    for (int k = 0; k < 30; ++k) {
      const Eigen::Matrix3Xd v_before = solver.state().v;
      solver.step(1.0 / 120.0);
      const ImplicitEulerSystem& system = *solver.implicit_system();
      const Eigen::Matrix3Xd dv = solver.state().v - v_before;
      const Eigen::VectorXd dv_flat = Eigen::Map<const Eigen::VectorXd>(dv.data(), dv.size());
      const double residual = (system.matrix() * dv_flat - system.right_hand_side()).norm() /
                              system.right_hand_side().norm();
      EXPECT_LE(residual, tolerance * 1.0001) << "step " << k;
      EXPECT_LE(system.stats().residual_last, tolerance);
    }
    const Eigen::SparseMatrix<double>& a = solver.implicit_system()->matrix();
    EXPECT_LT((Eigen::MatrixXd(a) - Eigen::MatrixXd(a).transpose()).norm(),
              1e-12 * Eigen::MatrixXd(a).norm());
    EXPECT_EQ(solver.implicit_system()->stats().unconverged, 0);
    EXPECT_EQ(solver.implicit_system()->stats().solves, 30);
    EXPECT_GT(solver.implicit_system()->stats().iterations_total, 30);
  }
}

TEST(ImplicitEuler, PinnedParticlesAreFilteredOutOfTheSystem) {
  const GridClothSpec spec = fixtures::stiff_sheet(5, 5);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  SpringDamperSettings settings;
  settings.integrator = Integrator::implicit_euler;
  settings.fast_springs = false;  // the assembled matrix
  SpringDamperSolver solver("pins", model, initial_grid_state(*model, spec, 1e-2, 3), settings);
  for (int k = 0; k < 20; ++k) solver.step(1.0 / 60.0);
  const Eigen::MatrixXd a(solver.implicit_system()->matrix());
  for (int i = 0; i < model->particle_count(); ++i) {
    if (!model->is_pinned(i)) continue;
    EXPECT_EQ(solver.state().x.col(i), model->rest_positions.col(i));
    EXPECT_EQ(solver.state().v.col(i).norm(), 0.0);
    for (int r = 0; r < 3; ++r) {
      EXPECT_EQ(a.row(3 * i + r).cwiseAbs().sum(), 1.0) << "a pinned row is the identity";
      EXPECT_EQ(solver.implicit_system()->right_hand_side()[3 * i + r], 0.0);
    }
  }
}

}  // namespace
}  // namespace drapelab
