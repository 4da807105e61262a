// One solver through the frame loop (frame_loop.hpp) with nothing written: the observer keeps the
// largest stretch and hands every frame that passed its checks to the caller.
#include "drapelab/runner/simulate_solver.hpp"

#include <algorithm>
#include <cmath>

#include "drapelab/runner/solver_factory.hpp"
#include "frame_loop.hpp"

namespace drapelab::runner {
namespace {

class TrialObserver final : public FrameObserver {
 public:
  TrialObserver(SimulationResult& result, const SimulationOptions& options)
      : result_(result), options_(options) {}

  void measured(const SolverRun& run, const FrameMeasure& measure) override {
    result_.final_metrics = measure.metrics;
    // The first frame sets it (a sheet under compression has a negative max stretch); a NaN state
    // must not read as stable, so NaN sticks.
    const double stretch = measure.metrics.max_stretch;
    if (measure.frame == 0 || std::isnan(stretch))
      result_.max_stretch = stretch;
    else if (!std::isnan(result_.max_stretch))
      result_.max_stretch = std::max(result_.max_stretch, stretch);
    if (measure.failed != StopCause::none) return;
    ++result_.frames_recorded;
    result_.stepping_seconds_at_frame.push_back(run.wall_seconds);
    if (options_.on_frame) options_.on_frame(measure.frame, run.solver->state(), measure.metrics);
  }

 private:
  SimulationResult& result_;
  const SimulationOptions& options_;
};

}  // namespace

double SimulationResult::second_half_wall_seconds_per_simulated_second(double frame_period) const {
  const int last = static_cast<int>(stepping_seconds_at_frame.size()) - 1;
  if (last < 2) return 0.0;
  const int middle = last / 2;
  return (stepping_seconds_at_frame[last] - stepping_seconds_at_frame[middle]) /
         ((last - middle) * frame_period);
}

SimulationResult simulate_solver(const scene::Scene& scene, const scene::SolverSpec& spec,
                                 const SceneSetup& setup, const SimulationOptions& options) {
  SimulationResult result;
  result.dt = spec.dt;
  std::vector<SolverRun> runs(1);
  SolverRun& run = runs.front();
  run.spec = &spec;
  run.solver = make_solver(scene, spec, setup.model, setup.initial, *setup.world);
  TrialObserver observer(result, options);
  FrameLoopOptions loop;
  loop.stretch_limit = options.stretch_limit;
  loop.interrupt = options.interrupt;
  const FrameLoopEnd end = run_frame_loop(scene, setup, runs, loop, observer);
  result.status = run.status;
  result.message = run.message;
  result.stopped_by = run.stopped_by != StopCause::none ? run.stopped_by
                      : end.interrupted                 ? StopCause::interrupted
                                                        : StopCause::none;
  result.stopped_at_frame = run.stopped_at_frame;
  result.wall_seconds = run.wall_seconds;
  result.steps = run.steps;
  result.final_state = run.solver->state();
  result.counters = run.solver->counters();
  return result;
}

}  // namespace drapelab::runner
