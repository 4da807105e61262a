#include "drapelab/runner/simulation.hpp"

#include <limits>

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
  std::vector<SolverRun> runs;  // in the scene's order; each spec points into `scene`
  std::vector<int> frames;      // per solver, the last frame measured
  std::vector<std::vector<Record>> records;

  void measure(std::size_t solver) {
    SolverRun& run = runs[solver];
    const FrameMeasure measure =
        measure_and_check(scene, setup, run, frames[solver], kNoStretchLimit);
    records[solver].push_back({measure.frame, measure.time, measure.metrics});
    stop_for_stretch(run, *setup.model, measure, kNoStretchLimit);
  }
};

Simulation::Simulation(scene::Scene scene, std::shared_ptr<const ClothModel> model)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.scene = std::move(scene);
  s.setup = build_scene_setup(s.scene, std::move(model));
  s.runs.reserve(s.scene.solvers.size());
  for (const auto& spec : s.scene.solvers) {
    SolverRun run;
    run.spec = &spec;
    run.solver = make_solver(s.scene, spec, s.setup.model, s.setup.initial, s.setup.contacts);
    s.runs.push_back(std::move(run));
  }
  s.frames.assign(s.runs.size(), 0);
  s.records.resize(s.runs.size());
  for (std::size_t k = 0; k < s.runs.size(); ++k) s.measure(k);
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
    advance_one_frame(run, frame, interrupt);
    // An interrupt in the middle of the frame leaves it unmeasured, as in drapelab run; the steps
    // taken stay taken.
    if (run.running() && interrupt && interrupt->load(std::memory_order_relaxed)) break;
    impl_->frames[solver] = frame;
    if (run.running()) impl_->measure(solver);
    ++done;
  }
  return done;
}

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
