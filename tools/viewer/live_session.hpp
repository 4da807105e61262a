// A scene running live for the viewer: a runner::Simulation of the scene (every solver built,
// stepped, measured and checked as `drapelab run` does it), stepped frame by frame on demand, with
// one live drag that pulls the same particle of every solver
// toward the same target (the mouse), and the record of the drags made, which saves as the scene's
// `interactions:` so that `drapelab run` replays them. Knows nothing of windows or GL.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drapelab/cloth_metrics.hpp"
#include "drapelab/drag_track.hpp"
#include "drapelab/runner/simulation.hpp"
#include "drapelab/scene/scene.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::viewer {

// One solver of the session and what the viewer shows of it.
struct LiveSolver {
  const Solver* solver = nullptr;  // the simulation's; replaced by a rebuild or a reset
  const scene::SolverSpec* spec = nullptr;
  // The run's status and message: the solver's own, or unstable when a frame's stretch passed the
  // scene's runaway_stretch.
  SolverStatus status = SolverStatus::ok;
  std::string message;
  ClothMetrics metrics;                    // at the last frame
  std::optional<double> max_penetration;   // m, against the scene's colliders (none: empty)
  double wall_seconds_per_step = 0.0;      // s, over the last frame
  std::vector<float> max_stretch_history;  // %, one per frame, for the plot
};

class LiveSession {
 public:
  // `loaded_model` is the loader's cloth of this scene (or null to build it).
  LiveSession(scene::Scene scene, std::shared_ptr<const ClothModel> loaded_model);

  const scene::Scene& scene() const { return scene_; }
  const ClothModel& model() const { return simulation_->model(); }
  std::vector<LiveSolver>& solvers() { return solvers_; }
  const std::vector<LiveSolver>& solvers() const { return solvers_; }
  double time() const { return time_; }  // s, the simulated time of the last frame
  int frame() const { return frame_; }

  // Advances every running solver by one frame of the scene (frame_rate), each with its own dt.
  void advance_frame();
  // Steps toward the end of the current frame for at most `budget` wall seconds (at least one
  // step of each unfinished solver), so that a window keeps drawing while a slow scene computes;
  // true when the frame completed. A frame spread over calls steps exactly as advance_frame.
  bool advance_for(double budget);
  // Every solver back to the scene's start, and the recording cleared: its drags acted on the run
  // that is gone, and a replay from the start would not meet the cloth they met.
  void reset();

  // The parameters the viewer's sliders change while the scene runs.
  struct Parameters {
    double stretch_ks = 0.0, shear_ks = 0.0, bend_ks = 0.0;  // N/m, the cloth's springs
    double contact_stiffness = 0.0;                          // N/m
    double friction = 0.0;                                   // every collider's Coulomb coefficient
    Eigen::Vector3d wind = Eigen::Vector3d::Zero();          // m/s (scenes with air only)
  };
  Parameters parameters() const;
  // Takes `changed` from the end of the current frame: every solver is rebuilt with it from its own
  // present positions and velocities (its dynamic bodies restart where the scene puts them), with
  // the same step. The saved scene carries the new values.
  void set_parameters(const Parameters& changed);

  // The live drag: press on particle `particle` pulling toward `target` (m) with `stiffness`
  // (N/m); move the target; release. The spring pulls from the next frame's start (a press during a
  // frame waits for it, so that every solver is pulled from the same step); the target
  // given by the time a frame starts is reached at that frame's end (linearly over it), and a
  // release lets go at the end of the last frame stepped. A press while one is held releases it.
  void press(int particle, const Eigen::Vector3d& target, double stiffness);
  void move(const Eigen::Vector3d& target);
  void release();
  bool dragging() const { return live_->held || pending_press_; }
  int dragged_particle() const {
    return pending_press_ ? pending_press_->particle : live_->particle;
  }
  double drag_stiffness() const { return live_->stiffness; }
  const Eigen::Vector3d& drag_target() const { return live_target_; }

  // The drags made so far (the one held included, up to now), as `interactions:` entries.
  std::vector<scene::DragSpec> recorded() const;
  // The scene with its own interactions and the recorded ones, as resolved YAML.
  std::string scene_with_recording() const;
  // Writes scene_with_recording() to `path` (throws std::runtime_error naming it on failure).
  void save(const std::filesystem::path& path) const;

 private:
  // The solvers' views, after the simulation was built, rebuilt or restarted (`histories`: the
  // plots to keep, one per solver, or empty to start them afresh).
  void refresh_views(std::vector<std::vector<float>> histories);
  // The view of the frame the simulation measured last, added to the stretch plot when `plot`.
  void show_frame(std::size_t solver, bool plot);
  void keyframe_now();  // the live target, for the end of the frame about to be stepped
  void start_frame();   // the pending press, the live keyframe, the step timers
  void finish_frame();  // counts the frame

  scene::Scene scene_;
  std::shared_ptr<DragTrack> live_;  // shared by every solver's constraints
  std::unique_ptr<runner::Simulation> simulation_;
  std::vector<LiveSolver> solvers_;
  Eigen::Vector3d live_target_ = Eigen::Vector3d::Zero();
  struct Press {
    int particle;
    double stiffness;
  };
  std::optional<Press> pending_press_;     // waits for the next frame's start
  bool frame_open_ = false;                // a frame is partly stepped
  std::vector<scene::DragSpec> finished_;  // released drags
  double time_ = 0.0;
  int frame_ = 0;
};

}  // namespace drapelab::viewer
