// The frame loop: step every running solver through a frame, then measure and check each.
#include "frame_loop.hpp"

#include <chrono>

#include "drapelab/scene/number_format.hpp"
#include "drapelab/triangle_penetration.hpp"

namespace drapelab::runner {
namespace {

using Clock = std::chrono::steady_clock;

bool interrupted(const std::atomic<bool>* interrupt) {
  return interrupt && interrupt->load(std::memory_order_relaxed);
}

}  // namespace

int advance_steps(SolverRun& run, int frame, int steps, const std::atomic<bool>* interrupt) {
  const auto start = Clock::now();
  int taken = 0;
  while (taken < steps) {
    run.solver->step(run.spec->dt);
    ++run.steps;
    ++taken;
    if (run.solver->status() != SolverStatus::ok || interrupted(interrupt)) break;
  }
  run.wall_seconds += std::chrono::duration<double>(Clock::now() - start).count();
  if (run.solver->status() == SolverStatus::ok) return taken;
  run.status = run.solver->status();
  run.message = run.solver->message();
  run.stopped_by = StopCause::solver;
  run.stopped_at_frame = frame;
  return taken;
}

void advance_one_frame(SolverRun& run, int frame, const std::atomic<bool>* interrupt) {
  advance_steps(run, frame, run.spec->steps_per_frame, interrupt);
}

namespace {

// The metrics of one state: cloth metrics and the self-intersection audit, plus clearance and
// triangle penetration when there are colliders (the same queries for every solver).
// The contact model one solver's metrics use: the scene's, or, with dynamic colliders, one whose
// dynamic colliders stand where this solver's own bodies are.
// Where this solver's own dynamic bodies are at `time`, the other colliders where the scene puts
// them; null without dynamic bodies.
std::shared_ptr<const ColliderPoseTable> own_body_poses(const SceneSetup& setup,
                                                        const Solver& solver, double time) {
  const std::vector<BodyState> bodies = solver.bodies();
  if (!setup.contacts || bodies.empty()) return nullptr;
  const ContactModel& scene_contacts = *setup.contacts;
  auto poses = std::make_shared<ColliderPoseTable>(scene_contacts.size());
  poses->set_substep(time, time);
  for (std::size_t c = 0; c < scene_contacts.size(); ++c) {
    ColliderSubstepMotion still;
    still.start = still.end = collider_pose(scene_contacts.collider(c), time);
    poses->set(c, still);
  }
  for (const BodyState& body : bodies) {
    ColliderSubstepMotion motion;
    motion.start = motion.end = body.pose;
    motion.velocity = body.velocity;
    motion.angular_velocity = body.angular_velocity;
    poses->set(static_cast<std::size_t>(body.collider), motion);
  }
  return poses;
}

std::shared_ptr<const ContactModel> contacts_for(
    const SceneSetup& setup, const std::shared_ptr<const ColliderPoseTable>& own_poses) {
  if (!setup.contacts || !own_poses) return setup.contacts;
  const ContactModel& scene_contacts = *setup.contacts;
  return std::make_shared<const ContactModel>(scene_contacts.colliders(),
                                              scene_contacts.parameters(),
                                              scene_contacts.query().radius(), own_poses);
}

FrameMeasure measure_frame(const scene::Scene& scene, const SceneSetup& setup, SolverRun& run,
                           int frame, double time) {
  const Solver& solver = *run.solver;
  const ClothState& state = solver.state();
  const std::shared_ptr<const ColliderPoseTable> own_poses = own_body_poses(setup, solver, time);
  const std::shared_ptr<const ContactModel> contacts = contacts_for(setup, own_poses);
  FrameMeasure measure;
  measure.frame = frame;
  measure.time = time;
  measure.metrics = frame_metrics(setup, scene, state);
  measure.metrics.self_intersections = setup.self_intersections->count(state.x);
  if (setup.constraints && setup.constraints->has_hard())
    measure.metrics.constraint_error = setup.constraints->largest_error(time, state.x);
  if (contacts) {
    measure.collisions = compute_collision_metrics(*setup.model, state, *contacts, time);
    measure.metrics.min_clearance = measure.collisions->min_clearance;
    measure.metrics.max_penetration = measure.collisions->max_penetration;
    measure.metrics.contact_count = measure.collisions->contact_count;
    measure.metrics.triangle_penetration =
        triangle_penetration(*setup.model, state.x, *contacts, time);
  }
  if (!run.energy)
    run.energy = std::make_unique<EnergyAudit>(
        scene::cloth_for_solver(scene, *run.spec, setup.model), scene, setup.contacts.get());
  const std::shared_ptr<const DistanceConstraints> constraints =
      own_poses ? constraints_on_own_bodies(setup.constraints, own_poses) : setup.constraints;
  run.energy->measure(contacts.get(), measure.collisions ? &*measure.collisions : nullptr,
                      constraints.get(), solver, time, measure.metrics);
  run.energy->check(frame, time, measure.metrics, *run.spec);
  return measure;
}

// Which stretch check refuses a measured frame (none when it passes); a NaN stretch is refused too:
// a stretch spring far beyond its rest length means the state has exploded even if every number is
// still finite.
StopCause stretch_check(const scene::SolverSpec& spec, const ClothMetrics& metrics,
                        double stretch_limit) {
  if (!(metrics.max_stretch <= spec.runaway_stretch)) return StopCause::runaway_stretch;
  if (!(metrics.max_stretch < stretch_limit)) return StopCause::stretch_limit;
  return StopCause::none;
}

}  // namespace

FrameMeasure measure_and_check(const scene::Scene& scene, const SceneSetup& setup, SolverRun& run,
                               int frame, double stretch_limit) {
  const double time = frame / scene.frame_rate;  // s
  FrameMeasure measure = measure_frame(scene, setup, run, frame, time);
  measure.failed = stretch_check(*run.spec, measure.metrics, stretch_limit);
  run.last_metrics = measure.metrics;
  run.rest.add(time, measure.metrics.kinetic_energy, measure.metrics.gravity_energy,
               setup.model->total_mass());
  ++run.frames_recorded;
  return measure;
}

void stop_for_stretch(SolverRun& run, const ClothModel& model, const FrameMeasure& measure,
                      double stretch_limit) {
  if (measure.failed == StopCause::none) return;
  const bool runaway = measure.failed == StopCause::runaway_stretch;
  run.status = SolverStatus::unstable;
  run.stopped_by = measure.failed;
  run.stopped_at_frame = measure.frame;
  run.message =
      describe_most_stretched_spring(model, run.solver->state()) +
      (runaway ? " (more than runaway_stretch = " + format_number(run.spec->runaway_stretch)
               : " (at least the stretch limit " + format_number(stretch_limit)) +
      ") at frame " + std::to_string(measure.frame) + ", step " + std::to_string(run.steps) +
      (runaway ? ". Try: a smaller dt, stiffer stretch springs, or more damping." : "");
}

FrameLoopEnd run_frame_loop(const scene::Scene& scene, const SceneSetup& setup,
                            std::vector<SolverRun>& runs, const FrameLoopOptions& options,
                            FrameObserver& observer) {
  FrameLoopEnd end;
  for (int frame = 0; frame <= scene.frame_count(); ++frame) {
    if (frame > 0)
      for (auto& run : runs)
        if (run.running()) advance_one_frame(run, frame, options.interrupt);
    if (frame > 0 && interrupted(options.interrupt)) {
      end.interrupted = true;
      break;
    }
    const double time = frame / scene.frame_rate;  // s
    for (auto& run : runs) {
      if (!run.running()) continue;
      const FrameMeasure measure =
          measure_and_check(scene, setup, run, frame, options.stretch_limit);
      observer.measured(run, measure);
      stop_for_stretch(run, *setup.model, measure, options.stretch_limit);
    }
    observer.frame_done(frame, time, runs);
    end.last_frame = frame;
    bool any_running = false;
    for (const auto& run : runs) any_running = any_running || run.running();
    if (!any_running) break;
  }
  return end;
}

}  // namespace drapelab::runner
