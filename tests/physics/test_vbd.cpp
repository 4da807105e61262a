// Vertex block descent (integrator vbd) at its own large steps: the known answers of
// docs/validation.md (V1 free fall, V2 hanging chain, V8 cloth on a sphere, V9 friction on an
// incline), energy that never grows on an undamped swinging sheet, the same bits on 1 and 2
// threads, pins that never move, and a stiff sheet that stays stable on a sphere at h = 1/60 s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "drapelab/collider.hpp"
#include "drapelab/collision_metrics.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/loop_threads.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "fixtures/chains.hpp"
#include "fixtures/colliders.hpp"
#include "fixtures/measured.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

constexpr double kGravity = 9.81;  // m/s^2

std::string number(double value) { return fixtures::measured(value, 4); }

SpringDamperSettings vbd_settings(int iterations) {
  SpringDamperSettings settings;
  settings.integrator = Integrator::vbd;
  settings.gravity = {0.0, -kGravity, 0.0};
  settings.vbd.iterations = iterations;
  return settings;
}

struct VbdRun {
  std::shared_ptr<const ClothModel> model;
  std::shared_ptr<const ContactModel> contacts;  // null without colliders
  std::unique_ptr<SpringDamperSolver> solver;

  // Steps of h (s) for `seconds`, stopping at the first unhealthy step.
  void run_for(double seconds, double h) {
    const int steps = static_cast<int>(std::lround(seconds / h));
    for (int k = 0; k < steps && solver->status() == SolverStatus::ok; ++k) solver->step(h);
    ASSERT_EQ(solver->status(), SolverStatus::ok) << solver->message();
  }
  CollisionMetrics collisions() const {
    return compute_collision_metrics(*model, solver->state(), *contacts, solver->state().time);
  }
};

VbdRun make_run(const GridClothSpec& spec, SpringDamperSettings settings,
                std::vector<Collider> colliders = {}, ContactParameters contact = {},
                const ClothState* initial = nullptr) {
  VbdRun r;
  r.model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  if (!colliders.empty()) {
    r.contacts =
        std::make_shared<const ContactModel>(std::move(colliders), contact, spec.thickness);
    settings.contacts = r.contacts;
  }
  const ClothState start = initial ? *initial : initial_grid_state(*r.model, spec, 0.0, 0);
  r.solver = std::make_unique<SpringDamperSolver>("vbd", r.model, start, settings);
  return r;
}

// V1: with no spring acting, each particle's descent is exact in one Newton step, so vbd is
// implicit Euler: the drop after n steps of h is g h^2 n(n+1)/2.
TEST(Vbd, V1FreeFallIsImplicitEulersDiscreteDrop) {
  const GridClothSpec spec = fixtures::with_springs(
      fixtures::flat_sheet(3, 1.0, {0.0, 1.0, 0.0}, 0.09), fixtures::kNoSprings);
  VbdRun r = make_run(spec, vbd_settings(10));
  const double h = 1.0 / 60.0;  // s
  const int n = 120;            // 2 s
  r.run_for(n * h, h);
  const double expected = kGravity * h * h * n * (n + 1.0) / 2.0;  // m
  double worst = 0.0;
  for (int i = 0; i < r.model->particle_count(); ++i) {
    const double drop = r.model->rest_positions(1, i) - r.solver->state().x(1, i);
    EXPECT_NEAR(drop, expected, 1e-12 * expected) << "particle " << i;
    worst = std::max(worst, std::abs(drop / expected - 1.0));
  }
  RecordProperty("worst_relative_error", number(worst));
}

// V2: ten particles of 10 g below a pinned one on springs of 100 N/m. The resting chain is a fixed
// point of every step whatever the sweep count (each particle's Newton step there is zero), so
// once damping has brought it to rest it holds Hooke's statics: spring j (0 at the top) stretches
// by (10 - j) m g / k, in all (m g / k) 55 = 0.053955 m.
TEST(Vbd, V2HangingChainRestsAtTheStaticsOfHookesLaw) {
  const GridClothSpec spec = fixtures::hanging_chain(0.05);  // kd 0.05 N*s/m per spring
  SpringDamperSettings settings = vbd_settings(20);
  settings.air_damping = 5.0;  // 1/s
  VbdRun r = make_run(spec, settings);
  const double h = 1.0 / 60.0;  // s
  r.run_for(30.0, h);           // 1800 steps of 20 sweeps
  const double m = 0.01, k = 100.0, L = 0.05;
  const auto& x = r.solver->state().x;
  EXPECT_LT(r.solver->state().v.cwiseAbs().maxCoeff(), 1e-9);  // m/s: at rest
  double total = 0.0, worst = 0.0;
  for (int j = 0; j < 10; ++j) {  // particle 10 is the top; spring j joins 10 - j and 9 - j
    const double extension = (x.col(10 - j) - x.col(9 - j)).norm() - L;
    const double expected = (10 - j) * m * kGravity / k;
    EXPECT_NEAR(extension, expected, 1e-6 * expected) << "spring " << j;
    worst = std::max(worst, std::abs(extension / expected - 1.0));
    total += extension;
  }
  EXPECT_NEAR(total, 0.053955, 1e-6 * 0.053955);
  const double closed_form = (m * kGravity / k) * 10 * 11 / 2;
  EXPECT_NEAR(total, closed_form, 1e-6 * closed_form);
  RecordProperty("worst_spring_relative_error", number(worst));
  RecordProperty("total_relative_error", number(std::abs(total / closed_form - 1.0)));
}

// V8: a 1 m, 41 x 41 cloth dropped 0.2 m onto a sphere of radius 0.3 m rests on it. At h = 1/120 s
// and 20 sweeps per step it has settled by 4 s (measured: fastest particle 0.014 m/s, deepest
// 6.4 mean sags, contact centroid 12.6 mm off the axis); with 10 sweeps the skirt's corners still
// move at 0.06 m/s there.
TEST(Vbd, V8ClothDroppedOnASphereRestsSymmetricallyAtTheThickness) {
  const double radius = 0.3, stiffness = 1000.0;  // m, N/m
  const GridClothSpec spec = fixtures::soft_sheet(41, 1.0, {0, 0.5 + radius + 0.2, 0}, 0.25);
  const double damping = std::sqrt(stiffness * 0.25 / 1681);  // N*s/m: damping ratio about 1/2
  SpringDamperSettings settings = vbd_settings(20);
  settings.air_damping = 2.0;  // 1/s
  VbdRun r = make_run(spec, settings, {fixtures::ball_collider({0, 0.5, 0}, radius)},
                      {stiffness, damping});
  const double h = 1.0 / 120.0;  // s
  r.run_for(4.0, h);             // 480 steps of 20 sweeps
  const CollisionMetrics c = r.collisions();
  ASSERT_GT(c.contact_count, 200);
  // The tolerance of V8: ten times the mean penalty sag M g / (N_c k) (the skirt's particles carry
  // several times the mean load).
  const double mean_sag = 0.25 * kGravity / (c.contact_count * stiffness);  // m
  EXPECT_GE(c.min_clearance, -10.0 * mean_sag);
  EXPECT_LT(c.max_penetration, 0.1 * spec.thickness);
  // Symmetric about the sphere's vertical axis: the contact set's centroid within one edge length.
  const auto& x = r.solver->state().x;
  Eigen::Vector3d contact_centroid = Eigen::Vector3d::Zero();
  int touching = 0;
  for (int i = 0; i < r.model->particle_count(); ++i)
    if ((x.col(i) - Eigen::Vector3d(0, 0.5, 0)).norm() <= radius + spec.thickness) {
      contact_centroid += x.col(i);
      ++touching;
    }
  ASSERT_GT(touching, 200);
  contact_centroid /= touching;
  EXPECT_LT(std::hypot(contact_centroid.x(), contact_centroid.z()), 1.0 / 40);
  const Eigen::Vector3d centroid = x * r.model->mass / r.model->total_mass();
  EXPECT_LT(std::hypot(centroid.x(), centroid.z()), 1.0 / 40);
  EXPECT_LT(r.solver->state().v.cwiseAbs().maxCoeff(), 0.05);  // m/s: settled
  RecordProperty("min_clearance_over_mean_sag", number(c.min_clearance / mean_sag));
  RecordProperty("max_speed", number(r.solver->state().v.cwiseAbs().maxCoeff()));
  RecordProperty("contact_centroid_offset",
                 number(std::hypot(contact_centroid.x(), contact_centroid.z())));
}

// A 65 x 65 sheet of 0.3 kg, its particles half a millimetre off flat at random, landing on a floor
// at 0.94 m/s (dropped 4.5 cm onto its 5 mm thickness), at vbd's default step and sweeps: at the
// impact, and after it, no particle goes deeper into the thickness than a tenth of it. Backward
// Euler stops a particle of m = 7.1e-5 kg on a contact of k = 1000 N/m within m v / (k h) = 8 um of
// the onset; the limit leaves room for the springs and the sweeps. A particle whose Newton move
// crosses a plane's onset stops where its block energy is least along the move (onset_fraction,
// vbd_loops.cpp): without that, the move went through and the sheet ended the impact step 2.1 mm
// deep.
TEST(Vbd, ASheetLandingFlatStopsAtTheThickness) {
  const GridClothSpec spec = fixtures::soft_sheet(65, 1.2, {0.0, 0.05, 0.0}, 0.3);
  const ClothModel model = build_grid_cloth(spec);
  const ClothState start = initial_grid_state(model, spec, 0.0005, 2);  // m, seed
  const double h = 1.0 / 120.0;                                         // s
  VbdRun r = make_run(spec, vbd_settings(10), {fixtures::floor_collider()}, {1000.0, 0.2}, &start);
  double deepest = 0.0;  // m into the thickness, over every step
  const int steps = static_cast<int>(std::lround(0.25 / h));
  for (int k = 0; k < steps; ++k) {
    r.run_for(h, h);
    deepest = std::max(deepest, r.collisions().max_penetration);
  }
  EXPECT_GT(r.collisions().contact_count, 4000);  // it lies on the floor
  EXPECT_LT(deepest, 0.1 * spec.thickness);
  RecordProperty("deepest_over_thickness", number(deepest / spec.thickness));
}

// V9: a 5 x 5 patch of 10 g laid on a plane tilted by `degrees`, friction 0.3 (mu_s = mu_k), at
// h = 1/120 s with vbd's default 10 sweeps per step. The patch slides as one body, a mode the
// sweeps alone (each particle held by springs of 1000 N/m against an inertia of m / h^2 = 5.8 N/m)
// converge slowly: without the coarse step the acceleration at 20 deg was 6 % of the answer with 10
// sweeps and 99.9 % with 1000; with it, 10 sweeps give it to 3e-6 and a creep of 0.19 mm at 16.2
// deg.
struct InclineRun {
  double creep = 0.0;         // m along the slope from t = 0.5 s to 2.5 s
  double acceleration = 0.0;  // m/s^2 along the slope, from the velocity at 1 s and 2 s
};

InclineRun slide_on_incline(double degrees) {
  const double h = 1.0 / 120.0;                   // s
  Collider incline = fixtures::floor_collider();  // friction 0.3
  incline.rotation = {0, 0, degrees};             // turned about z: the slope descends towards -x
  const GridClothSpec spec = fixtures::soft_sheet(5, 0.1, {0, 0, 0}, 0.01);
  const ClothModel model = build_grid_cloth(spec);
  const Eigen::Matrix3d turn = euler_rotation({0, 0, degrees});
  ClothState start = initial_grid_state(model, spec, 0.0, 0);
  for (int i = 0; i < model.particle_count(); ++i)  // on the slope, resting at the thickness
    start.x.col(i) = turn * (model.rest_positions.col(i) + Eigen::Vector3d(0, spec.thickness, 0));
  VbdRun r = make_run(spec, vbd_settings(10), {incline}, {2000.0, 0.02}, &start);
  const Eigen::Vector3d downhill = turn * Eigen::Vector3d(-1, 0, 0);
  auto position = [&] { return r.solver->state().x.rowwise().mean().dot(downhill); };
  auto velocity = [&] { return r.solver->state().v.rowwise().mean().dot(downhill); };
  InclineRun result;
  r.run_for(0.5, h);
  const double settled = position();
  r.run_for(0.5, h);
  const double v1 = velocity();
  r.run_for(1.0, h);
  const double v2 = velocity();
  r.run_for(0.5, h);
  result.creep = position() - settled;
  result.acceleration = v2 - v1;  // over 1 s
  return result;
}

TEST(Vbd, V9SticksBelowTheFrictionAngle) {
  const double threshold = std::atan(0.3) * 180.0 / std::numbers::pi;  // 16.70 deg
  const InclineRun below = slide_on_incline(threshold - 0.5);
  EXPECT_LT(std::abs(below.creep), 1e-3);  // m over 2 s
  RecordProperty("creep_m", number(below.creep));
}

TEST(Vbd, V9SlidesWithTheCoulombAccelerationAtTwentyDegrees) {
  const double theta = 20.0 * std::numbers::pi / 180.0;
  const double expected = kGravity * (std::sin(theta) - 0.3 * std::cos(theta));  // 0.5897 m/s^2
  const InclineRun run = slide_on_incline(20.0);
  EXPECT_NEAR(run.acceleration, expected, 0.02 * expected);
  RecordProperty("acceleration_relative_error", number(run.acceleration / expected - 1.0));
}

// Kinetic energy, gravity's potential (zero at y = 0) and the springs' energy (J).
double total_energy(const ClothModel& model, const ClothState& state) {
  double energy = 0.0;
  for (int i = 0; i < model.particle_count(); ++i)
    energy += model.mass[i] * (0.5 * state.v.col(i).squaredNorm() + kGravity * state.x(1, i));
  const SpringSet& s = model.springs;
  for (std::size_t e = 0; e < s.size(); ++e) {
    const double stretch = (state.x.col(s.v0[e]) - state.x.col(s.v1[e])).norm() - s.rest_length[e];
    energy += 0.5 * s.ks[e] * stretch * stretch;
  }
  return energy;
}

// Backward Euler only removes energy: a horizontal sheet with undamped springs, pinned along one
// edge and without air drag, swings down at h = 1/60 s without ever holding more energy than at
// the step before, with vbd's default 10 sweeps (measured: at least 0.14 mJ lost in every step).
// An unconverged step can gain energy: with the paper's adaptive initial guess and no coarse step,
// 10 sweeps let the energy rise 0.253 J above its initial 0.981 J (at step 23).
TEST(Vbd, EnergyNeverGrowsOnAnUndampedSwingingSheet) {
  GridClothSpec spec = fixtures::with_springs(fixtures::flat_sheet(15, 1.0, {0, 1.0, 0}, 0.1),
                                              fixtures::kUndampedSprings);
  spec.pins = {PinNamed{"edge_min_x"}};
  VbdRun r = make_run(spec, vbd_settings(10));
  const double initial = total_energy(*r.model, r.solver->state());  // J
  // Rounding of sums of about 10^3 terms of up to 1 J.
  const double allowance = 1e-12 * 1e3;  // J
  double largest_growth = -1e300, largest_step_growth = -1e300, lowest_y = 1.0, before = initial;
  const double h = 1.0 / 60.0;        // s
  for (int k = 0; k < 3 * 60; ++k) {  // 3 s
    r.solver->step(h);
    ASSERT_EQ(r.solver->status(), SolverStatus::ok) << r.solver->message();
    const double energy = total_energy(*r.model, r.solver->state());
    ASSERT_LE(energy, initial + allowance) << "step " << k;
    ASSERT_LE(energy, before + allowance) << "step " << k;
    largest_growth = std::max(largest_growth, energy - initial);
    largest_step_growth = std::max(largest_step_growth, energy - before);
    before = energy;
    lowest_y = std::min(lowest_y, r.solver->state().x.row(1).minCoeff());
  }
  EXPECT_LT(lowest_y, 0.5);  // m: it swung down
  RecordProperty("largest_growth_over_initial_J", number(largest_growth));
  RecordProperty("largest_growth_in_one_step_J", number(largest_step_growth));
}

// A 65 x 65 sheet (4,225 particles, above the 2,048 where the sweeps and the contact search run in
// parallel) falling onto a sphere with friction: 1 and 2 threads give the same bits.
TEST(Vbd, OneAndTwoThreadsGiveTheSameBits) {
  const GridClothSpec spec = fixtures::soft_sheet(65, 1.0, {0, 0.8 + 0.02, 0}, 0.3);
  Collider ball = fixtures::ball_collider();  // friction 0.3, top at y = 0.8 m
  SpringDamperSettings settings = vbd_settings(5);
  settings.vbd.chebyshev_rho = 0.5;
  settings.air_damping = 0.1;  // 1/s
  const int threads_before = kernels::thread_count();
  std::vector<Eigen::Matrix3Xd> ends;
  for (int threads : {1, 2}) {
    kernels::set_thread_count(threads);
    VbdRun r = make_run(spec, settings, {ball}, {2000.0, 0.05});
    r.run_for(0.5, 1.0 / 60.0);  // 30 steps
    EXPECT_GT(r.solver->vbd_stats()->contacts_last, 1000);
    ASSERT_EQ(r.solver->contact_totals().size(), 1u);
    EXPECT_GT(r.solver->contact_totals()[0].friction_force, 0.0);
    ends.push_back(r.solver->state().x);
  }
  kernels::set_thread_count(threads_before);
  ASSERT_EQ(ends[0].cols(), ends[1].cols());
  EXPECT_EQ(std::memcmp(ends[0].data(), ends[1].data(), sizeof(double) * ends[0].size()), 0);
}

// Pinned particles keep their position and a zero velocity, bit for bit, in both orders and with
// Chebyshev acceleration, while the cloth swings against a sphere.
TEST(Vbd, PinnedParticlesNeverMove) {
  GridClothSpec spec = fixtures::hanging_sheet(15, 0.1, fixtures::default_springs());
  spec.pins.push_back(PinNamed{"center"});
  for (int order : {1, 2}) {
    SCOPED_TRACE("order " + std::to_string(order));
    SpringDamperSettings settings = vbd_settings(20);
    settings.vbd.order = order;
    settings.vbd.chebyshev_rho = 0.7;
    VbdRun r = make_run(spec, settings, {fixtures::ball_collider({0.0, 0.6, 0.3}, 0.3)},
                        {2000.0, 0.05}, nullptr);
    int pinned = 0;
    for (int i = 0; i < r.model->particle_count(); ++i) pinned += r.model->is_pinned(i);
    ASSERT_EQ(pinned, 3);
    const ClothState start = r.solver->state();
    for (int k = 0; k < 120; ++k) {  // 2 s
      r.solver->step(1.0 / 60.0);
      ASSERT_EQ(r.solver->status(), SolverStatus::ok) << r.solver->message();
      for (int i = 0; i < r.model->particle_count(); ++i) {
        if (!r.model->is_pinned(i)) continue;
        ASSERT_EQ(r.solver->state().x.col(i), start.x.col(i)) << "particle " << i << ", step " << k;
        ASSERT_EQ(r.solver->state().v.col(i), Eigen::Vector3d::Zero())
            << "particle " << i << ", step " << k;
      }
    }
    EXPECT_GT(r.solver->vbd_stats()->contacts_last, 0);  // the sheet met the sphere
  }
}

// Stretch springs of 20,000 N/m and a contact of 50,000 N/m on particles of 0.092 g at h = 1/60 s:
// omega h is several hundred for both, far beyond any explicit scheme's 2; vbd, with its default 10
// sweeps, stays stable for 1 s.
TEST(Vbd, StiffSheetOnASphereStaysStableAtASixtiethOfASecond) {
  const GridClothSpec spec = fixtures::with_springs(
      fixtures::flat_sheet(33, 1.0, {0, 0.8 + 0.2, 0}, 0.1), fixtures::kStiffSprings);
  Collider ball = fixtures::ball_collider();  // friction 0.3, top at y = 0.8 m
  VbdRun r = make_run(spec, vbd_settings(10), {ball}, {50000.0, 5.0});
  const double h = 1.0 / 60.0;  // s
  for (int k = 0; k < 60; ++k) {
    r.solver->step(h);
    ASSERT_EQ(r.solver->status(), SolverStatus::ok) << r.solver->message();
  }
  EXPECT_TRUE(r.solver->state().x.allFinite());
  EXPECT_TRUE(r.solver->state().v.allFinite());
  EXPECT_GT(r.solver->vbd_stats()->contacts_last, 0);
  // It lies on the sphere, not through it.
  EXPECT_GT(r.collisions().min_clearance, -spec.thickness);
  RecordProperty("min_clearance_m", number(r.collisions().min_clearance));
}

}  // namespace
}  // namespace drapelab
