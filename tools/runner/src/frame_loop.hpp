// The one frame loop of every in-process run: drapelab run (run_scene) and the trials of the
// stability, study and bench verbs (simulate_solver). Each frame, every running solver takes its
// own steps_per_frame steps of dt; then each is measured the same way (cloth metrics, clearance
// with colliders) and checked (its status, the scene's runaway_stretch, an optional stretch limit).
// A solver that stops, stops alone; the others go on.
#pragma once

#include <atomic>
#include <limits>
#include <optional>
#include <vector>

#include "drapelab/cloth_metrics.hpp"
#include "drapelab/collision_metrics.hpp"
#include "drapelab/runner/scene_setup.hpp"
#include "drapelab/scene/scene.hpp"
#include "solver_run.hpp"

namespace drapelab::runner {

// One solver's state at one recorded frame, as measured.
struct FrameMeasure {
  int frame = 0;                               // 0 = the initial state
  double time = 0.0;                           // s
  ClothMetrics metrics;                        // clearance filled in when there are colliders
  std::optional<CollisionMetrics> collisions;  // per collider, when there are colliders
  StopCause failed = StopCause::none;          // the stretch check this frame failed, if any
};

// What the loop's caller does with each frame: write rows, keep results.
class FrameObserver {
 public:
  virtual ~FrameObserver() = default;
  // Every measured frame of every running solver, in solver order, the frame that fails a stretch
  // check included (measure.failed says so; the solver is stopped right after).
  virtual void measured(const SolverRun& run, const FrameMeasure& measure) = 0;
  // Once per frame, after every solver's frame was measured and checked.
  virtual void frame_done(int /*frame*/, double /*time*/, const std::vector<SolverRun>& /*runs*/) {}
};

struct FrameLoopOptions {
  // A measured max stretch not below this stops the solver as unstable, like runaway_stretch.
  double stretch_limit = std::numeric_limits<double>::infinity();
  const std::atomic<bool>* interrupt = nullptr;  // Ctrl-C: stop after the current step
};

struct FrameLoopEnd {
  int last_frame = 0;  // the last frame measured
  bool interrupted =
      false;  // stopped by options.interrupt (a partly stepped frame is not measured)
};

// The loop's pieces, for callers that step solvers one at a time (simulation.hpp).
// Takes up to `steps` steps of `run` within frame `frame`; stops early when it leaves `ok` (then
// recording why) or on `interrupt`. Returns the steps taken.
int advance_steps(SolverRun& run, int frame, int steps, const std::atomic<bool>* interrupt);
// Steps one solver through frame `frame` (its steps_per_frame steps); stops early when it leaves
// `ok` or on `interrupt`.
void advance_one_frame(SolverRun& run, int frame, const std::atomic<bool>* interrupt);
// Measures `run`'s state at `frame` and checks its stretch (measure.failed); records the frame in
// `run` (last metrics, rest tracker, frames recorded).
FrameMeasure measure_and_check(const scene::Scene& scene, const SceneSetup& setup, SolverRun& run,
                               int frame, double stretch_limit);
// Stops `run` as unstable, with its message, when `measure` failed a stretch check.
void stop_for_stretch(SolverRun& run, const ClothModel& model, const FrameMeasure& measure,
                      double stretch_limit);

// Runs `runs` (built from `setup`) through scene.duration, frame by frame.
FrameLoopEnd run_frame_loop(const scene::Scene& scene, const SceneSetup& setup,
                            std::vector<SolverRun>& runs, const FrameLoopOptions& options,
                            FrameObserver& observer);

}  // namespace drapelab::runner
