// A scene held in memory and stepped on request, one solver and one frame at a time, each frame
// measured exactly as `drapelab run` measures it (the same frame-loop pieces, so the same numbers
// to the last digit). For programs that drive the solvers themselves: the Python module and the
// viewer, which steps a frame a few steps at a time and changes the scene while it runs.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drapelab/cloth_metrics.hpp"
#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/distance_constraints.hpp"
#include "drapelab/scene/scene.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::runner {

class Simulation {
 public:
  // Builds every solver of `scene` (`model`: the loader's cloth of this scene, or null to build
  // it) and measures frame 0, the initial state.
  // `extra_constraints` are added to every solver's own (the viewer's live drag).
  explicit Simulation(scene::Scene scene, std::shared_ptr<const ClothModel> model = nullptr,
                      std::vector<DistanceConstraint> extra_constraints = {});
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  const scene::Scene& scene() const;
  const ClothModel& model() const;
  std::size_t solver_count() const;
  const std::string& solver_name(std::size_t solver) const;
  std::optional<std::size_t> find_solver(const std::string& name) const;

  // Steps `solver` through up to `frames` more frames, measuring each, as `drapelab run` does
  // (the scene's duration does not stop it). Stops early when the solver stops (unstable, error)
  // or when `interrupt` is set; a frame left partly stepped by an interrupt is not measured.
  // Returns the frames completed.
  // A frame left partly stepped (by an interrupt or advance_steps) is completed first.
  int advance(std::size_t solver, int frames, const std::atomic<bool>* interrupt = nullptr);
  // Takes up to `steps` more steps of `solver`'s frame under way and, when they complete it,
  // measures it as advance does. True when the frame completed or the solver has stopped.
  bool advance_steps(std::size_t solver, int steps);
  int steps_into_frame(std::size_t solver) const;  // steps taken of the frame under way

  // Every solver rebuilt on `changed` (the same solvers, in the same order, with the same steps),
  // each from its own present state; frames and records go on. Dynamic bodies restart where the
  // scene puts them. The energy audit starts afresh: the change is not the solver's doing.
  void rebuild(scene::Scene changed);
  // Back to the scene's start: every solver rebuilt from the initial state, its records cleared.
  void restart();

  int frame(std::size_t solver) const;    // the last frame measured (0: the initial state)
  double time(std::size_t solver) const;  // s, of that frame
  bool running(std::size_t solver) const;
  // The solver's own status, or unstable when a frame failed the scene's runaway_stretch.
  SolverStatus status(std::size_t solver) const;
  const std::string& message(std::size_t solver) const;  // why it stopped; empty while ok
  const ClothState& state(std::size_t solver) const;
  const Solver& solver(std::size_t solver) const;
  std::vector<BodyState> bodies(std::size_t solver) const;  // its dynamic colliders
  std::int64_t steps(std::size_t solver) const;
  double wall_seconds(std::size_t solver) const;  // s, stepping only

  // Every frame measured so far, frame 0 first.
  struct Record {
    int frame = 0;
    double time = 0.0;  // s
    ClothMetrics metrics;
  };
  const std::vector<Record>& records(std::size_t solver) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace drapelab::runner
