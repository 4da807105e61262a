// Google Benchmark micro-benchmarks of the step's kernels: the spring phase (plain edge list and
// the spring-family fast path, per spring), the continuum model's forces and a whole step of either
// model (per particle), the whole step with contacts on 1 and 2 threads, the
// contact phase alone (per contact), the adaptive substeps' shape bound (per particle), and a step
// of implicit Euler with the assembled or the matrix-free solve (with its CG iterations), and the
// per-frame mesh audits (self-intersections, triangle penetration). They measure; nothing here
// asserts a time. Run: build/bench/bench_kernels [--benchmark_filter=Springs]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "contact/contact_pass.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/continuum.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/implicit_euler.hpp"
#include "drapelab/self_intersections.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/spring_forces.hpp"
#include "drapelab/stability.hpp"
#include "drapelab/triangle_penetration.hpp"
#include "forces/continuum_arrays.hpp"
#include "forces/spring_families.hpp"
#include "integrators/shape_bound.hpp"

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
  explicit Sheet(int n)
      : spec(square_sheet(n)),
        model(build_grid_cloth(spec)),
        state(initial_grid_state(model, spec, 1e-3, 1)) {
    state.v.setRandom();
    force.setZero(3, model.particle_count());
  }
  GridClothSpec spec;
  ClothModel model;
  ClothState state;
  Eigen::Matrix3Xd force;
};

// Wall time per item of an iteration (ns): the rate of "giga-items" per second, inverted.
benchmark::Counter nanoseconds_per(double items) {
  return benchmark::Counter(
      items * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void report_per_spring(benchmark::State& bench, const ClothModel& model) {
  bench.counters["ns_per_spring"] = nanoseconds_per(static_cast<double>(model.springs.size()));
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
BENCHMARK(SpringsFamilies)
    ->Args({65, 1})
    ->Args({129, 1})
    ->Args({257, 1})
    ->Args({129, 2})
    ->Args({257, 2});

// The continuum model's forces (membranes, hinges and their damping) on the same sheet, with a
// cotton-like fabric: args are the particles per side and the threads. ns_per_particle compares
// with SpringsFamilies' (whose per-particle cost is ns_per_spring times about 6 springs).
ContinuumParams bench_fabric() {
  ContinuumParams params;
  params.stretch_modulus = 1000.0;
  params.poisson = 0.3;
  params.bending_rigidity = 1e-5;
  params.damping = 1e-4;
  return params;
}

void ContinuumForces(benchmark::State& bench) {
  Sheet sheet(static_cast<int>(bench.range(0)));
  kernels::set_thread_count(static_cast<int>(bench.range(1)));
  const ContinuumElements elements =
      build_continuum_elements(sheet.model.rest_positions, sheet.model.triangles, bench_fabric());
  const kernels::ContinuumArrays arrays = continuum_arrays(elements);
  std::vector<double> scratch(elements.force_scratch_size());
  for (auto _ : bench) {
    kernels::add_continuum_forces(arrays, sheet.state.x.data(), sheet.state.v.data(),
                                  scratch.data(), sheet.force.data());
    benchmark::DoNotOptimize(sheet.force.data());
  }
  bench.counters["ns_per_particle"] =
      nanoseconds_per(static_cast<double>(sheet.model.particle_count()));
}
BENCHMARK(ContinuumForces)
    ->Args({65, 1})
    ->Args({65, 2})
    ->Args({129, 1})
    ->Args({129, 2})
    ->Args({257, 1})
    ->Args({257, 2});

// A whole step of our solver on a free sheet, springs (arg 2 = 0) or continuum (1): symplectic
// Euler (arg 1 = 0) or vbd at 1/120 s with its default sweeps (1). Per particle, so the two models
// compare directly.
void ElasticStep(benchmark::State& bench) {
  GridClothSpec spec = square_sheet(static_cast<int>(bench.range(0)));
  if (bench.range(2) != 0) spec.continuum = bench_fabric();
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  SpringDamperSettings settings;
  settings.integrator = bench.range(1) != 0 ? Integrator::vbd : Integrator::symplectic_euler;
  SpringDamperSolver solver("bench", model, initial_grid_state(*model, spec, 1e-3, 1), settings);
  const double h = bench.range(1) != 0 ? 1.0 / 120.0 : 1e-5;
  for (auto _ : bench) solver.step(h);
  bench.counters["ns_per_particle"] = nanoseconds_per(static_cast<double>(model->particle_count()));
}
BENCHMARK(ElasticStep)
    ->Args({65, 0, 0})
    ->Args({65, 0, 1})
    ->Args({65, 1, 0})
    ->Args({65, 1, 1})
    ->Unit(benchmark::kMicrosecond);

// A sheet laid over a sphere: the particles above the ball's cap (about a fifth of them) start on
// its surface, sunk into the contact radius by their weight's sag, the rest of the sheet level with
// the cap's rim.
struct CappedSheet {
  explicit CappedSheet(int n) : sheet(n) {
    const double radius = 0.3;                             // m
    const Eigen::Vector3d center(0.0, 1.0 - radius, 0.0);  // m
    const double cap = 0.25;                               // m, the cap's horizontal radius
    Collider ball;
    ball.name = "ball";
    ball.shape = ColliderShape::sphere;
    ball.center = center;
    ball.radius = radius;
    contacts = std::make_shared<const ContactModel>(
        std::vector<Collider>{ball}, ContactParameters{1000, 0.2}, sheet.model.thickness);
    model = std::make_shared<const ClothModel>(sheet.model);
    start = initial_grid_state(*model, sheet.spec, 0.0, 1);
    for (int i = 0; i < model->particle_count(); ++i) {
      Eigen::Vector3d p = start.x.col(i);
      const double rho =
          std::min(cap, std::hypot(p.x() - center.x(), p.z() - center.z()));  // m, horizontal
      const double sag = model->mass[i] * 9.81 / 1000.0;  // m: the contact spring holds the weight
      p.y() = center.y() + std::sqrt(radius * radius - rho * rho) + model->thickness - sag;
      start.x.col(i) = p;
    }
  }
  Sheet sheet;
  std::shared_ptr<const ContactModel> contacts;
  std::shared_ptr<const ClothModel> model;
  ClothState start;
};

// A full step of our solver on the capped sheet. The stretched cap lifts off as the run goes on, so
// the mean contact count over the timed steps is reported with the time. On 1 or 2 threads: every
// phase (body forces, springs, contacts, update and health scan) is threaded.
void StepWithContacts(benchmark::State& bench) {
  const CappedSheet capped(static_cast<int>(bench.range(0)));
  kernels::set_thread_count(static_cast<int>(bench.range(1)));
  SpringDamperSettings settings;
  settings.contacts = capped.contacts;
  SpringDamperSolver solver("bench", capped.model, capped.start, settings);
  double contacts = 0.0;
  for (auto _ : bench) {
    solver.step(1e-5);
    contacts += solver.contact_totals().front().contact_count;
  }
  bench.counters["particles"] = capped.model->particle_count();
  bench.counters["mean_contacts"] = contacts / static_cast<double>(bench.iterations());
}
BENCHMARK(StepWithContacts)
    ->Args({65, 1})
    ->Args({65, 2})
    ->Args({129, 1})
    ->Args({129, 2})
    ->Args({257, 1})
    ->Args({257, 2});

// The contact phase alone on the same capped sheet, at its starting state: the broad phase of every
// particle, FCL's closed form for the particles near the ball, the end-of-step normal force and
// friction of each contact, and the totals. Reports the time per contact and per particle.
void ContactPhase(benchmark::State& bench) {
  const CappedSheet capped(static_cast<int>(bench.range(0)));
  kernels::set_thread_count(static_cast<int>(bench.range(1)));
  const ClothModel& model = *capped.model;
  Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  std::vector<ColliderContactTotals> totals;
  ContactWorkspace workspace;
  for (auto _ : bench) {
    capped.contacts->add_contact_forces(model, 0.0, 1e-5, capped.start.x, capped.start.v, force,
                                        totals, nullptr, &workspace,
                                        ContactNormalScheme::linearly_implicit);
    benchmark::DoNotOptimize(force.data());
  }
  const double contacts = totals.front().contact_count;
  bench.counters["contacts"] = contacts;
  bench.counters["ns_per_contact"] = nanoseconds_per(contacts);
  bench.counters["ns_per_particle"] = nanoseconds_per(model.particle_count());
}
BENCHMARK(ContactPhase)->Args({65, 1})->Args({65, 2})->Args({129, 1})->Args({129, 2});

// The adaptive substeps' shape bound (stability.hpp shape_stable_step): every particle's stiffness
// and damping tensors at the current shape and their largest eigenvalues, evaluated once per step
// of the scene (not per substep). Args: particles per side, threads, and 1 for the sums over spring
// families (the solver's choice on a grid) or 0 for the index lists (any cloth). ns_per_particle is
// per evaluation.
void ShapeBound(benchmark::State& bench) {
  Sheet sheet(static_cast<int>(bench.range(0)));
  kernels::set_thread_count(static_cast<int>(bench.range(1)));
  const auto families = SpringFamilies::build(sheet.model);
  const std::vector<SpringFamily>* by_family =
      bench.range(2) != 0 ? &families->families() : nullptr;
  ShapeBoundWorkspace workspace;
  for (auto _ : bench)
    benchmark::DoNotOptimize(
        shape_stable_step(sheet.model, sheet.state.x, 0.1, workspace, by_family));
  bench.counters["ns_per_particle"] = nanoseconds_per(sheet.model.particle_count());
}
BENCHMARK(ShapeBound)
    ->Args({65, 1, 0})
    ->Args({65, 1, 1})
    ->Args({65, 2, 1})
    ->Args({129, 1, 0})
    ->Args({129, 1, 1})
    ->Args({129, 2, 0})
    ->Args({129, 2, 1});

// A step of implicit Euler at h = 1/240 s on a free sheet (no collider) and its conjugate-gradient
// iterations: args are the particles per side, the threads, and 1 for the matrix-free solve on
// spring families (with the spring fast path) or 0 for the assembled sparse matrix (Eigen's CG,
// plain edge list). time / cg_iterations_per_step is the step's cost per iteration, force and
// assembly included.
void ImplicitStep(benchmark::State& bench) {
  Sheet sheet(static_cast<int>(bench.range(0)));
  kernels::set_thread_count(static_cast<int>(bench.range(1)));
  auto model = std::make_shared<const ClothModel>(sheet.model);
  SpringDamperSettings settings;
  settings.integrator = Integrator::implicit_euler;
  settings.implicit.tolerance = 1e-3;
  settings.fast_springs = bench.range(2) != 0;
  SpringDamperSolver solver("bench", model, sheet.state, settings);
  for (auto _ : bench) solver.step(1.0 / 240.0);
  const ImplicitSolveStats& stats = *solver.implicit_stats();
  bench.counters["cg_iterations_per_step"] =
      static_cast<double>(stats.iterations_total) / static_cast<double>(stats.solves);
}
BENCHMARK(ImplicitStep)
    ->Args({65, 1, 0})
    ->Args({65, 1, 1})
    ->Args({65, 2, 1})
    ->Args({129, 1, 0})
    ->Args({129, 1, 1})
    ->Args({129, 2, 1});

// A heap-like crumpled sheet for the self-intersection audit: the n x n sheet of 1 m squeezed to
// 0.3 m along x and z, folded by two crossed waves of 5 cm and jittered by up to 2 mm per particle
// (fixed seed), so that its folds lie on, touch and pass through each other.
Eigen::Matrix3Xd crumpled(const ClothModel& model) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> jitter(-0.002, 0.002);
  Eigen::Matrix3Xd x = model.rest_positions;
  for (int i = 0; i < model.particle_count(); ++i) {
    const double u = x(0, i), w = x(2, i);
    x(0, i) = 0.3 * u + jitter(random);
    x(2, i) = 0.3 * w + jitter(random);
    x(1, i) = 0.05 * std::sin(23.0 * u + 7.0 * w) * std::cos(17.0 * w - 5.0 * u) + jitter(random);
  }
  return x;
}

// The self-intersection audit of one frame: edge list kept, both trees rebuilt, every candidate
// pair decided exactly. Reports the crossing edges found and the time per frame in ms.
void SelfIntersections(benchmark::State& bench) {
  const int n = static_cast<int>(bench.range(0));
  const ClothModel model = build_grid_cloth(square_sheet(n));
  const Eigen::Matrix3Xd x = crumpled(model);
  const SelfIntersectionCounter counter(model.triangles);
  int crossings = 0;
  for (auto _ : bench) {
    crossings = counter.count(x);
    benchmark::DoNotOptimize(crossings);
  }
  bench.counters["crossing_edges"] = crossings;
  bench.counters["edges"] = static_cast<double>(counter.edge_count());
}
BENCHMARK(SelfIntersections)->Arg(65)->Arg(129)->Unit(benchmark::kMillisecond);

// Triangle penetration near its worst case: the n x n sheet of 1 m lying one thickness above a
// collider's top, so that the triangles over it pass the broad phase. Arg 1: the collider, 0 a box
// (0.6 m square top, about a third of the triangles; FCL's GJK and EPA), 1 an upright cylinder
// (radius 0.6 m, every triangle; GJK and EPA), 2 a sphere of radius 0.6 m (closed form; the
// triangles near its top), 3 a floor plane (closed form, every triangle).
void TrianglePenetration(benchmark::State& bench) {
  const int n = static_cast<int>(bench.range(0));
  const ClothModel model = build_grid_cloth(square_sheet(n));
  Collider collider;
  collider.name = "under";
  switch (bench.range(1)) {
    case 0:
      collider.shape = ColliderShape::box;
      collider.half_extents = Eigen::Vector3d(0.3, 0.3, 0.3);
      break;
    case 1:
      collider.shape = ColliderShape::cylinder;
      collider.radius = 0.6;
      collider.height = 0.6;
      break;
    case 2:
      collider.shape = ColliderShape::sphere;
      collider.radius = 0.6;
      collider.center = Eigen::Vector3d(0.0, -0.3, 0.0);
      break;
    default:
      collider.shape = ColliderShape::plane;
      collider.center = Eigen::Vector3d(0.0, 0.3, 0.0);
      break;
  }
  const ContactModel contacts({collider}, ContactParameters{}, model.thickness);
  Eigen::Matrix3Xd x = model.rest_positions;
  x.row(1).setConstant(0.3 + model.thickness);
  double reach = 0.0;
  for (auto _ : bench) {
    reach = triangle_penetration(model, x, contacts, 0.0);
    benchmark::DoNotOptimize(reach);
  }
  bench.counters["reach_mm"] = 1e3 * reach;
}
BENCHMARK(TrianglePenetration)
    ->Args({65, 0})
    ->Args({65, 1})
    ->Args({65, 2})
    ->Args({65, 3})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace drapelab

BENCHMARK_MAIN();
