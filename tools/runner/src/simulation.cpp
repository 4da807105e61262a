#include "drapelab/runner/simulation.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "drapelab/runner/scene_setup.hpp"
#include "drapelab/runner/solver_factory.hpp"
#include "frame_loop.hpp"
#include "solver_run.hpp"

namespace drapelab::runner {

// `drapelab run` has no stretch limit beyond each solver's runaway_stretch.
constexpr double kNoStretchLimit = std::numeric_limits<double>::infinity();

struct Simulation::Impl {
  scene::Scene scene;
  SceneSetup setup;
  std::vector<DistanceConstraint> extra_constraints;
  std::vector<SolverRun> runs;        // in the scene's order; each spec points into `scene`
  std::vector<int> frames;            // per solver, the last frame measured
  std::vector<int> steps_into_frame;  // per solver, of the frame under way
  std::vector<std::vector<Record>> records;

  // Every solver of `scene`, each from `starts[k]` (or the scene's initial state when empty); a
  // solver built again keeps its run's counts and, if it had stopped, its stop.
  void build_runs(const std::vector<ClothState>& starts) {
    std::vector<SolverRun> built;
    built.reserve(scene.solvers.size());
    // One world for every solver from the scene's start; solvers carried on from states of their
    // own each place the pins carried by colliders from their state. The drag is the user's.
    const std::shared_ptr<const World> shared =
        starts.empty() ? build_world(scene, setup.initial, setup.contacts, setup.constraints,
                                     extra_constraints)
                       : nullptr;
    for (std::size_t k = 0; k < scene.solvers.size(); ++k) {
      SolverRun run;
      run.spec = &scene.solvers[k];
      const ClothState& start = starts.empty() ? setup.initial : starts[k];
      const std::shared_ptr<const World> world =
          shared ? shared
                 : build_world(scene, start, setup.contacts, setup.constraints, extra_constraints);
      run.solver = make_solver(scene, *run.spec, setup.model, start, *world);
      if (k < runs.size()) {
        run.wall_seconds = runs[k].wall_seconds;
        run.steps = runs[k].steps;
        run.frames_recorded = runs[k].frames_recorded;
        run.status = runs[k].status;
        run.message = runs[k].message;
        run.stopped_by = runs[k].stopped_by;
        run.stopped_at_frame = runs[k].stopped_at_frame;
        run.last_metrics = runs[k].last_metrics;
      }
      built.push_back(std::move(run));
    }
    runs = std::move(built);
  }

  void measure(std::size_t solver) {
    SolverRun& run = runs[solver];
    const FrameMeasure measure =
        measure_and_check(scene, setup, run, frames[solver], kNoStretchLimit);
    records[solver].push_back({measure.frame, measure.time, measure.metrics});
    stop_for_stretch(run, *setup.model, measure, kNoStretchLimit);
  }

  void start() {
    runs.clear();
    build_runs({});
    frames.assign(runs.size(), 0);
    steps_into_frame.assign(runs.size(), 0);
    records.assign(runs.size(), {});
    for (std::size_t k = 0; k < runs.size(); ++k) measure(k);
  }
};

Simulation::Simulation(scene::Scene scene, std::shared_ptr<const ClothModel> model,
                       std::vector<DistanceConstraint> extra_constraints)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.scene = std::move(scene);
  s.setup = build_scene_setup(s.scene, std::move(model));
  s.extra_constraints = std::move(extra_constraints);
  s.start();
}

Simulation::~Simulation() = default;

const scene::Scene& Simulation::scene() const { return impl_->scene; }
const ClothModel& Simulation::model() const { return *impl_->setup.model; }
std::size_t Simulation::solver_count() const { return impl_->runs.size(); }
const std::string& Simulation::solver_name(std::size_t solver) const {
  return impl_->runs.at(solver).spec->name;
}

std::optional<std::size_t> Simulation::find_solver(const std::string& name) const {
  for (std::size_t k = 0; k < impl_->runs.size(); ++k)
    if (impl_->runs[k].spec->name == name) return k;
  return std::nullopt;
}

int Simulation::advance(std::size_t solver, int frames, const std::atomic<bool>* interrupt) {
  SolverRun& run = impl_->runs.at(solver);
  int done = 0;
  while (done < frames && run.running()) {
    if (interrupt && interrupt->load(std::memory_order_relaxed)) break;
    const int frame = impl_->frames[solver] + 1;
    int& stepped = impl_->steps_into_frame[solver];
    stepped += runner::advance_steps(run, frame, run.spec->steps_per_frame - stepped, interrupt);
    // An interrupt in the middle of the frame leaves it unmeasured, as in drapelab run; the steps
    // taken stay taken, and the next call completes the frame.
    if (run.running() && stepped < run.spec->steps_per_frame) break;
    stepped = 0;
    impl_->frames[solver] = frame;
    if (run.running()) impl_->measure(solver);
    ++done;
  }
  return done;
}

bool Simulation::advance_steps(std::size_t solver, int steps) {
  SolverRun& run = impl_->runs.at(solver);
  if (!run.running()) return true;
  const int frame = impl_->frames[solver] + 1;
  int& stepped = impl_->steps_into_frame[solver];
  stepped += runner::advance_steps(run, frame, std::min(steps, run.spec->steps_per_frame - stepped),
                                   nullptr);
  if (!run.running()) return true;
  if (stepped < run.spec->steps_per_frame) return false;
  stepped = 0;
  impl_->frames[solver] = frame;
  impl_->measure(solver);
  return true;
}

int Simulation::steps_into_frame(std::size_t solver) const {
  return impl_->steps_into_frame.at(solver);
}

void Simulation::rebuild(scene::Scene changed) {
  Impl& s = *impl_;
  if (changed.solvers.size() != s.runs.size())
    throw std::invalid_argument("a rebuilt simulation keeps its " + std::to_string(s.runs.size()) +
                                " solvers; the scene has " +
                                std::to_string(changed.solvers.size()));
  std::vector<ClothState> states;
  for (const SolverRun& run : s.runs) states.push_back(run.solver->state());
  s.scene = std::move(changed);
  s.setup = build_scene_setup(s.scene);
  s.build_runs(states);
}

void Simulation::restart() { impl_->start(); }

int Simulation::frame(std::size_t solver) const { return impl_->frames.at(solver); }
double Simulation::time(std::size_t solver) const {
  return impl_->frames.at(solver) / impl_->scene.frame_rate;
}
bool Simulation::running(std::size_t solver) const { return impl_->runs.at(solver).running(); }
SolverStatus Simulation::status(std::size_t solver) const { return impl_->runs.at(solver).status; }
const std::string& Simulation::message(std::size_t solver) const {
  return impl_->runs.at(solver).message;
}
const ClothState& Simulation::state(std::size_t solver) const {
  return impl_->runs.at(solver).solver->state();
}
const Solver& Simulation::solver(std::size_t solver) const {
  return *impl_->runs.at(solver).solver;
}
std::vector<BodyState> Simulation::bodies(std::size_t solver) const {
  return impl_->runs.at(solver).solver->bodies();
}
std::int64_t Simulation::steps(std::size_t solver) const { return impl_->runs.at(solver).steps; }
double Simulation::wall_seconds(std::size_t solver) const {
  return impl_->runs.at(solver).wall_seconds;
}
const std::vector<Simulation::Record>& Simulation::records(std::size_t solver) const {
  return impl_->records.at(solver);
}

}  // namespace drapelab::runner
