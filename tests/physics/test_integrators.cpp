// docs/validation.md, "V4 Integrators on a linear spring": every integrator on a linear spring
// x'' = -w^2 x, its convergence order from two step sizes, energy behaviour, and stability just
// inside and just outside its bound; and the stable-step estimates the loader and the advice rely
// on.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "drapelab/grid_cloth.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/stability.hpp"
#include "fixtures/chains.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

// Particle 1 (mass m) hangs on one spring from pinned particle 0, with no gravity: along the spring
// its displacement u obeys m u'' = -ks u - kd u' exactly while the spring keeps a positive length.
struct Oscillator {
  double mass = 1.0;        // kg
  double stiffness = 1.0;   // N/m
  double damping = 0.0;     // N*s/m
  double amplitude = 1e-3;  // m, initial displacement (rest length 1 m, so the spring never folds)

  double omega() const { return std::sqrt(stiffness / mass); }
};

class OscillatorRun {
 public:
  OscillatorRun(const Oscillator& o, Integrator integrator,
                ImplicitSolveSettings implicit = {1e-14, 50}) {
    const GridClothSpec spec = fixtures::spring_pendulum(1.0, o.mass, {o.stiffness, o.damping});
    auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
    ClothState start = initial_grid_state(*model, spec, 0.0, 0);
    rest_y_ = start.x(1, 0);
    start.x(1, 0) -= o.amplitude;
    SpringDamperSettings settings;
    settings.integrator = integrator;
    settings.gravity = Eigen::Vector3d::Zero();
    settings.implicit = implicit;
    settings.max_speed = 1e12;  // let a divergence show in the numbers, not stop the solver
    solver_ = std::make_unique<SpringDamperSolver>("oscillator", model, start, settings);
    oscillator_ = o;
  }
  void step(double h) { solver_->step(h); }
  double displacement() const {
    return -(solver_->state().x(1, 0) - rest_y_);
  }  // m, stretching positive
  double velocity() const { return -solver_->state().v(1, 0); }
  // Oscillator energy 1/2 m v^2 + 1/2 k u^2 (J).
  double energy() const {
    const double u = displacement(), v = velocity();
    return 0.5 * oscillator_.mass * v * v + 0.5 * oscillator_.stiffness * u * u;
  }
  bool ok() const { return solver_->status() == SolverStatus::ok; }
  const SpringDamperSolver& solver() const { return *solver_; }

 private:
  std::unique_ptr<SpringDamperSolver> solver_;
  Oscillator oscillator_;
  double rest_y_ = 0.0;
};

// |u(10) - A cos(w 10)| for a run of step h (w = 1 rad/s).
double error_at_ten_seconds(Integrator integrator, double h) {
  Oscillator o;
  o.amplitude = 0.1;
  OscillatorRun run(o, integrator);
  const int steps = static_cast<int>(std::lround(10.0 / h));
  for (int k = 0; k < steps; ++k) run.step(h);
  return std::abs(run.displacement() - o.amplitude * std::cos(o.omega() * 10.0));
}

TEST(V4Integrators, ConvergenceOrderFromTwoStepSizes) {
  for (Integrator integrator : all_integrators()) {
    SCOPED_TRACE(integrator_name(integrator));
    // Small enough to be in the asymptotic range, large enough that RK4's error stays above
    // rounding.
    const double h = integrator == Integrator::rk4 ? 0.05 : 0.01;
    const double measured =
        std::log2(error_at_ten_seconds(integrator, h) / error_at_ten_seconds(integrator, h / 2));
    EXPECT_NEAR(measured, order_of_accuracy(integrator), 0.1);
  }
}

TEST(V4Integrators, SymplecticSchemesKeepEnergyBoundedOverAHundredThousandSteps) {
  const double h = 0.05;  // w h = 0.05
  for (Integrator integrator :
       {Integrator::symplectic_euler, Integrator::verlet, Integrator::leapfrog}) {
    SCOPED_TRACE(integrator_name(integrator));
    OscillatorRun run(Oscillator{}, integrator);
    const double start = run.energy();
    double first_window = 0.0,
           last_window = 0.0;  // largest |E - E0| / E0 over the first and last 2000 steps
    const int steps = 100000;
    for (int k = 0; k < steps; ++k) {
      run.step(h);
      const double deviation = std::abs(run.energy() - start) / start;
      if (k < 2000) first_window = std::max(first_window, deviation);
      if (k >= steps - 2000) last_window = std::max(last_window, deviation);
    }
    EXPECT_LT(first_window, h);  // an O(w h) oscillation of the energy ...
    EXPECT_LT(last_window, first_window * 1.001 + 1e-12);  // ... that does not grow
  }
}

TEST(V4Integrators, EulerSchemesChangeEnergyByTheirExactFactorPerStep) {
  const double h = 0.1;  // w h = 0.1
  // vbd is backward Euler; on one particle its sweeps are Newton's method, converged well inside
  // its default 10 sweeps.
  for (Integrator integrator :
       {Integrator::explicit_euler, Integrator::implicit_euler, Integrator::vbd}) {
    SCOPED_TRACE(integrator_name(integrator));
    OscillatorRun run(Oscillator{}, integrator);
    const double factor =
        integrator == Integrator::explicit_euler ? 1.0 + h * h : 1.0 / (1.0 + h * h);
    for (int k = 0; k < 200; ++k) {
      const double before = run.energy();
      run.step(h);
      ASSERT_NEAR(run.energy() / before, factor, 1e-9) << "step " << k;
    }
  }
}

// Largest |u| over 400 steps at w h = ratio x the bound, relative to the start.
double growth(Integrator integrator, double omega_h) {
  OscillatorRun run(Oscillator{}, integrator);
  double largest = 0.0;
  for (int k = 0; k < 400; ++k) {
    run.step(omega_h);  // w = 1
    largest = std::max(largest, std::abs(run.displacement()));
  }
  return largest / 1e-3;
}

TEST(V4Integrators, BoundedJustInsideAndDivergingJustOutsideEachStabilityLimit) {
  for (Integrator integrator :
       {Integrator::symplectic_euler, Integrator::verlet, Integrator::leapfrog, Integrator::rk4}) {
    SCOPED_TRACE(integrator_name(integrator));
    const double limit = undamped_stability_limit(integrator);
    EXPECT_LT(growth(integrator, 0.95 * limit), 20.0);
    EXPECT_GT(growth(integrator, 1.05 * limit), 1e3);
  }
  // Explicit Euler and midpoint grow at any step on an undamped spring; implicit Euler never does.
  for (Integrator integrator : {Integrator::explicit_euler, Integrator::midpoint}) {
    OscillatorRun run(Oscillator{}, integrator);
    for (int k = 0; k < 2000; ++k) run.step(0.1);
    EXPECT_GT(run.energy(), 1.001 * 0.5 * 1e-6) << integrator_name(integrator);
  }
  EXPECT_LT(growth(Integrator::implicit_euler, 100.0), 1.0 + 1e-12);
  EXPECT_LT(growth(Integrator::vbd, 100.0), 1.0 + 1e-12);
}

// Damped: explicit Euler's mode factor |1 + h lambda|^2 = 1 - c h + w^2 h^2 (c = kd / m) is below 1
// exactly for h < kd / ks, the bound damping_ratio_step gives.
TEST(V4Integrators, ExplicitEulerOnADampedSpringIsStableBelowKdOverKs) {
  Oscillator o;
  o.stiffness = 100.0;
  o.damping = 1.0;  // zeta = 0.05, bound 0.01 s
  OscillatorRun probe(o, Integrator::explicit_euler);
  const double bound = damping_ratio_step(probe.solver().model());
  EXPECT_DOUBLE_EQ(bound, 0.01);
  for (double ratio : {0.95, 1.05}) {
    OscillatorRun run(o, Integrator::explicit_euler);
    double last_peak = 0.0;
    for (int k = 0; k < 20000; ++k) {
      run.step(ratio * bound);
      if (k >= 19000) last_peak = std::max(last_peak, std::abs(run.displacement()));
    }
    if (ratio < 1.0)
      EXPECT_LT(last_peak, o.amplitude);
    else
      EXPECT_GT(last_peak, 10.0 * o.amplitude);
  }
}

// The stable-step estimate of each explicit scheme is safe on a real cloth: 2 s of a pinned, damped
// sheet at 0.95 x the estimate stays finite and unstretched.
TEST(V4Integrators, StableStepEstimateHoldsOnACloth) {
  const GridClothSpec spec =
      fixtures::hanging_sheet(9, 0.1, {{800.0, 0.1}, {80.0, 0.01}, {8.0, 0.001}});
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  for (Integrator integrator : all_integrators()) {
    // The implicit schemes have no stable step (the estimate is infinite).
    if (integrator == Integrator::implicit_euler || integrator == Integrator::vbd) continue;
    SCOPED_TRACE(integrator_name(integrator));
    const double h = 0.95 * stable_step_estimate(*model, 0.0, {}, integrator);
    ASSERT_GT(h, 0.0);
    SpringDamperSettings settings;
    settings.integrator = integrator;
    SpringDamperSolver solver("sheet", model, initial_grid_state(*model, spec, 1e-3, 1), settings);
    for (int k = 0; k < static_cast<int>(2.0 / h) && solver.status() == SolverStatus::ok; ++k)
      solver.step(h);
    ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
    double worst = 0.0;
    const SpringSet& s = model->springs;
    for (std::size_t e = 0; e < s.size(); ++e)
      worst =
          std::max(worst, (solver.state().x.col(s.v0[e]) - solver.state().x.col(s.v1[e])).norm() /
                              s.rest_length[e]);
    EXPECT_LT(worst, 1.2);
  }
}

}  // namespace
}  // namespace drapelab
