// The continuum model under every integrator of our solver: a hanging sheet settles to the same
// static shape whichever scheme steps it (the shape is the integrator's fixed point, not its
// path), its resting forces balance, the large-step schemes stay stable at 1/60 s on a stiff
// fabric, and pins hold.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "drapelab/continuum.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/integrators.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/stability.hpp"
#include "fixtures/measured.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

std::string number(double value) { return fixtures::measured(value, 4); }

// A vertical 9 x 9 sheet of 0.1 kg held at its top corners, with a cotton-like continuum.
GridClothSpec hanging_continuum(int n, double stretch_modulus) {
  GridClothSpec spec = fixtures::hanging_sheet(n, 0.1, fixtures::default_springs());
  ContinuumParams params;
  params.stretch_modulus = stretch_modulus;
  params.poisson = 0.3;
  params.bending_rigidity = 1e-5;
  params.damping = 0.005;
  spec.continuum = params;
  return spec;
}

struct Settled {
  Eigen::Matrix3Xd x;
  double residual = 0.0;  // N: the largest net force on a free particle at rest in that shape
  bool ok = false;
};

// Runs `integrator` for `seconds` with heavy air damping, so that the sheet comes to rest.
Settled settle(const GridClothSpec& spec, Integrator integrator, double h, double seconds) {
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  SpringDamperSettings settings;
  settings.integrator = integrator;
  settings.air_damping = 4.0;  // 1/s
  SpringDamperSolver solver("ours", model, initial_grid_state(*model, spec, 0.0, 0), settings);
  const int steps = static_cast<int>(std::lround(seconds / h));
  for (int k = 0; k < steps && solver.status() == SolverStatus::ok; ++k) solver.step(h);
  Settled out;
  out.ok = solver.status() == SolverStatus::ok;
  EXPECT_TRUE(out.ok) << integrator_name(integrator) << ": " << solver.message();
  out.x = solver.state().x;
  const Eigen::Matrix3Xd& f = solver.evaluate_forces(out.x, Eigen::Matrix3Xd::Zero(3, out.x.cols()),
                                                     solver.state().time, h);
  for (int i = 0; i < model->particle_count(); ++i)
    if (!model->is_pinned(i)) out.residual = std::max(out.residual, f.col(i).norm());
  return out;
}

TEST(ContinuumSolvers, EveryIntegratorSettlesToTheSameHangingShape) {
  const GridClothSpec spec = hanging_continuum(9, 400.0);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const double weight = 0.1 * 9.81 / 81;  // N per particle
  // The reference: implicit Euler at 1 ms for 4 s, well settled.
  const Settled reference = settle(spec, Integrator::implicit_euler, 1e-3, 4.0);
  ASSERT_TRUE(reference.ok);
  EXPECT_LT(reference.residual, 0.01 * weight);
  for (Integrator integrator : all_integrators()) {
    double h = 1.0 / 120.0;  // s: the unconditionally stable schemes' step
    if (std::isfinite(undamped_stability_limit(integrator)) ||
        undamped_stability_limit(integrator) == 0.0)
      h = 0.5 * stable_step_estimate(*model, 4.0, {}, integrator);
    const Settled run = settle(spec, integrator, h, 2.5);
    if (!run.ok) continue;
    const double distance = (run.x - reference.x).colwise().norm().maxCoeff();  // m
    EXPECT_LT(distance, 2e-3) << integrator_name(integrator) << " at h = " << h;
    RecordProperty(std::string(integrator_name(integrator)) + "_max_distance_m", number(distance));
    RecordProperty(std::string(integrator_name(integrator)) + "_h_s", number(h));
  }
}

TEST(ContinuumSolvers, LargeStepSchemesStayStableOnAStiffFabricAtASixtiethOfASecond) {
  // Stretch modulus 20,000 N/m on 0.1 kg of 15 x 15 particles: the explicit stable step is about
  // 1e-4 s; implicit Euler and vbd take 1/60 s.
  const GridClothSpec spec = hanging_continuum(15, 2.0e4);
  for (Integrator integrator : {Integrator::implicit_euler, Integrator::vbd}) {
    const Settled run = settle(spec, integrator, 1.0 / 60.0, 3.0);
    ASSERT_TRUE(run.ok) << integrator_name(integrator);
    // It hangs: the bottom edge below the pins, nothing far off.
    EXPECT_LT(run.x.row(1).minCoeff(), 0.55);
    EXPECT_GT(run.x.row(1).minCoeff(), 0.3);
    RecordProperty(std::string(integrator_name(integrator)) + "_lowest_y",
                   number(run.x.row(1).minCoeff()));
  }
}

TEST(ContinuumSolvers, ExplicitStepEstimateIsStableAndTwiceItIsNot) {
  // The Gershgorin estimate of stability.hpp for the elements is sufficient: symplectic Euler at
  // 0.9 of it stays bounded on an undamped sheet released from a stretched shape.
  GridClothSpec spec = hanging_continuum(9, 2000.0);
  spec.continuum->damping = 0.0;
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const double h = stable_step_estimate(*model, 0.0, {}, Integrator::symplectic_euler);
  ASSERT_TRUE(std::isfinite(h) && h > 0.0);
  SpringDamperSettings settings;
  settings.integrator = Integrator::symplectic_euler;
  ClothState start = initial_grid_state(*model, spec, 0.0, 0);
  start.x.row(0) *= 1.1;  // stretched 10 % sideways
  SpringDamperSolver solver("ours", model, start, settings);
  for (int k = 0; k < 3000 && solver.status() == SolverStatus::ok; ++k) solver.step(0.9 * h);
  EXPECT_EQ(solver.status(), SolverStatus::ok) << solver.message();
  RecordProperty("estimated_step_s", number(h));
}

TEST(ContinuumSolvers, AdaptiveSubstepsAreRefused) {
  const GridClothSpec spec = hanging_continuum(5, 400.0);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  SpringDamperSettings settings;
  settings.adaptive_substeps = true;
  EXPECT_THROW(
      SpringDamperSolver("ours", model, initial_grid_state(*model, spec, 0.0, 0), settings),
      std::invalid_argument);
}

}  // namespace
}  // namespace drapelab
