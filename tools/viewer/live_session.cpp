// A scene running live for the viewer (see live_session.hpp).
#include "live_session.hpp"

#include <chrono>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "drapelab/scene/scene_writer.hpp"

namespace drapelab::viewer {

namespace {

// The live drag: a soft constraint of length 0 to the live track, in every solver.
std::vector<DistanceConstraint> live_drag_constraint(const std::shared_ptr<DragTrack>& track) {
  DistanceConstraint live;
  live.b.kind = ConstraintEnd::Kind::drag;
  live.b.drag = track;
  live.mode = ConstraintMode::soft;
  return {live};
}

constexpr std::size_t kHistory = 600;  // frames shown in the stretch plot

}  // namespace

LiveSession::LiveSession(scene::Scene scene, std::shared_ptr<const ClothModel> loaded_model)
    : scene_(std::move(scene)),
      live_(std::make_shared<DragTrack>()),
      simulation_(std::make_unique<runner::Simulation>(scene_, std::move(loaded_model),
                                                       live_drag_constraint(live_))) {
  refresh_views({});
}

void LiveSession::refresh_views(std::vector<std::vector<float>> histories) {
  solvers_.assign(simulation_->solver_count(), LiveSolver{});
  for (std::size_t k = 0; k < solvers_.size(); ++k) {
    LiveSolver& live = solvers_[k];
    live.solver = &simulation_->solver(k);
    live.spec = &simulation_->scene().solvers[k];
    const bool kept = k < histories.size();
    if (kept) live.max_stretch_history = std::move(histories[k]);
    show_frame(k, !kept);  // a kept plot shows this frame already
  }
}

void LiveSession::show_frame(std::size_t solver, bool plot) {
  LiveSolver& live = solvers_[solver];
  live.status = simulation_->status(solver);
  live.message = simulation_->message(solver);
  live.metrics = simulation_->records(solver).back().metrics;
  live.max_penetration = live.metrics.max_penetration;
  if (!plot) return;
  live.max_stretch_history.push_back(static_cast<float>(100.0 * live.metrics.max_stretch));
  if (live.max_stretch_history.size() > kHistory)
    live.max_stretch_history.erase(live.max_stretch_history.begin());
}

void LiveSession::advance_frame() {
  while (!advance_for(std::numeric_limits<double>::infinity())) {
  }
}

void LiveSession::start_frame() {
  if (pending_press_) {
    live_->particle = pending_press_->particle;
    live_->stiffness = pending_press_->stiffness;
    live_->damping = 0.0;
    live_->keyframes = {{time_, live_target_}};  // the spring pulls from this frame's start
    live_->held = true;
    pending_press_.reset();
  }
  if (live_->held) keyframe_now();
  for (LiveSolver& live : solvers_) live.wall_seconds_per_step = 0.0;
  frame_open_ = true;
}

bool LiveSession::advance_for(double budget) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  if (!frame_open_) start_frame();
  constexpr int kChunk = 8;  // steps between looks at the clock
  bool done = false;
  while (!done) {
    done = true;
    for (std::size_t k = 0; k < solvers_.size(); ++k) {
      LiveSolver& live = solvers_[k];
      if (live.status != SolverStatus::ok || simulation_->frame(k) > frame_) continue;
      const auto chunk_start = Clock::now();
      const bool frame_done = simulation_->advance_steps(k, kChunk);
      live.wall_seconds_per_step +=
          std::chrono::duration<double>(Clock::now() - chunk_start).count() /
          live.spec->steps_per_frame;
      if (frame_done && simulation_->frame(k) > frame_) show_frame(k, true);
      live.status = simulation_->status(k);  // a stop within the frame shows at once
      live.message = simulation_->message(k);
      done = done && frame_done;
    }
    if (!done && std::chrono::duration<double>(Clock::now() - start).count() >= budget)
      return false;
  }
  finish_frame();
  return true;
}

void LiveSession::finish_frame() {
  frame_open_ = false;
  ++frame_;
  time_ = frame_ * scene_.frame_period();
}

void LiveSession::reset() {
  if (dragging()) release();
  live_->keyframes.clear();
  finished_.clear();
  frame_open_ = false;
  simulation_->restart();
  refresh_views({});
  time_ = 0.0;
  frame_ = 0;
}

LiveSession::Parameters LiveSession::parameters() const {
  Parameters p;
  const GridClothSpec& cloth = scene_.cloth.grid;
  p.stretch_ks = cloth.stretch.ks;
  p.shear_ks = cloth.shear.ks;
  p.bend_ks = cloth.bend.ks;
  p.contact_stiffness = scene_.contact.stiffness;
  p.friction = scene_.contact.friction;
  p.wind = scene_.air.wind;
  return p;
}

void LiveSession::set_parameters(const Parameters& changed) {
  if (frame_open_) advance_frame();  // finish the frame under way with the old values
  scene_.cloth.grid.stretch.ks = changed.stretch_ks;
  scene_.cloth.grid.shear.ks = changed.shear_ks;
  scene_.cloth.grid.bend.ks = changed.bend_ks;
  scene_.contact.stiffness = changed.contact_stiffness;
  scene_.contact.friction = changed.friction;
  scene_.contact.static_friction = std::max(scene_.contact.static_friction, changed.friction);
  for (Collider& c : scene_.colliders) {
    c.friction = changed.friction;
    c.static_friction = std::max(c.static_friction, changed.friction);
  }
  if (scene_.air.enabled) scene_.air.wind = changed.wind;
  std::vector<std::vector<float>> histories;
  for (LiveSolver& live : solvers_) histories.push_back(std::move(live.max_stretch_history));
  simulation_->rebuild(scene_);
  refresh_views(std::move(histories));
}

void LiveSession::keyframe_now() {
  // The target read at a frame's start is where the spring pulls at the frame's end: over the frame
  // the target moves linearly from the last keyframe to it, so every solver sees a target known
  // when its frame begins, and `drapelab run` replays the same keyframes to the same targets.
  live_->keyframes.push_back({time_ + scene_.frame_period(), live_target_});
}

void LiveSession::press(int particle, const Eigen::Vector3d& target, double stiffness) {
  if (particle < 0 || particle >= model().particle_count())
    throw std::invalid_argument("drag of particle " + std::to_string(particle) +
                                ": the cloth has " + std::to_string(model().particle_count()));
  if (dragging()) release();
  pending_press_ = Press{particle, stiffness};
  live_target_ = target;
}

void LiveSession::move(const Eigen::Vector3d& target) { live_target_ = target; }

void LiveSession::release() {
  if (pending_press_) {  // let go before its frame began: no drag at all
    pending_press_.reset();
    return;
  }
  if (!live_->held) return;
  // The drag ends at its last keyframe: the end of the last frame stepped (or its press).
  live_->held = false;
  scene::DragSpec drag;
  drag.particle = live_->particle;
  drag.stiffness = live_->stiffness;
  drag.damping = live_->damping;
  drag.keyframes = live_->keyframes;
  finished_.push_back(std::move(drag));
}

std::vector<scene::DragSpec> LiveSession::recorded() const {
  std::vector<scene::DragSpec> all = finished_;
  if (live_->held) {
    scene::DragSpec held;
    held.particle = live_->particle;
    held.stiffness = live_->stiffness;
    held.keyframes = live_->keyframes;  // released at the last frame stepped
    all.push_back(std::move(held));
  }
  return all;
}

std::string LiveSession::scene_with_recording() const {
  scene::Scene out = scene_;
  for (scene::DragSpec& drag : recorded()) out.interactions.push_back(std::move(drag));
  return scene::resolved_scene_yaml(out);
}

void LiveSession::save(const std::filesystem::path& path) const {
  const std::string text = scene_with_recording();
  std::ofstream file(path);
  file << text;
  file.close();
  if (!file) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace drapelab::viewer
