// The energy ledger (drapelab/energy_ledger.hpp): what our solver's dampers, friction and air take
// out and what moving colliders and the wind put in balances the change of the cloth's energy,
// total + dissipated - external work = its start value, to within the integrator's error, which
// falls with the step. And the powers themselves: each damper's is minus the power of its force.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "drapelab/air.hpp"
#include "drapelab/cloth_metrics.hpp"
#include "drapelab/collision_metrics.hpp"
#include "drapelab/continuum.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/integrators.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/stability.hpp"
#include "fixtures/colliders.hpp"
#include "fixtures/sheets.hpp"
#include "forces/continuum_arrays.hpp"
#include "forces/spring_families.hpp"
#include "forces/spring_family_loops.hpp"

namespace drapelab {
namespace {

const Eigen::Vector3d kGravity{0.0, -9.81, 0.0};  // m/s^2

// The cloth's energy as the run's audit counts it: kinetic, gravity, elastic and contact (J).
double total_energy(const SpringDamperSolver& solver, const ContactModel* contacts) {
  const ClothState& s = solver.state();
  const ClothMetrics m = compute_cloth_metrics(solver.model(), s, solver.settings().gravity);
  double total = m.kinetic_energy + m.gravity_energy +
                 (solver.model().uses_continuum() ? continuum_energy(*solver.model().continuum, s.x)
                                                  : m.spring_energy);
  if (contacts)
    total += compute_collision_metrics(solver.model(), s, *contacts, s.time).contact_energy;
  return total;
}

struct Balance {
  double error = 0.0;       // J: total + dissipated - external - start
  double dissipated = 0.0;  // J
  double external = 0.0;    // J
  double start = 0.0;       // J
  double end = 0.0;         // J
};

// Runs `solver` for `seconds` in steps of h and balances its energy.
Balance run_and_balance(SpringDamperSolver& solver, double h, double seconds,
                        const ContactModel* contacts = nullptr) {
  Balance b;
  b.start = total_energy(solver, contacts);
  const int steps = static_cast<int>(std::lround(seconds / h));
  for (int k = 0; k < steps && solver.status() == SolverStatus::ok; ++k) solver.step(h);
  EXPECT_EQ(solver.status(), SolverStatus::ok) << solver.message();
  const EnergyLedger ledger = *solver.energy_ledger();
  b.end = total_energy(solver, contacts);
  b.dissipated = ledger.dissipated;
  b.external = ledger.external_work;
  b.error = b.end + b.dissipated - b.external - b.start;
  return b;
}

std::string describe(const Balance& b) {
  return "start " + std::to_string(b.start) + " J, end " + std::to_string(b.end) +
         " J, dissipated " + std::to_string(b.dissipated) + " J, external " +
         std::to_string(b.external) + " J, error " + std::to_string(b.error) + " J";
}

// A 1 m, 9 x 9 sheet of 0.1 kg held at two corners, released flat (horizontal), with damped
// springs and air damping: it swings down and loses much of what gravity gives it.
GridClothSpec swinging_sheet() {
  GridClothSpec spec = fixtures::hanging_sheet(9, 0.1, fixtures::kSoftSprings);
  spec.plane = GridPlane::xz;
  return spec;
}

SpringDamperSettings hanging_settings(Integrator integrator) {
  SpringDamperSettings settings;
  settings.integrator = integrator;
  settings.gravity = kGravity;
  settings.air_damping = 0.5;  // 1/s
  return settings;
}

TEST(EnergyLedger, EveryIntegratorBalancesASwingingDampedSheet) {
  const GridClothSpec spec = swinging_sheet();
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  for (Integrator integrator : all_integrators()) {
    SCOPED_TRACE(integrator_name(integrator));
    const bool implicit = integrator == Integrator::implicit_euler || integrator == Integrator::vbd;
    // s: the explicit schemes at a quarter of their stable step, the implicit ones at 1 ms.
    const double h = implicit ? 1e-3 : 0.25 * stable_step_estimate(*model, 0.5, {}, integrator);
    SpringDamperSolver solver("sheet", model, initial_grid_state(*model, spec, 0.0, 0),
                              hanging_settings(integrator));
    const Balance b = run_and_balance(solver, h, 1.0);
    // Gravity releases about 0.5 J as it swings down; the dampers take a good part of it.
    EXPECT_GT(b.dissipated, 0.05) << describe(b);
    EXPECT_EQ(b.external, 0.0);
    // Backward Euler's own damping takes energy no damper reports: its error is a loss.
    if (implicit) {
      EXPECT_LT(b.error, 0.02 * b.dissipated) << describe(b);
    } else {
      EXPECT_LT(std::abs(b.error), 0.02 * b.dissipated) << describe(b);
    }
    RecordProperty(std::string("error_over_dissipated_") + integrator_name(integrator),
                   std::to_string(b.error / b.dissipated));
  }
}

TEST(EnergyLedger, TheErrorFallsWithTheStep) {
  const GridClothSpec spec = swinging_sheet();
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const double stable = stable_step_estimate(*model, 0.5, {}, Integrator::symplectic_euler);  // s
  double previous = 0.0;
  for (double fraction : {0.8, 0.2}) {
    SpringDamperSolver solver("sheet", model, initial_grid_state(*model, spec, 0.0, 0),
                              hanging_settings(Integrator::symplectic_euler));
    const Balance b = run_and_balance(solver, fraction * stable, 1.0);
    if (previous > 0.0) {
      EXPECT_LT(std::abs(b.error), 0.5 * previous) << describe(b);
    }
    previous = std::abs(b.error);
  }
}

TEST(EnergyLedger, AirDampingTakesWhatAGlidingSheetLoses) {
  // No gravity, every particle at the same velocity: the springs stay at rest, only the air acts,
  // and the kinetic energy falls as exp(-2 c t).
  GridClothSpec spec = fixtures::flat_sheet(5, 0.5, {0.0, 1.0, 0.0}, 0.05);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  SpringDamperSettings settings;
  settings.gravity.setZero();
  settings.air_damping = 2.0;  // 1/s
  ClothState start = initial_grid_state(*model, spec, 0.0, 0);
  start.v.row(0).setConstant(1.5);  // m/s
  SpringDamperSolver solver("glide", model, start, settings);
  const double h = 0.5 * stable_step_estimate(*model, 2.0, {}, Integrator::symplectic_euler);
  const Balance b = run_and_balance(solver, h, 1.0);
  const double lost = b.start - b.end;  // J
  EXPECT_NEAR(lost, 0.5 * 0.05 * 1.5 * 1.5 * (1.0 - std::exp(-4.0)), 1e-3 * lost);
  EXPECT_NEAR(b.dissipated / lost, 1.0, 2e-3) << describe(b);
}

// A 0.4 m sheet of 50 g settled on the floor `floor` (0.5 s), and the step it runs at: half the
// symplectic stable step with the default contact.
struct Resting {
  std::shared_ptr<const ClothModel> model;
  std::shared_ptr<const ContactModel> contacts;
  SpringDamperSettings settings;
  ClothState state;
  double h = 0.0;  // s
};

Resting settle_on(const Collider& floor) {
  const GridClothSpec spec = fixtures::soft_sheet(9, 0.4, {0.0, 0.004, 0.0}, 0.05);
  Resting r;
  r.model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  Collider still = floor;
  still.motion = {};
  r.settings.gravity = kGravity;
  r.settings.contacts = std::make_shared<const ContactModel>(std::vector<Collider>{still},
                                                             ContactParameters{}, spec.thickness);
  const ContactParameters contact;
  r.h = 0.5 * stable_step_estimate(*r.model, 0.0, {contact.stiffness, contact.damping},
                                   Integrator::symplectic_euler);
  SpringDamperSolver settling("settle", r.model, initial_grid_state(*r.model, spec, 0.0, 0),
                              r.settings);
  for (int k = 0; k < static_cast<int>(0.5 / r.h); ++k) settling.step(r.h);
  EXPECT_EQ(settling.status(), SolverStatus::ok) << settling.message();
  r.state = settling.state();
  r.state.time = 0.0;
  r.contacts = std::make_shared<const ContactModel>(std::vector<Collider>{floor},
                                                    ContactParameters{}, spec.thickness);
  r.settings.contacts = r.contacts;
  return r;
}

TEST(EnergyLedger, FrictionTakesWhatASlidingSheetLoses) {
  // A sheet resting on the floor, pushed along at 1 m/s: friction (0.3) stops it within
  // v / (mu g) = 0.34 s, taking its kinetic energy.
  Resting r = settle_on(fixtures::floor_collider());
  r.state.v.row(0).array() += 1.0;  // m/s
  SpringDamperSolver solver("slide", r.model, r.state, r.settings);
  const Balance b = run_and_balance(solver, r.h, 0.6, r.contacts.get());
  EXPECT_LT(solver.state().v.norm(), 1e-2);  // it has stopped
  EXPECT_GT(b.dissipated, 0.9 * 0.5 * 0.05) << describe(b);
  EXPECT_LT(std::abs(b.error), 0.02 * b.dissipated) << describe(b);
}

TEST(EnergyLedger, ARisingFloorDoesTheWorkOfLiftingTheSheet) {
  // The floor rises at 0.2 m/s under a resting sheet for 0.5 s: it lifts the sheet 0.1 m, doing
  // about m g 0.1 J of work through the contacts.
  Collider floor = fixtures::floor_collider();
  floor.motion.velocity = {0.0, 0.2, 0.0};
  const Resting r = settle_on(floor);
  SpringDamperSolver solver("lift", r.model, r.state, r.settings);
  const Balance b = run_and_balance(solver, r.h, 0.5, r.contacts.get());
  const double lift_work = 0.05 * 9.81 * 0.1;  // J
  EXPECT_NEAR(b.external / lift_work, 1.0, 0.1) << describe(b);
  EXPECT_LT(std::abs(b.error), 0.02 * b.external) << describe(b);
}

TEST(EnergyLedger, TheWindDoesWorkOnAHangingSheet) {
  const GridClothSpec spec = fixtures::hanging_sheet(9, 0.1, fixtures::kSoftSprings);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  SpringDamperSettings settings = hanging_settings(Integrator::symplectic_euler);
  settings.air.enabled = true;
  settings.air.wind = {0.0, 0.0, 4.0};  // m/s, across the sheet
  const double h = 0.25 * stable_step_estimate(*model, 0.5, {}, Integrator::symplectic_euler);
  SpringDamperSolver solver("flag", model, initial_grid_state(*model, spec, 0.0, 0), settings);
  const Balance b = run_and_balance(solver, h, 1.0);
  EXPECT_GT(b.external, 0.01) << describe(b);
  EXPECT_LT(std::abs(b.error), 0.02 * (b.external + b.dissipated)) << describe(b);
}

// Each damper's power is minus the power of its force: the force at (x, v) less the force at
// (x, 0), dotted with v.
double damping_force_power(const Eigen::Matrix3Xd& with_v, const Eigen::Matrix3Xd& without_v,
                           const Eigen::Matrix3Xd& v) {
  return ((with_v - without_v).array() * v.array()).sum();
}

TEST(EnergyLedger, TheSpringFamiliesReportTheirDampersPowerOnAnyThreadCount) {
  const GridClothSpec spec = fixtures::hanging_sheet(33, 0.1, fixtures::kSoftSprings);
  const ClothModel model = build_grid_cloth(spec);
  std::unique_ptr<SpringFamilies> families = SpringFamilies::build(model);
  ASSERT_TRUE(families);
  ClothState state = initial_grid_state(model, spec, 0.0, 0);
  state.v = Eigen::Matrix3Xd::Random(3, model.particle_count());
  state.x += 0.01 * Eigen::Matrix3Xd::Random(3, model.particle_count());
  const Eigen::Matrix3Xd still = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  Eigen::Matrix3Xd with_v = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  Eigen::Matrix3Xd without_v = with_v;
  families->add_forces(state.x, still, without_v);
  const int threads_before = kernels::thread_count();
  kernels::set_thread_count(1);
  families->add_forces(state.x, state.v, with_v);
  const double one_thread = families->damper_power();
  kernels::set_thread_count(2);
  with_v.setZero();
  families->add_forces(state.x, state.v, with_v);
  const double two_threads = families->damper_power();
  kernels::set_thread_count(threads_before);
  EXPECT_EQ(one_thread, two_threads);
  const double expected = -damping_force_power(with_v, without_v, state.v);  // W
  EXPECT_GT(expected, 0.0);
  EXPECT_NEAR(one_thread / expected, 1.0, 1e-9);
}

TEST(EnergyLedger, TheContinuumReportsItsDampingsPower) {
  GridClothSpec spec = fixtures::hanging_sheet(9, 0.1, fixtures::default_springs());
  ContinuumParams params;
  params.stretch_modulus = 400.0;
  params.poisson = 0.3;
  params.bending_rigidity = 1e-5;
  params.damping = 0.01;
  spec.continuum = params;
  const ClothModel model = build_grid_cloth(spec);
  ClothState state = initial_grid_state(model, spec, 0.0, 0);
  state.x += 0.01 * Eigen::Matrix3Xd::Random(3, model.particle_count());
  state.v = Eigen::Matrix3Xd::Random(3, model.particle_count());
  const kernels::ContinuumArrays arrays = continuum_arrays(*model.continuum);
  std::vector<double> scratch(model.continuum->force_scratch_size());
  const Eigen::Matrix3Xd still = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  Eigen::Matrix3Xd with_v = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  Eigen::Matrix3Xd without_v = with_v;
  kernels::add_continuum_forces(arrays, state.x.data(), state.v.data(), scratch.data(),
                                with_v.data());
  kernels::add_continuum_forces(arrays, state.x.data(), still.data(), scratch.data(),
                                without_v.data());
  const double expected = -damping_force_power(with_v, without_v, state.v);  // W
  EXPECT_GT(expected, 0.0);
  EXPECT_NEAR(kernels::continuum_damping_power(arrays, state.x.data(), state.v.data()) / expected,
              1.0, 1e-9);
}

}  // namespace
}  // namespace drapelab
