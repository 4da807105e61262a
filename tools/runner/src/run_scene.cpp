// The run loop: every solver advances one frame (its own number of steps), then every solver's state
// is measured the same way and recorded. A solver that becomes unstable stops alone.
#include "drapelab/runner/run_scene.hpp"

#include <chrono>
#include <cstdio>
#include <ostream>

#include "drapelab/collision_metrics.hpp"
#include "drapelab/runner/output_files.hpp"
#include "drapelab/runner/scene_setup.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/scene/scene_writer.hpp"
#include "frame_tables.hpp"
#include "run_summary.hpp"
#include "solver_factory.hpp"

namespace drapelab::runner {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

bool wants_obj(scene::MeshOutput m) { return m == scene::MeshOutput::obj || m == scene::MeshOutput::both; }
bool wants_pc2(scene::MeshOutput m) { return m == scene::MeshOutput::pc2 || m == scene::MeshOutput::both; }

std::string frame_file(const std::string& solver, int frame) {
  char number[16];
  std::snprintf(number, sizeof number, "%04d", frame);
  return solver + "_" + number + ".obj";
}

// Steps one solver through a frame; stops early when it becomes unstable or on Ctrl-C.
void advance_one_frame(SolverRun& run, const std::atomic<bool>* interrupt) {
  const auto start = Clock::now();
  for (int s = 0; s < run.spec->steps_per_frame; ++s) {
    run.solver->step(run.spec->dt);
    ++run.steps;
    if (run.solver->status() != SolverStatus::ok) break;
    if (interrupt && interrupt->load(std::memory_order_relaxed)) break;
  }
  run.wall_seconds += std::chrono::duration<double>(Clock::now() - start).count();
  if (run.solver->status() != SolverStatus::ok) {
    run.status = run.solver->status();
    run.message = run.solver->message();
  }
}

// The runner's own runaway test, the same for every solver: a stretch spring far beyond its rest
// length means the state has exploded even if every number is still finite.
void check_runaway(SolverRun& run, const ClothModel& model, const ClothMetrics& metrics, int frame) {
  if (metrics.max_stretch <= run.spec->runaway_stretch) return;
  run.status = SolverStatus::unstable;
  run.message = describe_most_stretched_spring(model, run.solver->state()) + " (more than runaway_stretch = " +
                format_number(run.spec->runaway_stretch) + ") at frame " + std::to_string(frame) + ", step " +
                std::to_string(run.steps) + ". Try: a smaller dt, stiffer stretch springs, or more damping.";
}

// Clearance metrics from FCL on the solver's state (the same for every solver), and one contacts.csv
// row per collider with the forces the solver reports for its last step.
void record_collisions(FrameTables& tables, const SolverRun& run, const ClothModel& model,
                       const ContactModel& contacts, int frame, double time, ClothMetrics& metrics) {
  const CollisionMetrics collisions = compute_collision_metrics(model, run.solver->state(), contacts, time);
  metrics.min_clearance = collisions.min_clearance;
  metrics.max_penetration = collisions.max_penetration;
  metrics.contact_count = collisions.contact_count;
  const std::vector<ColliderForce> forces = run.solver->collider_forces();
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const ColliderForce force = c < forces.size() ? forces[c] : ColliderForce{};
    tables.add_contact(run.spec->name, frame, time, contacts.collider(c).name,
                       collisions.per_collider[c].contact_count, force.normal, force.friction,
                       collisions.per_collider[c].max_penetration);
  }
}

}  // namespace

int run_scene(const scene::Scene& scene, const RunOptions& options, std::ostream& log) {
  const std::string resolved = scene::resolved_scene_yaml(scene);
  if (const auto problem = prepare_run_folder(options.out_dir, resolved, options.force)) {
    log << "error: " << *problem << "\n";
    return kExitBadInput;
  }
  const fs::path& out = options.out_dir;
  write_file_atomically(out / "scene.yaml", options.scene_text);
  write_file_atomically(out / "resolved.yaml", resolved);

  const SceneSetup setup = build_scene_setup(scene);
  const std::shared_ptr<const ClothModel>& model = setup.model;
  const ClothState& initial = setup.initial;
  const std::shared_ptr<const ContactModel>& contacts = setup.contacts;
  std::vector<SolverRun> runs;
  runs.reserve(scene.solvers.size());
  for (const auto& spec : scene.solvers) {
    SolverRun run;
    run.spec = &spec;
    run.solver = make_solver(scene, spec, model, initial, contacts);
    runs.push_back(std::move(run));
  }

  const bool obj = wants_obj(scene.output.meshes), pc2 = wants_pc2(scene.output.meshes);
  if (obj || pc2) {
    fs::create_directories(out / "meshes");
    write_obj(out / "meshes" / "rest.obj", *model, model->rest_positions, "drapelab rest pose of " + scene.name);
    if (pc2)
      for (auto& run : runs)
        run.point_cache = std::make_unique<Pc2Writer>(out / "meshes" / (run.spec->name + ".pc2"), model->particle_count());
  }

  RunInfo info{"running", options.command_line, scene.frame_count(), 0};
  write_file_atomically(out / "summary.json", summary_json(scene, *model, runs, info));
  FrameTables tables(out);
  auto interrupted = [&] { return options.interrupt && options.interrupt->load(std::memory_order_relaxed); };

  for (int frame = 0; frame <= scene.frame_count(); ++frame) {
    if (frame > 0)
      for (auto& run : runs)
        if (run.running()) advance_one_frame(run, options.interrupt);
    if (frame > 0 && interrupted()) break;  // a partly stepped frame is not recorded
    const double time = frame / scene.frame_rate;  // s
    for (auto& run : runs) {
      if (!run.running()) continue;
      ClothMetrics metrics = frame_metrics(setup, scene, run.solver->state());
      if (contacts) record_collisions(tables, run, *model, *contacts, frame, time, metrics);
      tables.add_metrics(run.spec->name, frame, time, metrics);
      run.last_metrics = metrics;
      run.rest.add(time, metrics.kinetic_energy, metrics.gravity_energy, model->total_mass());
      ++run.frames_recorded;
      if (obj) write_obj(out / "meshes" / frame_file(run.spec->name, frame), *model, run.solver->state().x,
                         run.spec->name + " frame " + std::to_string(frame) + " t=" + format_number(time) + " s");
      if (run.point_cache) run.point_cache->append(run.solver->state().x);
      check_runaway(run, *model, metrics, frame);
    }
    for (std::size_t a = 0; a < runs.size(); ++a)
      for (std::size_t b = a + 1; b < runs.size(); ++b)
        if (runs[a].running() && runs[b].running())
          tables.add_comparison(runs[a].spec->name, runs[b].spec->name, frame, time,
                                compare_states(*model, runs[a].solver->state(), runs[b].solver->state()));
    tables.flush();
    info.frames_done = frame;
    bool any_running = false;
    for (const auto& run : runs) any_running = any_running || run.running();
    if (!any_running) break;
  }

  info.state = interrupted() ? "interrupted" : "finished";
  write_file_atomically(out / "summary.json", summary_json(scene, *model, runs, info));
  bool all_ok = true;
  for (const auto& run : runs) {
    if (run.status == SolverStatus::ok) continue;
    all_ok = false;
    log << "solver '" << run.spec->name << "' " << solver_status_name(run.status) << ": " << run.message << "\n";
  }
  if (interrupted()) {
    log << "interrupted after frame " << info.frames_done << "; every file in " << out.string()
        << " holds the frames recorded so far\n";
    return kExitInterrupted;
  }
  return all_ok ? kExitOk : kExitUnstable;
}

}  // namespace drapelab::runner
