// The step allocates nothing. This executable interposes malloc (glibc exports the real one as
// __libc_malloc), counts every heap allocation, and checks that none happens inside step().
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <memory>

#include "drapelab/attachments.hpp"
#include "drapelab/collider.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "fixtures/colliders.hpp"
#include "fixtures/sheets.hpp"

// GCC says AddressSanitizer with __SANITIZE_ADDRESS__, clang with __has_feature.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DRAPELAB_UNDER_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(DRAPELAB_UNDER_ASAN)
#define DRAPELAB_COUNT_ALLOCATIONS 0  // AddressSanitizer owns malloc; the count cannot be taken
#else
#define DRAPELAB_COUNT_ALLOCATIONS 1
#endif

namespace {
std::atomic<long> g_allocations{0};
}

#if DRAPELAB_COUNT_ALLOCATIONS
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void* malloc(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
void* realloc(void* pointer, std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(pointer, size);
}
}
#endif

namespace drapelab {
namespace {

TEST(StepAllocations, CounterSeesAnAllocation) {
  if (!DRAPELAB_COUNT_ALLOCATIONS)
    GTEST_SKIP() << "allocation counting is off under AddressSanitizer";
  const long before = g_allocations.load();
  auto* block = static_cast<volatile char*>(std::malloc(64));
  block[0] = 1;
  std::free(const_cast<char*>(block));
  EXPECT_GT(g_allocations.load(), before);  // the counter works, so the next test can fail
}

// Every explicit scheme. Implicit Euler is left out: Eigen's conjugate gradient allocates its work
// vectors on each solve (a few 3N vectors per step, small beside the solve itself); so is vbd,
// whose coarse step's sparse Cholesky factorisation and solve allocate their work space.
TEST(StepAllocations, StepAllocatesNothingForEveryExplicitIntegrator) {
  if (!DRAPELAB_COUNT_ALLOCATIONS)
    GTEST_SKIP() << "allocation counting is off under AddressSanitizer";
  GridClothSpec spec = fixtures::hanging_sheet(17, 0.1, fixtures::default_springs());
  spec.stretch = {500.0, 0.01};
  for (Integrator integrator : all_integrators()) {
    if (integrator == Integrator::implicit_euler || integrator == Integrator::vbd) continue;
    // Adaptive substeps too (where the scheme allows them): the bound's workspace is built by the
    // first step, and each later step's bound allocates nothing.
    const bool adaptive_allowed = integrator == Integrator::symplectic_euler;
    for (bool adaptive : {false, true}) {
      if (adaptive && !adaptive_allowed) continue;
      auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
      SpringDamperSettings settings;
      settings.integrator = integrator;
      settings.air_damping = 0.1;
      settings.adaptive_substeps = adaptive;
      SpringDamperSolver solver("s", model, initial_grid_state(*model, spec, 0.001, 3), settings);
      const double h = adaptive ? 1e-3 : 1e-5;  // s: adaptive steps split themselves
      solver.step(h);  // first step outside the count, in case a library initialises lazily
      const long before = g_allocations.load();
      for (int k = 0; k < 200; ++k) solver.step(h);
      EXPECT_EQ(g_allocations.load() - before, 0)
          << integrator_name(integrator) << (adaptive ? ", adaptive" : "");
      EXPECT_EQ(solver.status(), SolverStatus::ok);
      if (adaptive) {
        EXPECT_GT(solver.stats().steps, 201);  // really split into substeps
      }
    }
  }
}

TEST(StepAllocations, StepWithContactsAndFrictionAllocatesNothing) {
  if (!DRAPELAB_COUNT_ALLOCATIONS)
    GTEST_SKIP() << "allocation counting is off under AddressSanitizer";
  // Resting on the floor (and the sphere's top), sagging m g / k.
  const GridClothSpec spec = fixtures::flat_sheet(17, 0.6, {0, 0.8 + 0.005 - 3e-6, 0}, 0.05);
  Collider ball = fixtures::ball_collider();
  ball.motion.angular_velocity = {30, 0, 0};  // its top moves along z: friction drags the cloth
  const Collider floor = fixtures::floor_collider(0.8);
  auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  SpringDamperSettings settings;
  settings.contacts = std::make_shared<const ContactModel>(
      std::vector<Collider>{ball, floor}, ContactParameters{500.0, 0.05}, spec.thickness);
  SpringDamperSolver solver("s", model, initial_grid_state(*model, spec, 0.0, 0), settings);
  solver.step(1e-5);
  const long before = g_allocations.load();
  for (int k = 0; k < 200; ++k) solver.step(1e-5);
  EXPECT_EQ(g_allocations.load() - before, 0);
  ASSERT_EQ(solver.contact_totals().size(), 2u);
  EXPECT_GT(solver.contact_totals()[0].contact_count, 0);  // the step really met the colliders
  EXPECT_GT(solver.contact_totals()[0].friction_force, 0.0);
}

// Pins carried by a moving collider: each step places them and records their start for the
// energy ledger's account of the collider's work, in buffers sized when the solver is built.
TEST(StepAllocations, StepWithPinsOnAMovingColliderAllocatesNothing) {
  if (!DRAPELAB_COUNT_ALLOCATIONS)
    GTEST_SKIP() << "allocation counting is off under AddressSanitizer";
  const GridClothSpec spec = fixtures::hanging_sheet(17, 0.1, fixtures::default_springs());
  auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  Collider hand = fixtures::ball_collider();
  hand.motion.velocity = {0.2, 0.0, 0.0};  // m/s: the pins are carried along x
  auto attachments = std::make_shared<Attachments>();
  attachments->colliders = {hand};
  const ClothState start = initial_grid_state(*model, spec, 0.0, 0);
  const Eigen::Isometry3d pose = collider_pose(hand, 0.0);
  for (int i = 0; i < model->particle_count(); ++i)
    if (model->is_pinned(i)) attachments->list.push_back({i, 0, pose.inverse() * start.x.col(i)});
  ASSERT_EQ(attachments->list.size(), 2u);
  SpringDamperSettings settings;
  settings.attachments = attachments;
  SpringDamperSolver solver("s", model, start, settings);
  solver.step(1e-5);
  const long before = g_allocations.load();
  for (int k = 0; k < 200; ++k) solver.step(1e-5);
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_EQ(solver.status(), SolverStatus::ok);
  const int pinned = attachments->list.front().particle;
  EXPECT_NEAR(solver.state().x(0, pinned) - start.x(0, pinned), 0.2 * 201 * 1e-5, 1e-12);
  EXPECT_GT(solver.energy_ledger()->external_work, 0.0);  // the hand pulls the sheet along
}

}  // namespace
}  // namespace drapelab
