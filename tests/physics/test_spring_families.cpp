// The spring fast path (spring_families.hpp): the same forces as the plain edge loop to rounding on
// every grid shape, whole runs identical to rounding, and bitwise-identical results for 1 and 2
// threads.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "contact/broad_phase_loops.hpp"
#include "drapelab/disc_cloth.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/spring_forces.hpp"
#include "fixtures/sheets.hpp"
#include "forces/body_force_loops.hpp"
#include "forces/spring_families.hpp"
#include "forces/spring_family_loops.hpp"
#include "integrators/particle_loops.hpp"

namespace drapelab {
namespace {

// The solver-step suite's sheet (0.2 kg, held at two corners), lying in the xz plane.
GridClothSpec grid_spec(int nx, int ny) {
  GridClothSpec spec = fixtures::hanging_sheet(nx, ny, 0.2, fixtures::kTenfoldSprings);
  spec.plane = GridPlane::xz;
  return spec;
}

ClothState shaken(const ClothModel& model, const GridClothSpec& spec) {
  ClothState state = initial_grid_state(model, spec, 0.01, 4);
  // The same velocities every call (Eigen's Random would continue std::rand's sequence).
  for (int i = 0; i < model.particle_count(); ++i)
    state.v.col(i) = Eigen::Vector3d(std::sin(0.7 * i), std::cos(1.3 * i), std::sin(2.1 * i + 0.5));
  return state;
}

TEST(SpringFamilies, ForcesEqualThePlainLoopToRoundingOnEveryGrid) {
  for (auto [nx, ny] : {std::pair{2, 2}, {1, 7}, {7, 1}, {3, 9}, {33, 17}, {65, 65}}) {
    SCOPED_TRACE(std::to_string(nx) + " x " + std::to_string(ny));
    const GridClothSpec spec = grid_spec(nx, ny);
    const ClothModel model = build_grid_cloth(spec);
    const ClothState state = shaken(model, spec);
    auto families = SpringFamilies::build(model);
    if (nx * ny < 8) continue;  // too few springs for runs worth a fast path; the plain loop runs
    ASSERT_TRUE(families) << "a grid's springs come in families";
    EXPECT_LE(families->family_count(), 6);
    Eigen::Matrix3Xd plain = Eigen::Matrix3Xd::Constant(3, model.particle_count(), 0.25);
    Eigen::Matrix3Xd fast = plain;
    add_spring_forces(model, state.x, state.v, plain);
    families->add_forces(state.x, state.v, fast);
    EXPECT_LT((fast - plain).cwiseAbs().maxCoeff(), 1e-12 * plain.cwiseAbs().maxCoeff());
  }
}

// The solver's fast path starts the force from gravity and air drag inside the spring kernel's
// first pass: the same bits as the separate body-force pass followed by the springs, on 1 and 2
// threads.
TEST(SpringFamilies, BodyForcesInTheFirstPassEqualTheSeparatePassBitForBit) {
  for (int n : {9, 97}) {  // one thread's region, and one large enough to split among threads
    SCOPED_TRACE(n);
    const GridClothSpec spec = grid_spec(n, n);
    const ClothModel model = build_grid_cloth(spec);
    const ClothState state = shaken(model, spec);
    auto families = SpringFamilies::build(model);
    ASSERT_TRUE(families);
    const Eigen::Matrix3Xd mass = model.mass.transpose().replicate(3, 1);  // kg per coordinate
    const Eigen::Matrix3Xd weight = Eigen::Vector3d(0.3, -9.81, 0.1) * model.mass.transpose();  // N
    const double air = 0.7;  // 1/s
    const int threads_before = kernels::thread_count();
    for (int threads : {1, 2}) {
      kernels::set_thread_count(threads);
      Eigen::Matrix3Xd separate(3, model.particle_count());
      kernels::set_body_forces(model.particle_count(), weight.data(), mass.data(), air,
                               state.v.data(), separate.data());
      families->add_forces(state.x, state.v, separate);
      Eigen::Matrix3Xd fused =
          Eigen::Matrix3Xd::Constant(3, model.particle_count(), 123.0);  // overwritten
      families->set_body_and_spring_forces(state.x, state.v, weight, mass, air, fused);
      EXPECT_TRUE((fused.array() == separate.array()).all()) << threads << " thread(s)";
    }
    kernels::set_thread_count(threads_before);
  }
}

TEST(SpringFamilies, FamiliesWithVaryingSpringsReadPerSpringValuesAndStillEqualThePlainLoop) {
  // A grid's families are uniform (one rest length, ks and kd each); varying one spring of every
  // kind sends those families through the per-slot arrays instead.
  const GridClothSpec spec = grid_spec(33, 17);
  ClothModel model = build_grid_cloth(spec);
  for (std::size_t e = 0; e < model.springs.size(); e += 97) {
    model.springs.ks[e] *= 1.5;
    model.springs.rest_length[e] *= 0.9;
  }
  const ClothState state = shaken(model, spec);
  auto families = SpringFamilies::build(model);
  ASSERT_TRUE(families);
  Eigen::Matrix3Xd plain = Eigen::Matrix3Xd::Constant(3, model.particle_count(), -0.5);
  Eigen::Matrix3Xd fast = plain;
  add_spring_forces(model, state.x, state.v, plain);
  families->add_forces(state.x, state.v, fast);
  EXPECT_LT((fast - plain).cwiseAbs().maxCoeff(), 1e-12 * plain.cwiseAbs().maxCoeff());
  // The varied springs really change the force (the test would pass vacuously otherwise).
  const ClothModel uniform = build_grid_cloth(spec);
  Eigen::Matrix3Xd unvaried = Eigen::Matrix3Xd::Constant(3, model.particle_count(), -0.5);
  add_spring_forces(uniform, state.x, state.v, unvaried);
  EXPECT_GT((unvaried - plain).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(SpringFamilies, PerturbedRestLengthsReadOnlyTheRestArrayAndStillEqualThePlainLoop) {
  // A sheet built from perturbed positions: every rest length differs, ks and kd do not.
  const GridClothSpec spec = grid_spec(33, 17);
  ClothModel model = build_grid_cloth(spec);
  for (std::size_t e = 0; e < model.springs.size(); ++e)
    model.springs.rest_length[e] *= 1.0 + 0.01 * std::sin(0.37 * static_cast<double>(e));
  const ClothState state = shaken(model, spec);
  auto families = SpringFamilies::build(model);
  ASSERT_TRUE(families);
  for (const SpringFamily& family : families->families()) {
    EXPECT_TRUE(family.uniform_stiffness) << "offset " << family.offset;
    EXPECT_FALSE(family.uniform) << "offset " << family.offset;
    EXPECT_FALSE(family.empty_slots.empty())
        << "offset " << family.offset;  // row ends: cleared slots
  }
  Eigen::Matrix3Xd plain = Eigen::Matrix3Xd::Constant(3, model.particle_count(), 0.25);
  Eigen::Matrix3Xd fast = plain;
  add_spring_forces(model, state.x, state.v, plain);
  families->add_forces(state.x, state.v, fast);
  EXPECT_LT((fast - plain).cwiseAbs().maxCoeff(), 1e-12 * plain.cwiseAbs().maxCoeff());
}

TEST(SpringFamilies, MeshesWithManyOffsetsKeepThePlainLoop) {
  DiscSpec disc;
  MeshClothSpec spec;
  spec.mesh = make_disc_mesh(disc);
  spec.mass = 0.01;
  EXPECT_FALSE(SpringFamilies::build(build_mesh_cloth(spec)));
}

ClothState run(const std::shared_ptr<const ClothModel>& model, const GridClothSpec& spec, bool fast,
               int threads) {
  kernels::set_thread_count(threads);
  SpringDamperSettings settings;
  settings.fast_springs = fast;
  SpringDamperSolver solver("s", model, shaken(*model, spec), settings);
  EXPECT_EQ(solver.uses_fast_springs(), fast);
  for (int k = 0; k < 30; ++k) solver.step(2e-5);  // s, within the stable step of these springs
  EXPECT_EQ(solver.status(), SolverStatus::ok) << solver.message();
  kernels::set_thread_count(1);
  return solver.state();
}

TEST(SpringFamilies, RunsMatchThePlainPathAndAreBitwiseIdenticalForOneAndTwoThreads) {
  // Large enough that the loops really split among threads (families of >= 8192 springs).
  const GridClothSpec spec =
      grid_spec(97, 97);  // 97 x 96 = 9312 springs along x: above the threading threshold
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const ClothState plain = run(model, spec, false, 1);
  const ClothState one = run(model, spec, true, 1);
  const ClothState two = run(model, spec, true, 2);
  EXPECT_LT((one.x - plain.x).cwiseAbs().maxCoeff(), 1e-12);  // m, rounding grown over 30 steps
  EXPECT_TRUE((one.x.array() == two.x.array()).all()) << "thread count changed the positions";
  EXPECT_TRUE((one.v.array() == two.v.array()).all()) << "thread count changed the velocities";
}

TEST(SpringFamilies, ShortThreadRunsAndMoreThreadsThanBlocksGiveTheSameBits) {
  // A wide, short sheet (400 x 12: largest offset 800, ten blocks of 512 particles) run on 3 and 16
  // threads: runs shorter than the largest offset, whose gathers all wait for the barrier, and
  // threads with no block at all. Perturbed rest lengths send every family through the rest-array
  // layout.
  const GridClothSpec spec = grid_spec(400, 12);
  ClothModel perturbed = build_grid_cloth(spec);
  for (std::size_t e = 0; e < perturbed.springs.size(); ++e)
    perturbed.springs.rest_length[e] *= 1.0 + 0.01 * std::sin(0.37 * static_cast<double>(e));
  const auto model = std::make_shared<const ClothModel>(perturbed);
  const ClothState plain = run(model, spec, false, 1);
  const ClothState one = run(model, spec, true, 1);
  EXPECT_LT((one.x - plain.x).cwiseAbs().maxCoeff(), 1e-12);  // m
  for (int threads : {3, 16}) {
    const ClothState many = run(model, spec, true, threads);
    EXPECT_TRUE((one.x.array() == many.x.array()).all())
        << threads << " threads changed the positions";
    EXPECT_TRUE((one.v.array() == many.v.array()).all())
        << threads << " threads changed the velocities";
  }
}

}  // namespace
}  // namespace drapelab
