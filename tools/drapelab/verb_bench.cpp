// drapelab bench: the cost of every solver on a fixed set of scenes and resolutions, measured in
// one process run so the ratios compare like with like. Our solver runs twice: `ours`, vertex block
// descent at its default step and sweeps, and `ours_explicit`, symplectic Euler in adaptive
// substeps at 0.9 of its shape's stable step on the spring fast path (OpenMP threads in every
// phase of both); Bullet's classic cloth at its cheapest stable setting (a 240 Hz
// step with 4 iterations, halved until it holds); Bullet's deformable world at its own stable step
// (skipped above 65 x 65 particles: it costs minutes there); MuJoCo's cloth at its stable step
// (skipped where its buffer holds too few contacts: 129 x 129). Once per scene and size, a
// reference run (our cloth, symplectic Euler at a fixed quarter of its stable step) gives every
// solver's distance to it at the final frame. Writes bench.csv and bench.md; the numbers are
// measurements, never checked against targets.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <thread>

#include "drapelab/loop_threads.hpp"
#include "drapelab/mujoco/mujoco_mapping.hpp"
#include "drapelab/run_folder/files.hpp"
#include "drapelab/runner/bench_table.hpp"
#include "drapelab/runner/run_scene.hpp"
#include "drapelab/runner/simulate_solver.hpp"
#include "drapelab/runner/trial_scene.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/stability.hpp"
#include "interrupt.hpp"
#include "verbs.hpp"

namespace drapelab::cli {

using namespace drapelab::runner;  // the run pipeline: this file parses and prints
namespace {

namespace fs = std::filesystem;

// The solvers every bench scene runs, replacing the scene's own list (the entries of its `solvers`
// list, in scene-file syntax). The first spring_damper entry is "ours", the denominator of every
// cost ratio; further spring_damper entries are rows like any other.
const std::string kSolvers =
    "{name: ours, type: spring_damper, integrator: vbd, host: none},"
    " {name: ours_explicit, type: spring_damper, integrator: symplectic_euler, "
    "adaptive_substeps: true, host: none},"
    " {name: bullet_classic, type: bullet_softbody, iterations: 4, dt: 0.004166666666666667},"
    " {name: bullet_deformable, type: bullet_deformable}";
// MuJoCo's cloth, after them where its model fits MuJoCo 2.2 (mujoco_skip_reason).
const std::string kMujoco = "{name: mujoco, type: mujoco}";
// The reference run, appended to the list so the loader checks it and fills in its defaults; its
// automatic step is then replaced by a quarter of the stable step (reference_spec).
const std::string kReference =
    "{name: reference, type: spring_damper, integrator: symplectic_euler, host: none}";
constexpr int kReferenceStepFraction = 4;  // the reference's step is 1/4 of the stable step
constexpr int kLargestDeformable = 65;     // particles per side
constexpr int kClassicHalvings = 3;        // 240 Hz, then 480, 960, 1920 Hz

struct Measured {
  runner::SimulationResult result;
  double max_penetration = 0.0;                    // m, over every recorded frame
  double max_stretch = 0.0;                        // over every recorded frame
  std::optional<int> most_self_intersections;      // over every recorded frame
  std::optional<double> max_triangle_penetration;  // m, over every recorded frame
  Eigen::Matrix3Xd last_x;                         // m, the positions at the last recorded frame
};

// Why Bullet's deformable world does not run at this size (empty: it runs): minutes per run above
// 65 x 65.
std::string skip_reason(const scene::SolverSpec& spec, int n) {
  if (spec.type == SolverType::bullet_deformable && n > kLargestDeformable)
    return "over " + std::to_string(kLargestDeformable) + " x " +
           std::to_string(kLargestDeformable) + ": minutes per run";
  return "";
}

// Why MuJoCo's cloth does not run on n x n particles (empty: it runs), decided before the scene
// is loaded, since the loader refuses a model MuJoCo 2.2 cannot size: its 2 GB buffer holds fewer
// contacts than a quarter of the particles, where a drape touches with most of them, or its stack
// would pass 2^31 numbers (docs/mujoco.md, "Memory").
std::string mujoco_skip_reason(int n) {
  const std::int64_t particles = static_cast<std::int64_t>(n) * n, dofs = 3 * particles;
  const std::int64_t contacts = mujoco::contact_capacity(0, particles, dofs);
  const auto solver =
      mujoco::chosen_solver(mujoco::ConstraintSolver::automatic, static_cast<int>(dofs));
  if (4 * contacts >= particles &&
      mujoco::stack_size(contacts, dofs, particles + 1, solver) <= INT32_MAX)
    return "";
  return "MuJoCo 2.2's 2 GB buffer holds " + std::to_string(contacts) + " contacts for " +
         std::to_string(particles) + " particles";
}

Measured measure(const scene::Scene& scene, const scene::SolverSpec& spec,
                 const runner::SceneSetup& setup, const std::atomic<bool>& interrupt) {
  Measured m;
  runner::SimulationOptions options;
  options.interrupt = &interrupt;
  options.stretch_limit = 1.0;  // the stability verb's rule: twice the rest length has blown up
  options.on_frame = [&](int, const ClothState& state, const ClothMetrics& metrics) {
    m.max_stretch = std::max(m.max_stretch, metrics.max_stretch);
    if (metrics.max_penetration)
      m.max_penetration = std::max(m.max_penetration, *metrics.max_penetration);
    if (metrics.self_intersections)
      m.most_self_intersections =
          std::max(m.most_self_intersections.value_or(0), *metrics.self_intersections);
    if (metrics.triangle_penetration)
      m.max_triangle_penetration =
          std::max(m.max_triangle_penetration.value_or(0.0), *metrics.triangle_penetration);
    m.last_x = state.x;  // the final frame's, once the run has ended
  };
  m.result = runner::simulate_solver(scene, spec, setup, options);
  return m;
}

// Every run of one solver's setting in one cell: the fastest is reported, with the spread of the
// wall times. Our solver and Bullet's are deterministic, so a repeat that changes the physics
// (status, max stretch or max penetration) is worth a warning. An interrupted run only sets
// `interrupted`: its time is that of part of a run.
struct SolverRuns {
  scene::SolverSpec trial;
  bool skipped = false;
  std::string skip_reason;  // when skipped
  bool reference = false;   // the reference run of the cell, not one of kSolvers
  Measured fastest;
  double slowest_wall = 0.0;  // s
  int count = 0;
  bool differed = false, interrupted = false;

  void add(Measured m) {
    interrupted = m.result.interrupted();
    if (interrupted) return;
    if (count > 0 &&
        (m.result.status != fastest.result.status || m.max_stretch != fastest.max_stretch ||
         m.max_penetration != fastest.max_penetration))
      differed = true;
    slowest_wall = std::max(slowest_wall, m.result.wall_seconds);
    if (count == 0 || m.result.wall_seconds < fastest.result.wall_seconds) fastest = std::move(m);
    ++count;
  }
};

BenchRow bench_row(const scene::Scene& scene, int n, const ClothModel& model, const SolverRuns& r) {
  BenchRow row;
  row.scene = scene.name;
  row.size = n;
  row.particles = model.particle_count();
  row.springs = static_cast<long long>(model.springs.size());
  row.solver = r.trial.name;
  row.type = solver_type_name(r.trial.type);
  if (r.skipped) {
    row.status = "skipped";
    row.setting = r.skip_reason;
    return row;
  }
  const runner::SimulationResult& result = r.fastest.result;
  row.setting = r.reference ? std::string(integrator_name(r.trial.integrator)) + " at 1/" +
                                  std::to_string(kReferenceStepFraction) + " stable step"
                : r.trial.type == SolverType::spring_damper
                    ? std::string(integrator_name(r.trial.integrator))
                : r.trial.type == SolverType::bullet_softbody
                    ? std::to_string(r.trial.iterations) + " iterations"
                : r.trial.type == SolverType::mujoco
                    ? std::string(mujoco::constraint_solver_name(mujoco::chosen_solver(
                          r.trial.mujoco.constraint_solver, 3 * row.particles))) +
                          " at its stable step"
                    : "its stable step";
  if (r.trial.type == SolverType::spring_damper && r.trial.integrator == Integrator::vbd)
    row.setting += " (" + std::to_string(r.trial.vbd.iterations) + " sweeps" +
                   (r.trial.vbd.order == 2 ? ", BDF2" : "") + ")";
  row.dt = r.trial.dt;
  row.status = solver_status_name(result.status);
  row.wall_per_simulated = result.wall_seconds_per_simulated_second();
  row.ms_per_step = result.ms_per_step();
  if (r.trial
          .adaptive_substeps) {  // report the integrator's own steps: the mean substep and its cost
    row.setting += " (adaptive substeps)";
    const double substeps = result.counter("substeps").value_or(0.0);
    if (substeps > 0.0) {
      row.dt = result.simulated_seconds() / substeps;
      row.ms_per_step = 1e3 * result.wall_seconds / substeps;
    }
  }
  row.max_stretch = r.fastest.max_stretch;
  row.max_penetration = r.fastest.max_penetration;
  row.self_intersections = r.fastest.most_self_intersections;
  row.triangle_penetration = r.fastest.max_triangle_penetration;
  row.second_half_wall_per_simulated =
      result.second_half_wall_seconds_per_simulated_second(scene.frame_period());
  row.runs = r.count;
  row.wall_spread = result.wall_seconds > 0.0 ? r.slowest_wall / result.wall_seconds : 1.0;
  return row;
}

// The reference's setting: `spec` (kReference as the loader read it) at a fixed step of at most
// 1/kReferenceStepFraction of symplectic Euler's stable step estimate on this cloth (the estimate
// the loader's automatic step takes 0.9 of), rounded down to a whole number of steps per frame. The
// loader has checked that 0.9 of that estimate gives at most 1e7 steps per frame, so the count here
// fits an int.
scene::SolverSpec reference_spec(const scene::Scene& scene, const ClothModel& model,
                                 scene::SolverSpec spec) {
  const double stable = stable_step_estimate(model, scene.cloth.air_damping, scene.contact_rates(),
                                             Integrator::symplectic_euler);  // s, may be infinite
  const double frame_period = scene.frame_period();                          // s
  const double steps = std::max(1.0, std::ceil(frame_period * kReferenceStepFraction / stable));
  spec = with_steps_per_frame(std::move(spec), frame_period, static_cast<int>(steps));
  // The loader's note gave its automatic step; say which one runs instead.
  std::cerr << "note: solver '" << spec.name << "': the bench runs it at " << spec.steps_per_frame
            << " steps per frame instead (dt = " << format_number(spec.dt) << " s, at most 1/"
            << kReferenceStepFraction << " of the stable step estimate " << format_number(stable)
            << " s)\n";
  return spec;
}

bool ended_ok(const runner::SimulationResult& result) {
  return result.status == SolverStatus::ok && result.stopped_by == runner::StopCause::none;
}

// m: the root-mean-square distance between the two runs' particles at their final frames, matched
// by index (every solver keeps our node order); nothing unless both ran to the end.
std::optional<double> rms_distance(const Measured& a, const Measured& b) {
  if (!ended_ok(a.result) || !ended_ok(b.result) || a.last_x.cols() == 0 ||
      a.last_x.cols() != b.last_x.cols())
    return std::nullopt;
  return std::sqrt((a.last_x - b.last_x).colwise().squaredNorm().mean());
}

// The rows of one scene and size, in the order run, printed as they are added. The ratios'
// denominator is ours, the first spring_damper solver of kSolvers.
void add_cell_rows(BenchTable& table, const scene::Scene& scene, int n, const ClothModel& model,
                   const std::vector<SolverRuns>& runs) {
  double ours_cost = 0.0, ours_second_half_cost = 0.0;  // wall s per simulated s
  const auto ours = std::find_if(runs.begin(), runs.end(), [](const SolverRuns& r) {
    return !r.reference && !r.skipped && r.trial.type == SolverType::spring_damper;
  });
  if (ours != runs.end()) {
    const BenchRow row = bench_row(scene, n, model, *ours);
    ours_cost = row.wall_per_simulated;
    ours_second_half_cost = row.second_half_wall_per_simulated;
  }
  const auto reference =
      std::find_if(runs.begin(), runs.end(), [](const SolverRuns& r) { return r.reference; });
  for (const SolverRuns& r : runs) {
    BenchRow row = bench_row(scene, n, model, r);
    if (!r.skipped) {
      row.cost_ratio = ours_cost > 0.0 ? row.wall_per_simulated / ours_cost : 0.0;
      row.second_half_cost_ratio = ours_second_half_cost > 0.0
                                       ? row.second_half_wall_per_simulated / ours_second_half_cost
                                       : 0.0;
      if (reference != runs.end())
        row.rms_to_reference = rms_distance(r.fastest, reference->fastest);
      std::cout << format_row(row) << std::endl;
    }
    table.rows.push_back(row);
  }
}

std::string cpu_name() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

}  // namespace

void add_bench_options(CLI::App& verb, BenchArguments& arguments) {
  verb.add_flag("--quick", arguments.quick, "33 x 33 particles only, 0.1 s per run (a smoke test)");
  verb.add_option("--out", arguments.out, "Folder for bench.csv and bench.md (default out/bench)");
  verb.add_option("--sizes", arguments.sizes, "Particles per side (default 33,65,129,257)")
      ->delimiter(',');
  verb.add_option("--scenes", arguments.scenes,
                  "Scene files (default scenes/sphere_drape.yaml, scenes/table_drape.yaml, "
                  "scenes/curtain.yaml)")
      ->delimiter(',');
  verb.add_option("--duration", arguments.duration,
                  "Simulated seconds per run (default 0.5; 0.1 with --quick)");
  verb.add_option("--threads", arguments.threads,
                  "Threads for our solver's loops, fixed (default: every core the machine's other "
                  "processes leave free, step by step)");
  verb.add_option(
      "--repeat", arguments.repeat,
      "Runs of every solver in every cell, interleaved; the fastest is reported (default 1)");
  verb.add_flag("--no-reference", arguments.no_reference,
                "Skip the reference run of every cell (the rms_to_reference column stays empty)");
}

int bench_verb(const BenchArguments& arguments, const std::atomic<bool>& interrupt) {
  // Ctrl-C stops the current measurement; the cells measured so far are written.
  const PollingSection polling;
  std::vector<int> sizes = arguments.sizes;
  if (sizes.empty())
    sizes = arguments.quick ? std::vector<int>{33} : std::vector<int>{33, 65, 129, 257};
  std::vector<std::string> scenes = arguments.scenes;
  if (scenes.empty())
    scenes = {"scenes/sphere_drape.yaml", "scenes/table_drape.yaml", "scenes/curtain.yaml"};
  const double duration =
      arguments.duration > 0.0 ? arguments.duration : (arguments.quick ? 0.1 : 0.5);
  const fs::path out = arguments.out.empty() ? fs::path("out/bench") : fs::path(arguments.out);
  const int repeat = arguments.repeat;
  if (repeat < 1 || repeat > 100) {
    std::cerr << "error: --repeat: " << repeat << " runs is outside 1..100\n";
    return kExitBadInput;
  }
  for (int n : sizes)
    if (n < 2 || n > 2000) {
      std::cerr << "error: --sizes: " << n << " particles per side is outside 2..2000\n";
      return kExitBadInput;
    }
  // Without --threads our loops take every core the other processes leave them, step by step.
  if (arguments.threads > 0) kernels::set_thread_count(arguments.threads);

  BenchTable table;
  table.machine = cpu_name() + ", " + std::to_string(std::thread::hardware_concurrency()) +
                  " cores, at most " + std::to_string(kernels::thread_count()) +
                  " threads for our solver's loops";
  for (const std::string& file : scenes)
    for (int n : sizes) {
      const std::string resolution =
          "cloth.resolution=[" + std::to_string(n) + ", " + std::to_string(n) + "]";
      const bool with_reference = !arguments.no_reference;
      const std::string mujoco_skipped = mujoco_skip_reason(n);
      const std::string solvers = "solvers=[" + kSolvers +
                                  (mujoco_skipped.empty() ? ", " + kMujoco : "") +
                                  (with_reference ? ", " + kReference : "") + "]";
      std::shared_ptr<const ClothModel> model;
      auto scene = load_trial_scene(file, {resolution, solvers}, duration, &model);
      if (!scene) return kExitBadInput;  // the loader printed why
      const runner::SceneSetup setup = runner::build_scene_setup(*scene, model);
      std::optional<scene::SolverSpec> reference;  // run once, after the solvers and their repeats
      if (with_reference) {
        reference = reference_spec(*scene, *setup.model, scene->solvers.back());
        scene->solvers.pop_back();
      }
      // First each solver's setting and its first run, then the repeats, round by round across the
      // solvers, so that a slow spell of the machine falls on all of them alike.
      std::vector<SolverRuns> runs;
      bool stopped = false;  // interrupted: the runs completed so far still make rows
      for (const auto& spec : scene->solvers) {
        SolverRuns r;
        r.trial = spec;
        r.skip_reason = skip_reason(spec, n);
        r.skipped = !r.skip_reason.empty();
        if (!r.skipped) {
          r.add(measure(*scene, r.trial, setup, interrupt));
          // Bullet's classic cloth: halve the step until it holds (its cheapest stable setting).
          for (int halving = 0;
               spec.type == SolverType::bullet_softbody && halving < kClassicHalvings &&
               !r.interrupted && r.fastest.result.status != SolverStatus::ok;
               ++halving) {
            SolverRuns halved;
            halved.trial =
                with_steps_per_frame(r.trial, scene->frame_period(), 2 * r.trial.steps_per_frame);
            halved.add(measure(*scene, halved.trial, setup, interrupt));
            r = std::move(halved);
          }
        }
        if ((stopped = r.interrupted)) break;
        runs.push_back(std::move(r));
      }
      if (!mujoco_skipped.empty() && !stopped) {  // its row, with the reason
        SolverRuns r;
        r.trial.name = "mujoco";
        r.trial.type = SolverType::mujoco;
        r.skipped = true;
        r.skip_reason = mujoco_skipped;
        runs.push_back(std::move(r));
      }
      for (int round = 1; round < repeat && !stopped; ++round)
        for (SolverRuns& r : runs) {
          if (r.skipped) continue;
          const bool differed_before = r.differed;
          r.add(measure(*scene, r.trial, setup, interrupt));
          if ((stopped = r.interrupted)) break;
          if (r.differed && !differed_before)
            std::cerr
                << "warning: " << scene->name << " " << n << "x" << n << " " << r.trial.name
                << ": a repeated run gave a different status, max stretch or max penetration\n";
        }
      if (reference && !stopped) {
        SolverRuns r;
        r.trial = *reference;
        r.reference = true;
        r.add(measure(*scene, r.trial, setup, interrupt));
        if (!(stopped = r.interrupted)) runs.push_back(std::move(r));
      }
      add_cell_rows(table, *scene, n, *setup.model, runs);
      write_bench_files(out,
                        table);  // after every cell, so an interrupted bench keeps what it measured
      if (stopped) {
        std::cerr << "interrupted; " << (out / "bench.csv").string()
                  << " holds the rows measured so far\n";
        return runner::kExitInterrupted;
      }
    }
  write_bench_files(out, table);
  std::cout << "\n"
            << markdown(table) << "\nwrote " << (out / "bench.csv").string() << " and "
            << (out / "bench.md").string() << "\n";
  return 0;
}

}  // namespace drapelab::cli
