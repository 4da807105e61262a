// drapelab run: the frame loop (frame_loop.hpp) with an observer that writes every measured frame
// into the run folder: metrics.csv, contacts.csv, compare.csv, meshes, and summary.json at the
// start and the end. The folder is written as a transaction (run_transaction.hpp): files go to a
// staging folder and move into place when the run ends.
#include "drapelab/runner/run_scene.hpp"

#include <algorithm>
#include <chrono>
#include <optional>
#include <ostream>
#include <variant>

#include "drapelab/run_folder/files.hpp"
#include "drapelab/run_folder/output_file.hpp"
#include "drapelab/run_folder/point_cache.hpp"
#include "drapelab/run_folder/run_transaction.hpp"
#include "drapelab/runner/mesh_output.hpp"
#include "drapelab/runner/scene_setup.hpp"
#include "drapelab/runner/solver_factory.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/scene/scene_writer.hpp"
#include "frame_loop.hpp"
#include "frame_tables.hpp"
#include "run_summary.hpp"

namespace drapelab::runner {
namespace {

namespace fs = std::filesystem;

bool wants_obj(scene::MeshOutput m) {
  return m == scene::MeshOutput::obj || m == scene::MeshOutput::both;
}
bool wants_pc2(scene::MeshOutput m) {
  return m == scene::MeshOutput::pc2 || m == scene::MeshOutput::both;
}

// Writes each measured frame into the run folder's tables and meshes. A frame's rows are committed
// when the frame ends; a write error rolls every file back to the last committed frame.
class RunFolderWriter final : public FrameObserver {
 public:
  RunFolderWriter(const fs::path& out, const scene::Scene& scene, const SceneSetup& setup,
                  std::vector<SolverRun>& runs)
      : out_(out),
        scene_(scene),
        setup_(setup),
        runs_(runs),
        tables_(out, has_dynamic_colliders(scene)),
        obj_(wants_obj(scene.output.meshes)) {}

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
    for (const BodyState& body : run.solver->bodies())
      tables_.add_body(name, measure.frame, measure.time,
                       scene_.colliders[static_cast<std::size_t>(body.collider)].name, body);
    const ClothState& state = run.solver->state();
    if (obj_) {
      pending_objs_.push_back(out_ / run_folder::kMeshesFolder /
                              run_folder::obj_frame_name(name, measure.frame));
      write_obj(pending_objs_.back(), *setup_.model, state.x,
                name + " frame " + std::to_string(measure.frame) +
                    " t=" + format_number(measure.time) + " s");
    }
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
    tables_.commit();
    for (auto& run : runs_)
      if (run.point_cache) run.point_cache->commit();
    pending_objs_.clear();
    committed_frame_ = frame;
  }

  // After a write error: every file back to the last committed frame, and the solvers' recorded
  // frame counts with them. Returns false when a file could not be cut back.
  bool rollback() noexcept {
    bool whole = tables_.rollback();
    for (auto& run : runs_) {
      if (run.point_cache) whole = run.point_cache->rollback() && whole;
      run.frames_recorded = std::min(run.frames_recorded, committed_frame_ + 1);
    }
    std::error_code ignored;
    for (const auto& path : pending_objs_) fs::remove(path, ignored);
    pending_objs_.clear();
    return whole;
  }
  int committed_frame() const { return committed_frame_; }  // -1 before frame 0 is complete

 private:
  const fs::path& out_;
  const scene::Scene& scene_;
  const SceneSetup& setup_;
  std::vector<SolverRun>& runs_;
  FrameTables tables_;
  bool obj_;
  std::vector<fs::path> pending_objs_;  // OBJ files of the frame not yet committed
  int committed_frame_ = -1;
};

// Passes every frame on to the run folder's writer, then tells a progress display where each solver
// is. A solver's wall time there is its stepping, timed by the frame loop, plus its measuring: the
// time between the loop's calls here, less the stepping done in between.
class ProgressReporter final : public FrameObserver {
 public:
  using Clock = std::chrono::steady_clock;

  ProgressReporter(FrameObserver& writer, RunProgress& progress, const scene::Scene& scene,
                   const std::vector<SolverRun>& runs)
      : writer_(writer),
        progress_(progress),
        scene_(scene),
        runs_(runs),
        measuring_seconds_(runs.size(), 0.0) {
    mark();
  }

  void measured(const SolverRun& run, const FrameMeasure& measure) override {
    const double since = std::chrono::duration<double>(Clock::now() - last_call_).count();
    const double stepped = stepping_seconds() - stepping_at_last_call_;
    measuring_seconds_[static_cast<std::size_t>(&run - runs_.data())] +=
        std::max(0.0, since - stepped);
    writer_.measured(run, measure);
    mark();
  }

  void frame_done(int frame, double time, const std::vector<SolverRun>& runs) override {
    writer_.frame_done(frame, time, runs);
    std::vector<SolverProgress> solvers;
    for (std::size_t k = 0; k < runs_.size(); ++k) {
      const SolverRun& run = runs_[k];
      SolverProgress solver;
      solver.name = run.spec->name;
      solver.frames_done = std::max(run.frames_recorded - 1, 0);
      solver.frames_total = scene_.frame_count();
      solver.simulated_seconds = solver.frames_done / scene_.frame_rate;
      solver.duration_seconds = scene_.duration;
      solver.wall_seconds = run.wall_seconds + measuring_seconds_[k];
      if (!run.running()) solver.stopped = solver_status_name(run.status);
      solvers.push_back(std::move(solver));
    }
    progress_.frame_recorded(solvers);
    mark();
  }

 private:
  double stepping_seconds() const {
    double total = 0.0;
    for (const auto& run : runs_) total += run.wall_seconds;
    return total;
  }
  void mark() {
    last_call_ = Clock::now();
    stepping_at_last_call_ = stepping_seconds();
  }

  FrameObserver& writer_;
  RunProgress& progress_;
  const scene::Scene& scene_;
  const std::vector<SolverRun>& runs_;
  std::vector<double> measuring_seconds_;  // s, per solver
  Clock::time_point last_call_;
  double stepping_at_last_call_ = 0.0;  // s, every solver's stepping at last_call_
};

// The path of a file inside the staging folder as it is named once the run is in place.
std::string as_placed(const fs::path& file, const fs::path& staging, const fs::path& folder) {
  const fs::path relative = file.lexically_relative(staging);
  if (relative.empty() || *relative.begin() == "..") return file.string();
  return (folder / relative).string();
}

}  // namespace

RunResult run_scene(const scene::Scene& scene, const RunOptions& options, std::ostream& log) {
  RunResult result;
  const std::string resolved = scene::resolved_scene_yaml(scene);
  auto opened = run_folder::RunTransaction::open(options.out_dir, resolved, options.force);
  if (const auto* refusal = std::get_if<std::string>(&opened)) {
    log << "error: " << *refusal << "\n";
    result.exit_code = kExitBadInput;
    return result;
  }
  run_folder::RunTransaction& transaction =
      *std::get<std::unique_ptr<run_folder::RunTransaction>>(opened);
  if (!options.quiet)
    for (const auto& note : transaction.notes()) log << "note: " << note << "\n";
  const fs::path& out = transaction.staging();

  const SceneSetup setup = build_scene_setup(scene, options.model);
  const ClothModel& model = *setup.model;
  std::vector<SolverRun> runs;
  runs.reserve(scene.solvers.size());
  for (const auto& spec : scene.solvers) {
    SolverRun run;
    run.spec = &spec;
    run.solver = make_solver(scene, spec, setup.model, setup.initial, *setup.world);
    runs.push_back(std::move(run));
  }

  RunInfo info{"running", options.command_line, scene.frame_count(), 0};
  FrameLoopEnd end;
  std::optional<run_folder::WriteError> write_error;
  std::unique_ptr<RunFolderWriter> writer;
  try {
    run_folder::write_whole_file(out / run_folder::kSceneYaml, options.scene_text);
    run_folder::write_whole_file(out / run_folder::kResolvedYaml, resolved);
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
    run_folder::write_file_atomically(out / run_folder::kSummaryJson,
                                      summary_json(scene, model, runs, info));
    writer = std::make_unique<RunFolderWriter>(out, scene, setup, runs);
    FrameLoopOptions loop;
    loop.interrupt = options.interrupt;
    if (options.progress) {
      ProgressReporter reporter(*writer, *options.progress, scene, runs);
      end = run_frame_loop(scene, setup, runs, loop, reporter);
    } else {
      end = run_frame_loop(scene, setup, runs, loop, *writer);
    }
  } catch (const run_folder::WriteError& error) {
    write_error = error;
  } catch (const fs::filesystem_error& error) {  // creating meshes/
    write_error = run_folder::WriteError(error.path1(), error.code());
  }
  if (options.progress) options.progress->frames_ended();
  if (write_error) {
    // Disk full or refused: free the reserve so the summary fits, and end on the last whole frame.
    transaction.release_reserve();
    if (writer && !writer->rollback())
      log << "warning: a table could not be cut back to its last whole frame\n";
  }

  const bool interrupted = options.interrupt && options.interrupt->load(std::memory_order_relaxed);
  info.state = write_error ? "write_failed" : interrupted ? "interrupted" : "finished";
  info.frames_done =
      write_error ? (writer ? std::max(writer->committed_frame(), 0) : 0) : end.last_frame;
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
  try {
    run_folder::write_file_atomically(out / run_folder::kSummaryJson,
                                      summary_json(scene, model, runs, info));
    result.folder = transaction.commit(info.state == "finished");
  } catch (const run_folder::WriteError& error) {
    log << "error: " << as_placed(error.path(), out, transaction.folder()) << ": cannot write ("
        << error.error().message() << "); the run's files stay in " << out.string() << "\n";
    result.folder = out;
    result.exit_code = all_ok ? kExitBadInput : kExitUnstable;
    return result;
  }
  if (result.folder != transaction.folder())
    log << "note: " << transaction.folder().string()
        << " holds a finished run, which is kept; this incomplete run is in "
        << result.folder.string() << "\n";
  if (write_error) {
    log << "error: cannot write " << as_placed(write_error->path(), out, result.folder) << ": "
        << write_error->error().message() << "; the run stopped, and every file in "
        << result.folder.string() << " holds frames 0.." << info.frames_done << "\n";
    result.exit_code = all_ok ? kExitBadInput : kExitUnstable;
  } else if (interrupted) {
    log << "interrupted after frame " << info.frames_done << "; every file in "
        << result.folder.string() << " holds the frames recorded so far\n";
    result.exit_code = kExitInterrupted;
  } else {
    result.exit_code = all_ok ? kExitOk : kExitUnstable;
  }
  return result;
}

}  // namespace drapelab::runner
