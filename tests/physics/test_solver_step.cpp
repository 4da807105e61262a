// The step of our solver: force assembly, each integrator's update, pins, air damping, and the
// health check that stops a blown-up run with a useful message.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>

#include "contact/broad_phase_loops.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/spring_forces.hpp"
#include "drapelab/stability.hpp"
#include "fixtures/sheets.hpp"
#include "forces/body_force_loops.hpp"
#include "forces/spring_family_loops.hpp"
#include "forces/spring_force.hpp"
#include "integrators/particle_loops.hpp"

namespace drapelab {
namespace {

// The sheet of every test here: n x n particles of 0.2 kg in all, hanging from two corners.
GridClothSpec sheet(int n) { return fixtures::hanging_sheet(n, 0.2, fixtures::kTenfoldSprings); }

ClothState random_state(const ClothModel& model, unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ClothState state;
  state.x = model.rest_positions;
  state.v = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  for (int i = 0; i < model.particle_count(); ++i)
    for (int c = 0; c < 3; ++c) {
      state.x(c, i) += 0.01 * u(random);
      state.v(c, i) = u(random);
    }
  return state;
}

TEST(SolverStep, ForcesAreGravityPlusEverySpringPlusAirDamping) {
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(sheet(5)));
  const ClothState state = random_state(*model, 3);
  SpringDamperSettings settings;
  settings.gravity = {0.5, -9.0, 0.25};
  settings.air_damping = 0.7;
  SpringDamperSolver solver("s", model, state, settings);
  const Eigen::Matrix3Xd force = solver.evaluate_forces(state.x, state.v, 0.0, 1e-4);

  Eigen::Matrix3Xd expected(3, model->particle_count());
  for (int i = 0; i < model->particle_count(); ++i)
    expected.col(i) = model->mass[i] * settings.gravity - 0.7 * model->mass[i] * state.v.col(i);
  const SpringSet& s = model->springs;
  for (std::size_t e = 0; e < s.size(); ++e) {
    const Eigen::Vector3d f =
        damped_spring_force(state.x.col(s.v0[e]), state.x.col(s.v1[e]), state.v.col(s.v0[e]),
                            state.v.col(s.v1[e]), s.ks[e], s.kd[e], s.rest_length[e]);
    expected.col(s.v0[e]) += f;
    expected.col(s.v1[e]) -= f;
  }
  EXPECT_LT((force - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
  // Internal forces cancel: the total is the external force alone.
  const Eigen::Vector3d total_external =
      model->total_mass() * settings.gravity - 0.7 * state.v * model->mass;
  EXPECT_LT((force.rowwise().sum() - total_external).norm(), 1e-10);
}

TEST(SolverStep, EachIntegratorTakesItsDocumentedUpdate) {
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(sheet(4)));
  const ClothState start = random_state(*model, 5);
  const double h = 1e-4;
  for (Integrator integrator : {Integrator::explicit_euler, Integrator::symplectic_euler}) {
    SpringDamperSettings settings;
    settings.integrator = integrator;
    SpringDamperSolver solver("s", model, start, settings);
    ClothState zeroed_pins = start;
    for (int i = 0; i < model->particle_count(); ++i)
      if (model->is_pinned(i)) zeroed_pins.v.col(i).setZero();
    const Eigen::Matrix3Xd force = solver.evaluate_forces(zeroed_pins.x, zeroed_pins.v, 0.0, h);
    const Eigen::Matrix3Xd a = force * model->inverse_mass.asDiagonal();
    solver.step(h);
    const Eigen::Matrix3Xd v1 = zeroed_pins.v + h * a;
    const Eigen::Matrix3Xd x1 =
        zeroed_pins.x + h * (integrator == Integrator::explicit_euler ? zeroed_pins.v : v1);
    EXPECT_LT((solver.state().v - v1).cwiseAbs().maxCoeff(), 1e-12) << integrator_name(integrator);
    EXPECT_LT((solver.state().x - x1).cwiseAbs().maxCoeff(), 1e-15) << integrator_name(integrator);
    EXPECT_DOUBLE_EQ(solver.state().time, h);
    EXPECT_EQ(solver.state().step_count, 1);
  }
}

TEST(SolverStep, PinnedParticlesNeverMove) {
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(sheet(9)));
  ClothState start =
      random_state(*model, 9);  // pins start with a velocity: the solver must zero it
  for (Integrator integrator : {Integrator::explicit_euler, Integrator::symplectic_euler}) {
    SpringDamperSettings settings;
    settings.integrator = integrator;
    SpringDamperSolver solver("s", model, start, settings);
    for (int k = 0; k < 2000; ++k) solver.step(2e-5);
    ASSERT_EQ(solver.status(), SolverStatus::ok);
    for (int i = 0; i < model->particle_count(); ++i) {
      if (!model->is_pinned(i)) continue;
      EXPECT_EQ(solver.state().x.col(i), start.x.col(i));  // bitwise
      EXPECT_EQ(solver.state().v.col(i).norm(), 0.0);
    }
  }
}

TEST(SolverStep, AirDampingDecaysVelocityGeometrically) {
  // No gravity, no spring force (all at rest length, moving together): symplectic Euler gives
  // v(n) = v(0) (1 - gamma h)^n exactly up to rounding.
  GridClothSpec spec = sheet(3);
  spec.pins.clear();
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  ClothState start = initial_grid_state(*model, spec, 0.0, 0);
  start.v.colwise() = Eigen::Vector3d(1.0, -2.0, 0.5);
  SpringDamperSettings settings;
  settings.gravity.setZero();
  settings.air_damping = 3.0;  // 1/s
  SpringDamperSolver solver("s", model, start, settings);
  const double h = 1e-3;
  for (int k = 0; k < 100; ++k) solver.step(h);
  const double factor = std::pow(1.0 - 3.0 * h, 100);
  for (int i = 0; i < model->particle_count(); ++i)
    EXPECT_NEAR((solver.state().v.col(i) - factor * Eigen::Vector3d(1.0, -2.0, 0.5)).norm(), 0.0,
                1e-9);
}

TEST(SolverStep, StableStepBoundHoldsAndTwiceTheTrueLimitBlowsUp) {
  GridClothSpec spec = sheet(9);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const double bound = symplectic_euler_stable_step(*model, 0.0);
  ASSERT_TRUE(std::isfinite(bound));
  const ClothState start = random_state(*model, 21);
  {
    SpringDamperSolver solver("at_bound", model, start, {});
    for (int k = 0; k < 20000; ++k) solver.step(0.95 * bound);
    EXPECT_EQ(solver.status(), SolverStatus::ok) << solver.message();
  }
  {
    SpringDamperSolver solver("far_above", model, start, {});
    for (int k = 0; k < 20000 && solver.status() == SolverStatus::ok; ++k) solver.step(4.0 * bound);
    EXPECT_EQ(solver.status(), SolverStatus::unstable);
  }
}

TEST(SolverStep, UnstableRunStopsWithParticleStepAndAdvice) {
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(sheet(9)));
  const ClothState start = initial_grid_state(*model, sheet(9), 0.001, 1);
  SpringDamperSettings settings;
  settings.integrator = Integrator::explicit_euler;
  SpringDamperSolver solver("blows_up", model, start, settings);
  int steps = 0;
  while (solver.status() == SolverStatus::ok && steps < 100000) {
    solver.step(5e-3);
    ++steps;
  }
  ASSERT_EQ(solver.status(), SolverStatus::unstable);
  const std::string& message = solver.message();
  EXPECT_NE(message.find("particle "), std::string::npos) << message;
  EXPECT_NE(message.find("step " + std::to_string(steps)), std::string::npos) << message;
  EXPECT_NE(message.find("Try:"), std::string::npos) << message;
  EXPECT_NE(message.find("symplectic_euler"), std::string::npos) << message;
  // After stopping, stepping does nothing.
  const ClothState frozen = solver.state();
  solver.step(5e-3);
  EXPECT_EQ(solver.state().step_count, frozen.step_count);
}

TEST(SolverStep, StepStatsCountEveryPhase) {
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(sheet(5)));
  SpringDamperSolver solver("s", model, initial_grid_state(*model, sheet(5), 0.0, 0), {});
  for (int k = 0; k < 10; ++k) solver.step(1e-4);
  EXPECT_EQ(solver.stats().steps, 10);
  double total = 0.0;
  for (double seconds : solver.stats().seconds) {
    EXPECT_GE(seconds, 0.0);
    total += seconds;
  }
  EXPECT_GT(total, 0.0);
}

// A sheet of 80 x 80 particles (13 contact blocks, so both threads take several) sagging into a
// sphere and a tilted floor, with random velocities: about a third of the particles touch
// something.
struct ContactSheet {
  std::shared_ptr<const ClothModel> model;
  ClothState start;
  SpringDamperSettings settings;
};

ContactSheet contact_sheet(Integrator integrator) {
  GridClothSpec spec = sheet(80);
  spec.plane = GridPlane::xz;
  spec.center = {0.0, 0.29, 0.0};  // m: the sheet's middle 1 cm inside the ball's top
  spec.pins = {PinNamed{"corners"}};
  ContactSheet sheet;
  sheet.model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  sheet.start = random_state(*sheet.model, 17);
  Collider ball;
  ball.shape = ColliderShape::sphere;
  ball.radius = 0.3;
  Collider floor;
  floor.shape = ColliderShape::plane;
  floor.normal = Eigen::Vector3d(0.3, 1.0, 0.0).normalized();
  floor.center = {0.0, 0.27, 0.0};
  sheet.settings.integrator = integrator;
  sheet.settings.air_damping = 0.1;
  sheet.settings.contacts = std::make_shared<const ContactModel>(
      std::vector<Collider>{ball, floor}, ContactParameters{1000.0, 0.2}, 0.005);
  return sheet;
}

// With colliders, the Euler pair updates each block of particles inside the contact phase. That
// must be exactly the force of evaluate_forces followed by the whole-cloth update pass, on any
// thread count.
TEST(SolverStep, WithCollidersEachEulerStepIsTheForceThenTheUpdatePass) {
  const int threads_before = kernels::thread_count();
  for (Integrator integrator : {Integrator::symplectic_euler, Integrator::explicit_euler})
    for (int threads : {1, 2}) {
      kernels::set_thread_count(threads);
      const ContactSheet sheet = contact_sheet(integrator);
      const double h = 2e-5;  // s
      SpringDamperSolver stepped("stepped", sheet.model, sheet.start, sheet.settings);
      SpringDamperSolver reference("reference", sheet.model, sheet.start, sheet.settings);
      ClothState expected =
          reference.state();  // the pins' velocities zeroed, as the solver holds them
      for (int step = 0; step < 3; ++step) {
        const Eigen::Matrix3Xd force =
            reference.evaluate_forces(expected.x, expected.v, expected.time, h);
        int touching = 0;
        for (const ColliderContactTotals& total : reference.contact_totals())
          touching += total.contact_count;
        ASSERT_GT(touching, sheet.model->particle_count() / 10)
            << "the sheet must press on the colliders";
        Eigen::Matrix3Xd inverse_mass(3, sheet.model->particle_count());
        for (int i = 0; i < sheet.model->particle_count(); ++i)
          inverse_mass.col(i).setConstant(sheet.model->inverse_mass[i]);
        const auto pass = integrator == Integrator::symplectic_euler
                              ? kernels::symplectic_euler_pass
                              : kernels::explicit_euler_pass;
        ASSERT_EQ(pass(sheet.model->particle_count(), inverse_mass.data(), force.data(), h,
                       expected.x.data(), expected.v.data(), 1e6),
                  -1);
        expected.time += h;
        stepped.step(h);
        ASSERT_EQ(stepped.status(), SolverStatus::ok) << stepped.message();
        EXPECT_TRUE(stepped.state().x == expected.x)
            << integrator_name(integrator) << ", " << threads << " threads";
        EXPECT_TRUE(stepped.state().v == expected.v)
            << integrator_name(integrator) << ", " << threads << " threads";
      }
    }
  kernels::set_thread_count(threads_before);
}

// The update inside the contact phase still scans every block: a runaway particle in a late block
// stops the run, and of two the lower-numbered one is named, whichever thread's block holds it.
TEST(SolverStep, WithCollidersTheFirstRunawayParticleIsNamed) {
  const int threads_before = kernels::thread_count();
  for (int threads : {1, 2}) {
    kernels::set_thread_count(threads);
    ContactSheet sheet = contact_sheet(Integrator::symplectic_euler);
    sheet.start.v.col(6000) = Eigen::Vector3d(2000.0, 0.0, 0.0);  // m/s, over the 1000 m/s limit
    sheet.start.v.col(5200) = Eigen::Vector3d(0.0, 0.0, -1500.0);
    SpringDamperSolver solver("runaway", sheet.model, sheet.start, sheet.settings);
    solver.step(1e-6);
    ASSERT_EQ(solver.status(), SolverStatus::unstable);
    EXPECT_NE(solver.message().find(sheet.model->describe_particle(5200) + " moves at"),
              std::string::npos)
        << solver.message();
  }
  kernels::set_thread_count(threads_before);
}

}  // namespace
}  // namespace drapelab
