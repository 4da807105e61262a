// Google Benchmark micro-benchmarks of the step's kernels: the spring phase (plain edge list and the
// spring-family fast path, per spring), the contact phase (per particle) and one conjugate-gradient
// solve of implicit Euler (per iteration). They measure; nothing here asserts a time.
// Run: build/bench/bench_kernels [--benchmark_filter=Springs]
#include <benchmark/benchmark.h>

#include <memory>

#include "drapelab/contact_model.hpp"
#include "drapelab/forces.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/implicit_euler.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/spring_families.hpp"

namespace drapelab {
namespace {

GridClothSpec square_sheet(int n) {
  GridClothSpec spec;
  spec.nx = spec.ny = n;
  spec.mass = 0.25;
  spec.stretch = {1000.0, 0.01};
  spec.shear = {100.0, 0.005};
  spec.bend = {5.0, 0.001};
  return spec;
}

struct Sheet {
  explicit Sheet(int n) : spec(square_sheet(n)), model(build_grid_cloth(spec)), state(initial_grid_state(model, spec, 1e-3, 1)) {
    state.v.setRandom();
    force.setZero(3, model.particle_count());
  }
  GridClothSpec spec;
  ClothModel model;
  ClothState state;
  Eigen::Matrix3Xd force;
};

// Wall time per spring (ns): the rate of "giga-springs" per second, inverted.
void report_per_spring(benchmark::State& bench, const ClothModel& model) {
  bench.counters["ns_per_spring"] =
      benchmark::Counter(static_cast<double>(model.springs.size()) * 1e-9,
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void SpringsPlain(benchmark::State& bench) {
  Sheet sheet(static_cast<int>(bench.range(0)));
  for (auto _ : bench) {
    add_spring_forces(sheet.model, sheet.state.x, sheet.state.v, sheet.force);
    benchmark::DoNotOptimize(sheet.force.data());
  }
  report_per_spring(bench, sheet.model);
}
BENCHMARK(SpringsPlain)->Arg(65)->Arg(129)->Arg(257);

void SpringsFamilies(benchmark::State& bench) {
  Sheet sheet(static_cast<int>(bench.range(0)));
  kernels::set_thread_count(static_cast<int>(bench.range(1)));
  auto families = SpringFamilies::build(sheet.model);
  for (auto _ : bench) {
    families->add_forces(sheet.state.x, sheet.state.v, sheet.force);
    benchmark::DoNotOptimize(sheet.force.data());
  }
  report_per_spring(bench, sheet.model);
}
BENCHMARK(SpringsFamilies)->Args({65, 1})->Args({129, 1})->Args({257, 1})->Args({129, 2})->Args({257, 2});

// A full step of our solver with a sphere under the sheet (contacts on about a fifth of it).
void StepWithContacts(benchmark::State& bench) {
  Sheet sheet(static_cast<int>(bench.range(0)));
  Collider ball;
  ball.name = "ball";
  ball.shape = ColliderShape::sphere;
  ball.center = {0.0, 0.7005, 0.0};  // touching the sheet at y = 1 m from below, 0.3 m radius
  ball.radius = 0.3;
  SpringDamperSettings settings;
  settings.contacts = std::make_shared<const ContactModel>(std::vector<Collider>{ball}, ContactParameters{1000, 0.2},
                                                           sheet.model.thickness);
  auto model = std::make_shared<const ClothModel>(sheet.model);
  SpringDamperSolver solver("bench", model, initial_grid_state(*model, sheet.spec, 0.0, 1), settings);
  for (auto _ : bench) solver.step(1e-5);
  bench.counters["particles"] = model->particle_count();
}
BENCHMARK(StepWithContacts)->Arg(65)->Arg(129);

// Conjugate-gradient cost per iteration of implicit Euler at h = 1/240 s.
void ImplicitSolve(benchmark::State& bench) {
  Sheet sheet(static_cast<int>(bench.range(0)));
  auto model = std::make_shared<const ClothModel>(sheet.model);
  SpringDamperSettings settings;
  settings.integrator = Integrator::implicit_euler;
  SpringDamperSolver solver("bench", model, sheet.state, settings);
  for (auto _ : bench) solver.step(1.0 / 240.0);
  const auto& stats = solver.implicit_system()->stats();
  bench.counters["cg_iterations_per_step"] = static_cast<double>(stats.iterations_total) / static_cast<double>(stats.solves);
}
BENCHMARK(ImplicitSolve)->Arg(33)->Arg(65);

}  // namespace
}  // namespace drapelab

BENCHMARK_MAIN();
