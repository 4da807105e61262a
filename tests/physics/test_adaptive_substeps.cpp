// The shape-dependent stable step (stability.hpp shape_rate_bounds) and the adaptive substeps that
// follow it: the bound holds the linearised network's largest frequency on flat and crumpled
// sheets, is about half Gershgorin's on a flat one, and a solver splitting its steps by it stays
// stable and close to the fixed-step run.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>

#include "drapelab/grid_cloth.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/stability.hpp"
#include "fixtures/sheets.hpp"
#include "forces/spring_families.hpp"
#include "forces/spring_family_loops.hpp"
#include "forces/spring_jacobian.hpp"
#include "integrators/shape_bound.hpp"
#include "integrators/shape_bound_loops.hpp"

namespace drapelab {
namespace {

using Tensors = ShapeBoundWorkspace;

// The sheet of every test here: n x n particles, 0.2 kg, soft springs, hanging from two corners.
GridClothSpec hanging_sheet(int n) {
  return fixtures::hanging_sheet(n, 0.2, fixtures::kSoftSprings);
}

// The largest eigenvalues of M^-1/2 K M^-1/2 and M^-1/2 D M^-1/2 over the free particles, from the
// assembled linearised stiffness K (spring_jacobian_for_solve) and damping D of the springs at x.
NetworkRates exact_rates(const ClothModel& model, const Eigen::Matrix3Xd& x) {
  const int n = model.particle_count();
  Eigen::MatrixXd stiffness = Eigen::MatrixXd::Zero(3 * n, 3 * n), damping = stiffness;
  const SpringSet& s = model.springs;
  for (std::size_t e = 0; e < s.size(); ++e) {
    const SpringJacobian j = spring_jacobian_for_solve(x.col(s.v0[e]), x.col(s.v1[e]), s.ks[e],
                                                       s.kd[e], s.rest_length[e]);
    const int a = 3 * s.v0[e], b = 3 * s.v1[e];
    for (const auto& [matrix, block] :
         {std::pair{&stiffness, -j.dforce_dx}, std::pair{&damping, -j.dforce_dv}}) {
      matrix->block<3, 3>(a, a) += block;
      matrix->block<3, 3>(b, b) += block;
      matrix->block<3, 3>(a, b) -= block;
      matrix->block<3, 3>(b, a) -= block;
    }
  }
  Eigen::VectorXd scale(3 * n);  // 1/sqrt(m), 0 on pins (their rows and columns drop out)
  for (int i = 0; i < n; ++i) scale.segment<3>(3 * i).setConstant(std::sqrt(model.inverse_mass[i]));
  const auto largest = [&](const Eigen::MatrixXd& m) {
    const Eigen::MatrixXd scaled = scale.asDiagonal() * m * scale.asDiagonal();
    return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(scaled, Eigen::EigenvaluesOnly)
        .eigenvalues()
        .maxCoeff();
  };
  return {largest(stiffness), largest(damping)};
}

TEST(ShapeStepBound, LargestEigenvalueOfThreeByThreeMatchesEigenFromAbove) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Matrix3d> cases = {
      Eigen::Matrix3d::Identity(), Eigen::Vector3d(2, 2, 0).asDiagonal(),
      Eigen::Vector3d(0, 0, 0).asDiagonal(), Eigen::Vector3d(5, 1, 1).asDiagonal()};
  const Eigen::Vector3d w(1, 2, 3);
  cases.push_back(3.0 * w.normalized() * w.normalized().transpose());  // rank one
  for (int k = 0; k < 2000; ++k) {
    Eigen::Matrix3d a;
    for (int c = 0; c < 9; ++c) a(c) = u(random);
    cases.push_back(a * a.transpose() *
                    std::pow(10.0, 4.0 * u(random)));  // PSD, spread over 8 decades
  }
  for (const Eigen::Matrix3d& m : cases) {
    const double expected =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvalues().maxCoeff();
    const double got =
        kernels::largest_symmetric_eigenvalue(m(0, 0), m(1, 1), m(2, 2), m(0, 1), m(0, 2), m(1, 2));
    const double scale = std::max(m.norm(), 1e-300);
    EXPECT_GE(got, expected - 1e-14 * scale) << m;
    EXPECT_NEAR(got, expected, 1e-8 * scale) << m;
  }
}

TEST(ShapeStepBound, HoldsTheLinearisedNetworkOnFlatAndCrumpledSheets) {
  const auto spec = hanging_sheet(7);
  const ClothModel model = build_grid_cloth(spec);
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Tensors tensors;
  const double spacing = 1.0 / 6.0;  // m
  for (double amplitude :
       {0.0, 0.1, 0.5, 1.5}) {  // times the spacing: flat to crumpled past folding
    SCOPED_TRACE(amplitude);
    Eigen::Matrix3Xd x = model.rest_positions;
    for (int i = 0; i < x.cols(); ++i)
      for (int c = 0; c < 3; ++c) x(c, i) += amplitude * spacing * u(random);
    const NetworkRates exact = exact_rates(model, x);
    const NetworkRates bound = shape_rate_bounds(model, x, 0.0, {}, tensors);
    EXPECT_GE(bound.stiffness, exact.stiffness);
    EXPECT_GE(bound.damping, exact.damping);
    // The bound is twice a particle's largest tensor eigenvalue: never more than twice the truth's
    // worst row, and on the flat sheet close to the truth itself.
    if (amplitude == 0.0) {
      EXPECT_LT(bound.stiffness, 1.25 * exact.stiffness);
      const NetworkRates gershgorin = network_rate_bounds(model, 0.0);
      EXPECT_NEAR(bound.stiffness / gershgorin.stiffness, 0.5, 5e-9);  // every spring in the plane
      EXPECT_NEAR(bound.damping / gershgorin.damping, 0.5, 5e-9);
    }
  }
}

// Each particle's own rates, 2 lambda_max(S_i) / m_i and 2 lambda_max(D_i) / m_i, with its tensors
// summed here from the springs at x and their eigenvalues taken by Eigen (0 for a pinned particle).
std::vector<NetworkRates> particle_rates(const ClothModel& model, const Eigen::Matrix3Xd& x) {
  const int n = model.particle_count();
  std::vector<Eigen::Matrix3d> stiffness(n, Eigen::Matrix3d::Zero()),
      damping(n, Eigen::Matrix3d::Zero());
  const SpringSet& s = model.springs;
  for (std::size_t e = 0; e < s.size(); ++e) {
    const Eigen::Vector3d d = x.col(s.v0[e]) - x.col(s.v1[e]);
    const Eigen::Vector3d dir = d.normalized();
    const double across = std::max(0.0, 1.0 - s.rest_length[e] / d.norm());
    const Eigen::Matrix3d block = s.ks[e] * ((1.0 - across) * dir * dir.transpose() +
                                             across * Eigen::Matrix3d::Identity());  // N/m
    for (int end : {s.v0[e], s.v1[e]}) {
      stiffness[end] += block;
      damping[end] += s.kd[e] * dir * dir.transpose();
    }
  }
  const auto largest = [](const Eigen::Matrix3d& m) {
    return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvalues().maxCoeff();
  };
  std::vector<NetworkRates> rates(n);
  for (int i = 0; i < n; ++i)
    rates[i] = {2.0 * largest(stiffness[i]) * model.inverse_mass[i],
                2.0 * largest(damping[i]) * model.inverse_mass[i]};
  return rates;
}

// The per-particle pass runs in chunks of particles (its eigenvalues vectorised over a chunk): on a
// sheet of several chunks, with pins and every particle of its own mass, the bound is the largest
// 2 lambda_max(S_i) / m_i and 2 lambda_max(D_i) / m_i over the free particles, each tensor summed
// here from the springs and its eigenvalue taken by Eigen. A tensor paired with another particle's
// mass, or a pinned particle counted, moves the maximum.
TEST(ShapeStepBound, IsTheLargestParticleRateOverASheetOfManyChunks) {
  const ClothModel base = build_grid_cloth(hanging_sheet(41));  // 1,681 particles: 7 chunks of 256
  ClothModel model = base;
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < model.particle_count(); ++i)
    if (!model.is_pinned(i))
      model.inverse_mass[i] /= std::pow(4.0, u(random));  // masses over a factor 16
  Eigen::Matrix3Xd x = model.rest_positions;
  const double spacing = 1.0 / 40.0;  // m
  for (int i = 0; i < x.cols(); ++i)
    for (int c = 0; c < 3; ++c) x(c, i) += 0.4 * spacing * u(random);
  const std::vector<NetworkRates> rates = particle_rates(model, x);
  NetworkRates expected;
  for (const NetworkRates& rate : rates) {
    expected.stiffness = std::max(expected.stiffness, rate.stiffness);
    expected.damping = std::max(expected.damping, rate.damping);
  }
  Tensors tensors;
  // Both ways of summing a particle's springs: the index lists, and the spring families of the grid
  // (row ends leave empty slots; a particle in the first rows ends no spring of the +2nx family).
  const auto families = SpringFamilies::build(model);
  ASSERT_NE(families, nullptr);
  const int threads_before = kernels::thread_count();
  for (const std::vector<SpringFamily>* by_family :
       {static_cast<const std::vector<SpringFamily>*>(nullptr), &families->families()}) {
    for (int threads : {1, 2}) {
      kernels::set_thread_count(threads);
      SCOPED_TRACE(std::string(by_family ? "families, " : "index lists, ") +
                   std::to_string(threads) + " threads");
      const NetworkRates bound = shape_rate_bounds(model, x, 0.0, {}, tensors, by_family);
      EXPECT_GE(bound.stiffness, expected.stiffness * (1.0 - 1e-12));
      EXPECT_NEAR(bound.stiffness, expected.stiffness, 1e-8 * expected.stiffness);
      EXPECT_GE(bound.damping, expected.damping * (1.0 - 1e-12));
      EXPECT_NEAR(bound.damping, expected.damping, 1e-8 * expected.damping);
    }
  }
  kernels::set_thread_count(threads_before);
}

// The bound is a maximum over particles, which the edges, with the fewest springs, rarely hold:
// here every particle of the first and last two rows and of the first and last columns (where the
// families' loops start and stop: a particle there starts or ends no spring of some family) and a
// few inside bounds the sheet alone, every other particle pinned by a zero inverse mass, so each
// one's own sum over the spring families is checked against its tensors assembled here.
TEST(ShapeStepBound, SpringFamiliesSumEveryParticlesOwnSpringsUpToTheSheetsEdges) {
  const ClothModel base = build_grid_cloth(hanging_sheet(41));
  std::mt19937_64 random(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3Xd x = base.rest_positions;
  for (int i = 0; i < x.cols(); ++i)
    for (int c = 0; c < 3; ++c) x(c, i) += 0.4 / 40.0 * u(random);
  const std::vector<NetworkRates> expected = particle_rates(base, x);
  const auto families = SpringFamilies::build(base);
  ASSERT_NE(families, nullptr);
  Tensors tensors;
  ClothModel alone = base;
  int checked = 0;
  for (int i = 0; i < base.particle_count(); ++i) {
    const int row = i / 41, column = i % 41;
    const bool edge = row < 2 || row > 38 || column == 0 || column == 40;
    if ((!edge && i % 97 != 0) || base.is_pinned(i)) continue;
    alone.inverse_mass.setZero();
    alone.inverse_mass[i] = base.inverse_mass[i];
    const NetworkRates bound = shape_rate_bounds(alone, x, 0.0, {}, tensors, &families->families());
    EXPECT_GE(bound.stiffness, expected[i].stiffness * (1.0 - 1e-12)) << "particle " << i;
    EXPECT_NEAR(bound.stiffness, expected[i].stiffness, 1e-8 * expected[i].stiffness)
        << "particle " << i;
    EXPECT_GE(bound.damping, expected[i].damping * (1.0 - 1e-12)) << "particle " << i;
    EXPECT_NEAR(bound.damping, expected[i].damping, 1e-8 * expected[i].damping) << "particle " << i;
    ++checked;
  }
  EXPECT_GT(checked, 200);
}

// The family sums are the index-list sums in another order: on a crumpled sheet large enough to
// split among threads, with springs of varied rest lengths (so no family is uniform) and a few
// particles pinned, the two bounds agree to rounding, and the family bound has the same bits on 1
// and 2 threads.
TEST(ShapeStepBound, SpringFamiliesGiveTheIndexListBoundToRoundingAndTheSameBitsOnAnyThreadCount) {
  ClothModel model = build_grid_cloth(hanging_sheet(97));  // 9,409 particles
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double& rest : model.springs.rest_length) rest *= 1.0 + 0.2 * u(random);
  for (int i = 0; i < model.particle_count(); ++i)
    if (!model.is_pinned(i)) model.inverse_mass[i] /= std::pow(2.0, u(random));
  Eigen::Matrix3Xd x = model.rest_positions;
  for (int i = 0; i < x.cols(); ++i)
    for (int c = 0; c < 3; ++c) x(c, i) += 0.3 / 96.0 * u(random);
  const auto families = SpringFamilies::build(model);
  ASSERT_NE(families, nullptr);
  Tensors tensors;
  const ContactRates contact{1000.0, 0.2};
  const int threads_before = kernels::thread_count();
  kernels::set_thread_count(1);
  const NetworkRates lists = shape_rate_bounds(model, x, 0.1, contact, tensors);
  const NetworkRates one =
      shape_rate_bounds(model, x, 0.1, contact, tensors, &families->families());
  kernels::set_thread_count(2);
  const NetworkRates two =
      shape_rate_bounds(model, x, 0.1, contact, tensors, &families->families());
  kernels::set_thread_count(threads_before);
  EXPECT_NEAR(one.stiffness, lists.stiffness, 1e-12 * lists.stiffness);
  EXPECT_NEAR(one.damping, lists.damping, 1e-12 * lists.damping);
  EXPECT_EQ(one.stiffness, two.stiffness);
  EXPECT_EQ(one.damping, two.damping);
}

TEST(ShapeStepBound, ContactAndAirAddAsInTheGershgorinBound) {
  const auto spec = hanging_sheet(5);
  const ClothModel model = build_grid_cloth(spec);
  Tensors tensors;
  const NetworkRates bare = shape_rate_bounds(model, model.rest_positions, 0.0, {}, tensors);
  const NetworkRates with =
      shape_rate_bounds(model, model.rest_positions, 0.3, {2000.0, 0.5}, tensors);
  const double lightest = model.inverse_mass.maxCoeff();  // 1/kg: the lightest particle's 1/m
  // Each particle's contact rate adds to its own: the maximum grows by at most the lightest one's.
  EXPECT_GE(with.stiffness, std::max(bare.stiffness, 2000.0 * lightest));
  EXPECT_LE(with.stiffness, (bare.stiffness + 2000.0 * lightest) * (1.0 + 1e-12));
  EXPECT_GE(with.damping, bare.damping + 0.3);
  EXPECT_LE(with.damping, (bare.damping + 0.5 * lightest + 0.3) * (1.0 + 1e-12));
}

SpringDamperSolver make_solver(const std::shared_ptr<const ClothModel>& model,
                               const GridClothSpec& spec, bool adaptive,
                               Integrator integrator = Integrator::symplectic_euler) {
  SpringDamperSettings settings;
  settings.integrator = integrator;
  settings.air_damping = 0.1;
  settings.adaptive_substeps = adaptive;
  return SpringDamperSolver("sheet", model, initial_grid_state(*model, spec, 1e-3, 3), settings);
}

TEST(AdaptiveSubsteps, SplitsEachStepByTheShapeBoundIntoPlainSteps) {
  const auto spec = hanging_sheet(9);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  SpringDamperSolver adaptive = make_solver(model, spec, true);
  SpringDamperSolver plain = make_solver(model, spec, false);
  const double h = 1.0 / 240.0;  // s
  Tensors tensors;
  const double bound =
      step_from_rates(shape_rate_bounds(*model, adaptive.state().x, 0.1, {}, tensors),
                      Integrator::symplectic_euler, 0.0);
  const int expected = static_cast<int>(std::ceil(h / (0.9 * bound)));
  adaptive.step(h);
  ASSERT_EQ(adaptive.stats().steps, expected);
  EXPECT_EQ(adaptive.stats().outer_steps, 1);
  // Fewer than the Gershgorin step would take on this flat sheet.
  EXPECT_LT(
      expected,
      std::ceil(h / (0.9 * stable_step_estimate(*model, 0.1, {}, Integrator::symplectic_euler))));
  // The substeps are ordinary steps: the same bits as stepping h / n by hand (no collider, so the
  // clock's rounding does not enter), and the clock ends exactly at h.
  for (int k = 0; k < expected; ++k) plain.step(h / expected);
  EXPECT_EQ((adaptive.state().x - plain.state().x).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((adaptive.state().v - plain.state().v).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(adaptive.state().time, h);
  const auto counters = adaptive.counters();
  ASSERT_FALSE(counters.empty());
  EXPECT_EQ(counters[0].first, "substeps");
  EXPECT_EQ(counters[0].second, expected);
}

// A sheet hanging from two corners falls, swings and folds for 1.5 s: the shape changes the bound
// as it goes, and the adaptive run stays stable and ends close to a reference run (a quarter of the
// fixed Gershgorin step): within 5 mm, and within three times the fixed-step run's distance to it.
// The substeps are 1.4 times longer than the fixed ones, and the error grows faster than the step
// near the stable limit (measured: 2.7 times).
TEST(AdaptiveSubsteps, SwingingSheetStaysStableAndAsAccurateAsItsStepAllows) {
  const auto spec = hanging_sheet(13);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  {
    const Integrator integrator = Integrator::symplectic_euler;
    SpringDamperSolver adaptive = make_solver(model, spec, true, integrator);
    SpringDamperSolver fixed = make_solver(model, spec, false, integrator);
    SpringDamperSolver reference = make_solver(model, spec, false, integrator);
    const double frame = 1.0 / 60.0, h = frame / 4.0;  // s
    const int fixed_steps =
        static_cast<int>(std::ceil(h / (0.9 * stable_step_estimate(*model, 0.1, {}, integrator))));
    for (int k = 0; k < 360 && adaptive.status() == SolverStatus::ok; ++k) {
      adaptive.step(h);
      for (int s = 0; s < fixed_steps; ++s) fixed.step(h / fixed_steps);
      for (int s = 0; s < 4 * fixed_steps; ++s) reference.step(h / (4 * fixed_steps));
    }
    ASSERT_EQ(adaptive.status(), SolverStatus::ok) << adaptive.message();
    ASSERT_EQ(fixed.status(), SolverStatus::ok) << fixed.message();
    ASSERT_EQ(reference.status(), SolverStatus::ok) << reference.message();
    EXPECT_LT(adaptive.stats().steps, fixed.stats().steps);
    EXPECT_GE(adaptive.stats().substeps_max, adaptive.stats().substeps_min);
    const auto distance = [&](const SpringDamperSolver& run) {  // m, the worst particle
      return (run.state().x - reference.state().x).colwise().norm().maxCoeff();
    };
    EXPECT_LT(distance(adaptive), 3.0 * distance(fixed));
    EXPECT_LT(distance(adaptive), 5e-3);
    double worst = 0.0;
    const SpringSet& s = model->springs;
    for (std::size_t e = 0; e < s.size(); ++e)
      worst = std::max(worst,
                       (adaptive.state().x.col(s.v0[e]) - adaptive.state().x.col(s.v1[e])).norm() /
                           s.rest_length[e]);
    EXPECT_LT(worst, 1.2);
    std::printf("%s: %lld substeps (fixed %lld), distance to reference %.3g m (fixed %.3g m)\n",
                integrator_name(integrator), static_cast<long long>(adaptive.stats().steps),
                static_cast<long long>(fixed.stats().steps), distance(adaptive), distance(fixed));
  }
}

TEST(AdaptiveSubsteps, OneAndTwoThreadsGiveIdenticalBits) {
  // Large enough that the spring loops and the shape bound split among threads.
  const auto spec = hanging_sheet(97);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const int threads_before = kernels::thread_count();
  std::vector<ClothState> ends;
  for (int threads : {1, 2}) {
    kernels::set_thread_count(threads);
    SpringDamperSolver solver = make_solver(model, spec, true);
    for (int k = 0; k < 3; ++k) solver.step(1.0 / 120.0);
    ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
    ends.push_back(solver.state());
  }
  kernels::set_thread_count(threads_before);
  EXPECT_EQ(ends[0].step_count, ends[1].step_count);
  EXPECT_TRUE((ends[0].x.array() == ends[1].x.array()).all())
      << "thread count changed the positions";
  EXPECT_TRUE((ends[0].v.array() == ends[1].v.array()).all())
      << "thread count changed the velocities";
}

// Without shear or bend springs the hanging sheet folds up quickly, lining up the stretch springs
// at many particles (the case where a particle's largest tensor eigenvalue climbs towards its
// trace): the bound follows within each 1/120 s step, and the run stays stable.
TEST(AdaptiveSubsteps, SheetWithoutShearSpringsFoldsUpStably) {
  GridClothSpec spec = hanging_sheet(17);
  spec.shear = {0.0, 0.0};
  spec.bend = {0.0, 0.0};
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  SpringDamperSolver solver = make_solver(model, spec, true);
  for (int k = 0; k < 240 && solver.status() == SolverStatus::ok; ++k) solver.step(1.0 / 120.0);
  ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
  EXPECT_GT(solver.stats().substeps_max,
            solver.stats().substeps_min);  // the bound moved with the shape
}

TEST(AdaptiveSubsteps, AStoppedRunSaysWhichSubstepAndSuggestsTurningThemOff) {
  const auto spec = hanging_sheet(9);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  SpringDamperSettings settings;
  settings.adaptive_substeps = true;
  settings.max_speed = 0.05;  // m/s: the falling sheet passes it within the first steps
  SpringDamperSolver solver("sheet", model, initial_grid_state(*model, spec, 1e-3, 3), settings);
  for (int k = 0; k < 60 && solver.status() == SolverStatus::ok; ++k) solver.step(1.0 / 120.0);
  ASSERT_EQ(solver.status(), SolverStatus::unstable);
  const std::string& message = solver.message();
  EXPECT_NE(message.find("after step " + std::to_string(solver.state().step_count)),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("adaptive_substeps: false"), std::string::npos) << message;
}

TEST(AdaptiveSubsteps, RefusesEverySchemeButSymplecticEuler) {
  const auto spec = hanging_sheet(3);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  for (Integrator integrator : all_integrators()) {
    if (integrator == Integrator::symplectic_euler) continue;
    EXPECT_THROW(make_solver(model, spec, true, integrator), std::invalid_argument)
        << integrator_name(integrator);
  }
}

}  // namespace
}  // namespace drapelab
