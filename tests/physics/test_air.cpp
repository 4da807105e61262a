// Air (drapelab/air.hpp): a sheet falling face-on reaches the terminal speed sqrt(2 m g /
// (rho C_d A)), edge-on it falls freely, a stiff plate hinged at its top edge settles in a wind at
// the angle where the drag's moment balances gravity's, the force depends on the wind only through
// the relative velocity, lift is across the flow, and the gusts are smooth and reproducible.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <string>

#include "drapelab/air.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/integrators.hpp"
#include "drapelab/spring_damper_solver.hpp"

namespace drapelab {
namespace {

constexpr double kG = 9.81;  // m/s^2

// A 0.5 m square sheet of 20 g (80 g/m^2), stiff enough to stay flat, horizontal (xz) or vertical
// (xy), centred at y = 10 m.
GridClothSpec sheet(GridPlane plane) {
  GridClothSpec spec;
  spec.nx = spec.ny = 9;
  spec.size = {0.5, 0.5};
  spec.plane = plane;
  spec.center = {0.0, 10.0, 0.0};
  spec.areal_density = 0.08;  // kg/m^2: each particle's mass in proportion to its area, as the air
                              // loads it, so the sheet falls flat
  spec.stretch = {200.0, 0.02};
  spec.shear = {20.0, 0.002};
  spec.bend = {2.0, 0.0002};
  return spec;
}

AirSettings still_air() {
  AirSettings air;
  air.enabled = true;
  air.density = 1.2;
  air.drag = 1.0;
  return air;
}

SpringDamperSettings settings_with(Integrator integrator, const AirSettings& air) {
  SpringDamperSettings settings;
  settings.integrator = integrator;
  settings.gravity = {0.0, -kG, 0.0};
  settings.air = air;
  return settings;
}

double mean_vertical_velocity(const ClothState& s) { return s.v.row(1).mean(); }

TEST(Air, AFaceOnSheetReachesItsTerminalSpeed) {
  const GridClothSpec spec = sheet(GridPlane::xz);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const double area = 0.25;                                                                // m^2
  const double terminal = std::sqrt(2.0 * model->total_mass() * kG / (1.2 * 1.0 * area));  // m/s
  for (Integrator integrator : all_integrators()) {
    SCOPED_TRACE(integrator_name(integrator));
    SpringDamperSolver solver("face_on", model, initial_grid_state(*model, spec, 0.0, 0),
                              settings_with(integrator, still_air()));
    // s: explicit Euler is stable only while the springs' damping outweighs its energy gain.
    const double h = integrator == Integrator::explicit_euler ? 5e-5 : 1e-4;
    // 1 s, eight time constants v_t / g: v = v_t tanh(g t / v_t) is within 1e-7 of v_t.
    for (int k = 0; k < static_cast<int>(std::lround(1.0 / h)); ++k) solver.step(h);
    ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
    EXPECT_NEAR(-mean_vertical_velocity(solver.state()) / terminal, 1.0, 0.01);
    RecordProperty(std::string("terminal_over_theory_") + integrator_name(integrator),
                   std::to_string(-mean_vertical_velocity(solver.state()) / terminal));
  }
}

TEST(Air, AnEdgeOnSheetFallsFreely) {
  const GridClothSpec spec = sheet(GridPlane::xy);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  SpringDamperSolver with_air("edge_on", model, initial_grid_state(*model, spec, 0.0, 0),
                              settings_with(Integrator::symplectic_euler, still_air()));
  for (int k = 0; k < 500; ++k) with_air.step(1e-3);
  // Symplectic Euler's free fall after n steps: v = -g n h exactly, whatever the air.
  EXPECT_NEAR(mean_vertical_velocity(with_air.state()), -kG * 0.5, 1e-9);
}

TEST(Air, AirOffChangesNothingBitForBit) {
  const GridClothSpec spec = sheet(GridPlane::xz);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  AirSettings none;  // not enabled
  AirSettings empty = still_air();
  empty.density = 0.0;  // enabled, but every force is +0
  SpringDamperSolver off("off", model, initial_grid_state(*model, spec, 0.001, 3),
                         settings_with(Integrator::symplectic_euler, none));
  SpringDamperSolver zero("zero", model, initial_grid_state(*model, spec, 0.001, 3),
                          settings_with(Integrator::symplectic_euler, empty));
  for (int k = 0; k < 300; ++k) {
    off.step(1e-3);
    zero.step(1e-3);
  }
  EXPECT_EQ(off.state().x, zero.state().x);
  EXPECT_EQ(off.state().v, zero.state().v);
}

// A 20 cm plate of 10 g hinged at its top edge (pinned), in a steady horizontal wind U along z: it
// settles at the angle theta from the vertical where the drag on the plate, whose normal wind is
// U cos theta, balances its weight about the hinge. Each particle i at distance d_i below the hinge
// takes the pressure on its area A_i and carries its mass m_i, so 1/2 rho C_d U^2 cos^2 theta sum
// A_i d_i = g sin theta sum m_i d_i (for a uniform plate, 1/2 rho C_d A U^2 cos^2 theta = m g sin
// theta). Stiff springs keep it flat.
TEST(Air, AHingedPlateSettlesWhereDragBalancesGravity) {
  GridClothSpec spec;
  spec.nx = spec.ny = 9;
  spec.size = {0.2, 0.2};
  spec.plane = GridPlane::xy;
  spec.center = {0.0, 1.0, 0.0};
  spec.areal_density = 0.25;  // kg/m^2: 10 g
  spec.stretch = {2000.0, 0.05};
  spec.shear = {2000.0, 0.05};
  spec.bend = {500.0, 0.01};
  spec.pins = {PinNamed{"edge_max_y"}};
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  AirSettings air = still_air();
  air.wind = {0.0, 0.0, 2.0};  // m/s
  SpringDamperSettings settings = settings_with(Integrator::implicit_euler, air);
  settings.air_damping = 5.0;  // 1/s: settles faster; no force at rest
  SpringDamperSolver solver("plate", model, initial_grid_state(*model, spec, 0.0, 0), settings);
  for (int k = 0; k < 4000; ++k) solver.step(1e-3);  // 4 s
  ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
  // The angle of the bottom edge's middle below the top edge's middle.
  const ClothState& s = solver.state();
  const Eigen::Vector3d top = 0.5 * (s.x.col(9 * 8) + s.x.col(9 * 8 + 8));
  const Eigen::Vector3d bottom = 0.5 * (s.x.col(0) + s.x.col(8));
  const double measured = std::atan2(bottom.z() - top.z(), top.y() - bottom.y());  // rad
  // Solve the balance by bisection; the moments about the hinge come from the model's areas and
  // masses at rest.
  double area_moment = 0.0, mass_moment = 0.0;  // m^3, kg m
  for (int i = 0; i < model->particle_count(); ++i) {
    const double below = model->rest_positions(1, 9 * 8) - model->rest_positions(1, i);  // m
    area_moment += model->vertex_area[i] * below;
    mass_moment += model->mass[i] * below;
  }
  const double push = 0.5 * 1.2 * 1.0 * 4.0 * area_moment, weight = kG * mass_moment;  // N m
  double low = 0.0, high = std::numbers::pi / 2;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (low + high);
    (push * std::cos(mid) * std::cos(mid) > weight * std::sin(mid) ? low : high) = mid;
  }
  const double expected = 0.5 * (low + high);
  EXPECT_NEAR(measured / expected, 1.0, 0.01)
      << "measured " << measured * 180 / std::numbers::pi << " deg, expected "
      << expected * 180 / std::numbers::pi << " deg";
  RecordProperty("plate_angle_deg", std::to_string(measured * 180 / std::numbers::pi));
}

// The force depends on the wind only through u = W - v (Galilean invariance), and without wind the
// drag is a force of the velocity alone, opposing it along the normal.
TEST(Air, TheForceDependsOnTheRelativeVelocityOnly) {
  AirSettings air = still_air();
  air.lift = 0.4;
  const Eigen::Vector3d normal = Eigen::Vector3d(0.2, 1.0, -0.3).normalized();
  const Eigen::Vector3d v(0.3, -1.2, 0.5), w(2.0, 0.1, -0.4);
  const Eigen::Vector3d moving = triangle_air_force(air, 0.01, normal, w - v);
  const Eigen::Vector3d still =
      triangle_air_force(air, 0.01, normal, (w - v) - Eigen::Vector3d::Zero());
  EXPECT_EQ(moving, still);
  air.lift = 0.0;
  const Eigen::Vector3d drag = triangle_air_force(air, 0.01, normal, -v);
  EXPECT_LT(drag.dot(v), 0.0);                                // it opposes the motion
  EXPECT_LT(drag.cross(normal).norm(), 1e-15 * drag.norm());  // along the normal
  EXPECT_NEAR(drag.norm(), 0.5 * 1.2 * 0.01 * std::pow(v.dot(normal), 2), 1e-15);
}

// Lift is across the flow, towards the side the air pushes, of size 1/2 rho C_l A |u_n| |u_t|.
TEST(Air, LiftIsAcrossTheFlow) {
  AirSettings air = still_air();
  air.drag = 0.0;
  air.lift = 1.0;
  const Eigen::Vector3d normal(0.0, 1.0, 0.0);
  const double attack = 20.0 * std::numbers::pi / 180.0;  // the flow 20 degrees below the plate
  const Eigen::Vector3d u = 3.0 * Eigen::Vector3d(std::cos(attack), std::sin(attack), 0.0);
  const Eigen::Vector3d lift = triangle_air_force(air, 0.02, normal, u);
  EXPECT_NEAR(lift.dot(u), 0.0, 1e-14);  // across the flow
  EXPECT_GT(lift.y(), 0.0);              // towards the pushed side (+y: the air rises into it)
  EXPECT_NEAR(lift.norm(), 0.5 * 1.2 * 0.02 * std::abs(u.y()) * std::abs(u.x()), 1e-14);
}

TEST(Air, GustsAreSmoothReproducibleAndOfTheirAmplitude) {
  AirSettings air = still_air();
  air.wind = {3.0, 0.0, 0.0};
  air.gust_amplitude = 1.5;
  air.gust_period = 2.0;
  air.seed = 7;
  const Wind a(air), b(air);
  AirSettings other = air;
  other.seed = 8;
  const Wind c(other);
  double sum_of_squares = 0.0, steepest = 0.0, difference = 0.0;
  const double dt = 0.01;      // s
  const int samples = 200000;  // 2000 s: many periods
  for (int k = 0; k < samples; ++k) {
    const double t = dt * k;
    ASSERT_EQ(a.at(t), b.at(t));  // the same seed: the same bits
    const Eigen::Vector3d w = a.at(t);
    EXPECT_EQ(w.y(), 0.0);  // along the mean wind only
    sum_of_squares += (w.x() - 3.0) * (w.x() - 3.0);
    steepest = std::max(steepest, std::abs(a.at(t + dt).x() - w.x()) / dt);
    difference = std::max(difference, std::abs(c.at(t).x() - w.x()));
  }
  EXPECT_NEAR(std::sqrt(sum_of_squares / samples) / 1.5, 1.0, 0.05);  // RMS = amplitude
  // Smooth: no faster than its fastest sinusoid allows (amplitude x 2 pi / (T/2), times the
  // weights' spread), far from a jump.
  EXPECT_LT(steepest, 4.0 * 1.5 * 2.0 * std::numbers::pi / 1.0);
  EXPECT_GT(difference, 0.5);  // another seed, other gusts
}

// Turbulence: over space its |u'| has the RMS it is given and no mean, it is divergence-free
// (incompressible), frozen in the air that the mean wind carries, the same for the same seed, and
// leaves the gusts as they were.
TEST(Air, TurbulenceHasItsIntensityNoDivergenceAndMovesWithTheWind) {
  AirSettings air = still_air();
  air.wind = {2.0, 0.0, 1.0};
  air.gust_amplitude = 0.5;
  air.gust_period = 2.0;
  air.turbulence_intensity = 0.8;  // m/s
  air.turbulence_length = 0.5;     // m
  air.seed = 11;
  const Wind wind(air), twin(air);
  AirSettings calm = air;
  calm.turbulence_intensity = 0.0;
  const Wind gusts_only(calm);
  ASSERT_TRUE(wind.varies_in_space());
  ASSERT_FALSE(gusts_only.varies_in_space());
  std::mt19937_64 random(3);
  const auto uniform = [&random] { return static_cast<double>(random() >> 11) * 0x1.0p-53; };
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double sum_of_squares = 0.0, worst_divergence = 0.0, worst_frozen = 0.0;
  const int samples = 20000;
  const double h = 1e-5;  // m, for the central differences
  for (int k = 0; k < samples; ++k) {
    const Eigen::Vector3d x(20.0 * uniform(), 20.0 * uniform(), 20.0 * uniform());  // m
    const double t = 10.0 * uniform();                                              // s
    const Eigen::Vector3d u = wind.eddies(t, x);
    ASSERT_EQ(u, twin.eddies(t, x));          // the same seed: the same bits
    ASSERT_EQ(wind.at(t), gusts_only.at(t));  // the gusts are untouched
    ASSERT_EQ(wind.at(t, x), Eigen::Vector3d(wind.at(t) + u));
    mean += u;
    sum_of_squares += u.squaredNorm();
    if (k < 500) {
      double divergence = 0.0;
      for (int d = 0; d < 3; ++d) {
        const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(d);
        divergence += (wind.eddies(t, x + step)[d] - wind.eddies(t, x - step)[d]) / (2.0 * h);
      }
      worst_divergence = std::max(worst_divergence, std::abs(divergence));
      // Carried by the mean wind: 0.7 s later the same eddy is 0.7 W further on.
      const Eigen::Vector3d later = wind.eddies(t + 0.7, x + 0.7 * air.wind);
      worst_frozen = std::max(worst_frozen, (later - u).norm());
    }
  }
  mean /= samples;
  EXPECT_NEAR(std::sqrt(sum_of_squares / samples) / 0.8, 1.0, 0.03);
  EXPECT_LT(mean.norm(), 0.03 * 0.8);
  // The eddies' velocity gradients are about 0.8 m/s over 0.1 m: the divergence is rounding.
  EXPECT_LT(worst_divergence, 1e-5 * 0.8 / 0.1);
  EXPECT_LT(worst_frozen, 1e-12);
  RecordProperty("turbulence_rms_over_intensity",
                 std::to_string(std::sqrt(sum_of_squares / samples) / 0.8));
}

// With turbulence each triangle feels the wind at its centroid: a sheet's air force is the sum of
// triangle_air_force with that wind, a third to each corner.
TEST(Air, EachTriangleFeelsTheWindAtItsCentroid) {
  GridClothSpec spec;
  spec.nx = spec.ny = 5;
  spec.size = {0.4, 0.4};
  spec.plane = GridPlane::xy;
  spec.center = {0.0, 1.0, 0.0};
  spec.mass = 0.01;
  const ClothModel model = build_grid_cloth(spec);
  const ClothState state = initial_grid_state(model, spec, 0.0, 0);
  AirSettings air = still_air();
  air.wind = {0.0, 0.0, 3.0};
  air.turbulence_intensity = 1.0;
  air.turbulence_length = 0.2;
  air.seed = 5;
  const Wind wind(air);
  const double t = 0.3;  // s
  Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  add_air_forces(model, air, wind, t, state.x, state.v, force);
  Eigen::Matrix3Xd expected = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  double spread = 0.0;  // N: how much the triangles' forces differ (the eddies matter)
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (Eigen::Index k = 0; k < model.triangles.cols(); ++k) {
    const Eigen::Vector3d a = state.x.col(model.triangles(0, k));
    const Eigen::Vector3d b = state.x.col(model.triangles(1, k));
    const Eigen::Vector3d c = state.x.col(model.triangles(2, k));
    const Eigen::Vector3d doubled = (b - a).cross(c - a);
    const Eigen::Vector3d f = triangle_air_force(air, 0.5 * doubled.norm(), doubled.normalized(),
                                                 wind.at(t, (a + b + c) / 3.0));
    if (k == 0) first = f;
    spread = std::max(spread, (f - first).norm());
    for (int corner = 0; corner < 3; ++corner) expected.col(model.triangles(corner, k)) += f / 3.0;
  }
  EXPECT_LT((force - expected).norm(), 1e-14);
  EXPECT_GT(spread, 0.1 * first.norm());
}

}  // namespace
}  // namespace drapelab
