// drapelab run: the frame loop (frame_loop.hpp) with an observer that writes every measured frame
// into the run folder: metrics.csv, contacts.csv, compare.csv, meshes, and summary.json at the
// start and the end.
#include "drapelab/runner/run_scene.hpp"

#include <ostream>

#include "drapelab/run_folder/files.hpp"
#include "drapelab/run_folder/point_cache.hpp"
#include "drapelab/runner/mesh_output.hpp"
#include "drapelab/runner/scene_setup.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/scene/scene_writer.hpp"
#include "frame_loop.hpp"
#include "frame_tables.hpp"
#include "run_summary.hpp"
#include "solver_factory.hpp"

namespace drapelab::runner {
namespace {

namespace fs = std::filesystem;

bool wants_obj(scene::MeshOutput m) {
  return m == scene::MeshOutput::obj || m == scene::MeshOutput::both;
}
bool wants_pc2(scene::MeshOutput m) {
  return m == scene::MeshOutput::pc2 || m == scene::MeshOutput::both;
}

// Writes each measured frame into the run folder's tables and meshes, flushed frame by frame so
// that every file stays complete whenever the run stops.
class RunFolderWriter final : public FrameObserver {
 public:
  RunFolderWriter(const fs::path& out, const scene::Scene& scene, const SceneSetup& setup)
      : out_(out), setup_(setup), tables_(out), obj_(wants_obj(scene.output.meshes)) {}

  void measured(const SolverRun& run, const FrameMeasure& measure) override {
    const std::string& name = run.spec->name;
    if (measure.collisions) {
      // One contacts.csv row per collider, with the forces the solver reports for its last step.
      const std::vector<ColliderForce> forces = run.solver->collider_forces();
      for (std::size_t c = 0; c < setup_.contacts->size(); ++c) {
        const ColliderForce force = c < forces.size() ? forces[c] : ColliderForce{};
        const auto& per_collider = measure.collisions->per_collider[c];
        tables_.add_contact(name, measure.frame, measure.time, setup_.contacts->collider(c).name,
                            per_collider.contact_count, force.normal, force.friction,
                            per_collider.max_penetration);
      }
    }
    tables_.add_metrics(name, measure.frame, measure.time, measure.metrics);
    const ClothState& state = run.solver->state();
    if (obj_)
      write_obj(out_ / run_folder::kMeshesFolder / run_folder::obj_frame_name(name, measure.frame),
                *setup_.model, state.x,
                name + " frame " + std::to_string(measure.frame) +
                    " t=" + format_number(measure.time) + " s");
    if (run.point_cache) run.point_cache->append(state.x);
  }

  // compare.csv: every pair of solvers both still running, then the frame's rows reach the disk.
  void frame_done(int frame, double time, const std::vector<SolverRun>& runs) override {
    for (std::size_t a = 0; a < runs.size(); ++a)
      for (std::size_t b = a + 1; b < runs.size(); ++b)
        if (runs[a].running() && runs[b].running())
          tables_.add_comparison(
              runs[a].spec->name, runs[b].spec->name, frame, time,
              compare_states(*setup_.model, runs[a].solver->state(), runs[b].solver->state()));
    tables_.flush();
  }

 private:
  const fs::path& out_;
  const SceneSetup& setup_;
  FrameTables tables_;
  bool obj_;
};

}  // namespace

RunResult run_scene(const scene::Scene& scene, const RunOptions& options, std::ostream& log) {
  RunResult result;
  const std::string resolved = scene::resolved_scene_yaml(scene);
  if (const auto problem =
          run_folder::prepare_run_folder(options.out_dir, resolved, options.force)) {
    log << "error: " << *problem << "\n";
    result.exit_code = kExitBadInput;
    return result;
  }
  const fs::path& out = options.out_dir;
  run_folder::write_file_atomically(out / run_folder::kSceneYaml, options.scene_text);
  run_folder::write_file_atomically(out / run_folder::kResolvedYaml, resolved);

  const SceneSetup setup = build_scene_setup(scene, options.model);
  const ClothModel& model = *setup.model;
  std::vector<SolverRun> runs;
  runs.reserve(scene.solvers.size());
  for (const auto& spec : scene.solvers) {
    SolverRun run;
    run.spec = &spec;
    run.solver = make_solver(scene, spec, setup.model, setup.initial, setup.contacts);
    runs.push_back(std::move(run));
  }

  if (wants_obj(scene.output.meshes) || wants_pc2(scene.output.meshes)) {
    const fs::path meshes = out / run_folder::kMeshesFolder;
    fs::create_directories(meshes);
    write_obj(meshes / "rest.obj", model, model.rest_positions,
              "drapelab rest pose of " + scene.name);
    if (wants_pc2(scene.output.meshes))
      for (auto& run : runs)
        run.point_cache = std::make_unique<run_folder::Pc2Writer>(
            meshes / run_folder::point_cache_name(run.spec->name), model.particle_count());
  }

  RunInfo info{"running", options.command_line, scene.frame_count(), 0};
  run_folder::write_file_atomically(out / run_folder::kSummaryJson,
                                    summary_json(scene, model, runs, info));
  FrameLoopEnd end;
  {
    RunFolderWriter writer(out, scene, setup);
    FrameLoopOptions loop;
    loop.interrupt = options.interrupt;
    end = run_frame_loop(scene, setup, runs, loop, writer);
  }

  const bool interrupted = options.interrupt && options.interrupt->load(std::memory_order_relaxed);
  info.state = interrupted ? "interrupted" : "finished";
  info.frames_done = end.last_frame;
  run_folder::write_file_atomically(out / run_folder::kSummaryJson,
                                    summary_json(scene, model, runs, info));
  result.state = info.state;
  result.frames_done = info.frames_done;
  bool all_ok = true;
  for (const auto& run : runs) {
    result.solvers.push_back(outcome_of(run));
    if (run.status == SolverStatus::ok) continue;
    all_ok = false;
    log << "solver '" << run.spec->name << "' " << solver_status_name(run.status) << ": "
        << run.message << "\n";
  }
  if (interrupted) {
    log << "interrupted after frame " << info.frames_done << "; every file in " << out.string()
        << " holds the frames recorded so far\n";
    result.exit_code = kExitInterrupted;
  } else {
    result.exit_code = all_ok ? kExitOk : kExitUnstable;
  }
  return result;
}

}  // namespace drapelab::runner
