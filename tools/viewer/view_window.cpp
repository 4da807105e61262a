// The viewer's window (see view_window.hpp).
#include "view_window.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl2.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <optional>

#include "drapelab/render/camera.hpp"
#include "drapelab/render/collider_meshes.hpp"
#include "drapelab/render/image.hpp"
#include "drapelab/render/panel_renderer.hpp"
#include "drapelab/render/png_io.hpp"
#include "drapelab/render/texture.hpp"
#include "input_script.hpp"

namespace drapelab::viewer {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kPickRadius = 30.0;  // pixels: how near the cursor a particle must be to grab

// The camera as the mouse moves it: an orbit about `target` at `distance`.
struct Orbit {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  // m
  double distance = 3.0;                             // m
  double azimuth = 0.5, elevation = 0.6;             // rad
  double fov_degrees = render::kDefaultFovDegrees;
  double near = 0.01, far = 100.0;  // m

  render::Camera camera() const {
    render::Camera c;
    c.target = target;
    c.eye = target + distance * Eigen::Vector3d(std::cos(elevation) * std::sin(azimuth),
                                                std::sin(elevation),
                                                std::cos(elevation) * std::cos(azimuth));
    c.fov_degrees = fov_degrees;
    c.near = near;
    c.far = far;
    return c;
  }
};

// What the scene starts with: the cloth, the solid colliders' centres and the mesh colliders'
// whole extent (a mesh's centre is the origin of its file, which may lie anywhere near it).
render::Bounds start_bounds(const LiveSession& session) {
  render::Bounds bounds;
  const ClothState& start = session.solvers().front().solver->state();
  for (Eigen::Index i = 0; i < start.x.cols(); ++i) bounds.add(start.x.col(i));
  for (const Collider& c : session.scene().colliders) {
    if (c.shape == ColliderShape::mesh)
      render::add_collider_bounds(c, collider_pose(c, 0.0), bounds);
    if (c.shape != ColliderShape::plane) bounds.add(collider_pose(c, 0.0).translation());
  }
  return bounds;
}

// The orbit that the render's default 3/4 view gives for `bounds`.
Orbit default_orbit(const render::Bounds& bounds, double aspect, double extra_radius) {
  const render::Camera c = render::frame_camera(bounds, aspect, {}, extra_radius);
  Orbit orbit;
  orbit.target = c.target;
  const Eigen::Vector3d d = c.eye - c.target;
  orbit.distance = d.norm();
  orbit.elevation = std::asin(std::clamp(d.y() / orbit.distance, -1.0, 1.0));
  orbit.azimuth = std::atan2(d.x(), d.z());
  orbit.near = c.near;
  orbit.far = c.far * 4.0;  // room to zoom out
  return orbit;
}

// The panels of the window: which solvers are drawn, each in [x0, x1) pixels of the window width,
// right of the controls' column.
struct PanelLayout {
  std::vector<int> solvers;
  int width = 1, height = 1;  // window pixels
  int left = 0;               // pixels taken by the controls

  int n() const { return static_cast<int>(solvers.size()); }
  int panel_of(double x) const {
    return std::clamp(static_cast<int>((x - left) * n() / std::max(1, width - left)), 0, n() - 1);
  }
  int x0(int k) const { return left + k * (width - left) / n(); }
  int x1(int k) const { return left + (k + 1) * (width - left) / n(); }
};

constexpr int kControlsWidth = 390;  // pixels

// A world ray through window pixel (x, y) of panel k (y down).
std::pair<Eigen::Vector3d, Eigen::Vector3d> cursor_ray(const render::Camera& camera,
                                                       const PanelLayout& layout, int k, double x,
                                                       double y) {
  const double w = layout.x1(k) - layout.x0(k), h = layout.height;
  const Eigen::Matrix4d clip_of_world =
      render::projection_matrix(camera, w / h) * render::view_matrix(camera);
  const Eigen::Matrix4d world_of_clip = clip_of_world.inverse();
  const double nx = 2.0 * (x - layout.x0(k)) / w - 1.0, ny = 1.0 - 2.0 * y / h;
  auto unproject = [&](double z) {
    const Eigen::Vector4d p = world_of_clip * Eigen::Vector4d(nx, ny, z, 1.0);
    return Eigen::Vector3d(p.head<3>() / p.w());
  };
  const Eigen::Vector3d from = unproject(-1.0);
  return {from, (unproject(1.0) - from).normalized()};
}

class Window {
 public:
  Window(LiveSession& session, const ViewOptions& options) : session_(session), options_(options) {}

  int run(const std::vector<ScriptEvent>& script);

 private:
  void handle_mouse();
  void apply(const ScriptEvent& event, int* exit_code, bool* quit);
  void grab(double x, double y);
  void drag_to(double x, double y);
  void draw_panels();
  void draw_controls();
  void parameter_sliders();
  bool screenshot(const std::string& file);
  bool save(const std::string& file);
  void step_simulation(bool lockstep);

  LiveSession& session_;
  const ViewOptions& options_;
  GLFWwindow* window_ = nullptr;
  std::unique_ptr<render::PanelRenderer> renderer_;
  Orbit orbit_;
  PanelLayout layout_;
  int shown_ = -1;  // the solver drawn alone, -1: all side by side
  bool playing_ = true;
  bool step_once_ = false;
  float time_scale_ = 1.0f;  // scene frames per drawn frame
  double frame_debt_ = 0.0;  // scene frames owed to the time scale
  Clock::time_point last_draw_ = Clock::now();
  double draw_seconds_ = 0.0;           // s, the last frame's drawing and swap
  float drag_stiffness_ = 20.0f;        // N/m
  int grab_panel_ = 0;                  // the panel the drag started in
  Eigen::Vector3d grab_normal_;         // the drag plane's normal (towards the camera)
  Eigen::Vector3d grab_point_;          // a point of it (m)
  double last_x_ = 0.0, last_y_ = 0.0;  // cursor, for orbit and pan
  std::string status_line_;
};

void Window::grab(double x, double y) {
  const render::Camera camera = orbit_.camera();
  const int k = layout_.panel_of(x);
  const Solver& solver = *session_.solvers()[static_cast<std::size_t>(layout_.solvers[k])].solver;
  const int w = layout_.x1(k) - layout_.x0(k);
  double best = kPickRadius;
  int picked = -1;
  const Eigen::Matrix3Xd& positions = solver.state().x;
  for (Eigen::Index i = 0; i < positions.cols(); ++i) {
    if (session_.model().is_pinned(static_cast<int>(i))) continue;
    const auto pixel = render::project_to_pixel(camera, positions.col(i), w, layout_.height);
    if (!pixel) continue;
    const double d = std::hypot(pixel->x() + layout_.x0(k) - x, pixel->y() - y);
    if (d < best) best = d, picked = static_cast<int>(i);
  }
  if (picked < 0) {
    status_line_ = "no free particle under the cursor";
    return;
  }
  grab_panel_ = k;
  grab_point_ = positions.col(picked);
  grab_normal_ = (camera.eye - camera.target).normalized();
  session_.press(picked, grab_point_, drag_stiffness_);
  // describe_particle names the particle itself: "particle 50 (grid i=6, j=5)".
  status_line_ = "dragging " + session_.model().describe_particle(picked);
}

void Window::drag_to(double x, double y) {
  if (!session_.dragging()) return;
  const auto [from, direction] = cursor_ray(orbit_.camera(), layout_, grab_panel_, x, y);
  const double facing = direction.dot(grab_normal_);
  if (std::abs(facing) < 1e-9) return;  // the ray runs along the plane
  const double along = (grab_point_ - from).dot(grab_normal_) / facing;
  session_.move(from + along * direction);
}

void Window::handle_mouse() {
  const ImGuiIO& io = ImGui::GetIO();
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window_, &x, &y);
  const bool left = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  const bool right = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  const bool middle = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
  const double dx = x - last_x_, dy = y - last_y_;
  last_x_ = x, last_y_ = y;
  if (session_.dragging()) {
    if (left)
      drag_to(x, y);
    else
      session_.release();
    return;
  }
  if (io.WantCaptureMouse) return;
  if (left && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) grab(x, y);
  if (right) {  // orbit
    orbit_.azimuth -= 0.005 * dx;
    orbit_.elevation = std::clamp(orbit_.elevation + 0.005 * dy, -1.5, 1.5);
  }
  if (middle) {  // pan in the view plane
    const render::Camera c = orbit_.camera();
    const Eigen::Vector3d forward = (c.target - c.eye).normalized();
    const Eigen::Vector3d side = forward.cross(Eigen::Vector3d::UnitY()).normalized();
    const Eigen::Vector3d up = side.cross(forward);
    const double scale = orbit_.distance * 0.0015;  // m per pixel, roughly
    orbit_.target += scale * (-dx * side + dy * up);
  }
  if (io.MouseWheel != 0.0f) orbit_.distance *= std::pow(0.9, io.MouseWheel);
}

void Window::step_simulation(bool lockstep) {
  const auto now = Clock::now();
  const double wall = std::min(0.1, std::chrono::duration<double>(now - last_draw_).count());
  last_draw_ = now;
  if (!playing_ && !step_once_) return;
  if (lockstep) {  // a script: exactly time_scale frames per drawn frame, for reproducibility
    frame_debt_ += step_once_ ? 1.0 : time_scale_;
    step_once_ = false;
    for (; frame_debt_ >= 1.0; frame_debt_ -= 1.0) session_.advance_frame();
    return;
  }
  // Live: the scene's frames at time_scale x real time as far as the budget of this drawn frame
  // allows; a slow scene runs slower than real time, and the window keeps its frame rate.
  frame_debt_ = std::min(
      2.0, frame_debt_ + (step_once_ ? 1.0 : time_scale_ * session_.scene().frame_rate * wall));
  step_once_ = false;
  // Stepping gets what a 40 Hz frame leaves after drawing (at least 4 ms): the window stays above
  // 30 frames per second however slow the solvers are.
  const double budget = std::max(0.004, 1.0 / 40.0 - draw_seconds_);  // s
  while (frame_debt_ > 0.0) {
    const double left = budget - std::chrono::duration<double>(Clock::now() - now).count();
    if (left <= 0.0) break;
    if (!session_.advance_for(left)) break;
    frame_debt_ -= 1.0;
  }
}

void Window::draw_panels() {
  const render::Camera camera = orbit_.camera();
  for (std::size_t k = 0; k < layout_.solvers.size(); ++k) {
    const LiveSolver& live = session_.solvers()[static_cast<std::size_t>(layout_.solvers[k])];
    render::BodyPoses bodies;
    for (const BodyState& body : live.solver->bodies()) bodies[body.collider] = body.pose;
    const int x0 = layout_.x0(static_cast<int>(k)), x1 = layout_.x1(static_cast<int>(k));
    renderer_->draw(camera, x0, 0, x1 - x0, layout_.height, live.solver->state().x,
                    live.solver->state().time, &bodies);
  }
  glViewport(0, 0, layout_.width, layout_.height);
  // Each panel's solver, and the live drag as a line from the particle to its target.
  ImDrawList* overlay = ImGui::GetForegroundDrawList();
  for (std::size_t k = 0; k < layout_.solvers.size(); ++k) {
    const Solver& solver = *session_.solvers()[static_cast<std::size_t>(layout_.solvers[k])].solver;
    const int x0 = layout_.x0(static_cast<int>(k)), w = layout_.x1(static_cast<int>(k)) - x0;
    overlay->AddText(ImVec2(float(x0 + 8), 6.0f), IM_COL32(20, 20, 20, 255), solver.name().c_str());
    if (!session_.dragging()) continue;
    const auto from = render::project_to_pixel(
        camera, solver.state().x.col(session_.dragged_particle()), w, layout_.height);
    const auto to = render::project_to_pixel(camera, session_.drag_target(), w, layout_.height);
    if (from && to)
      overlay->AddLine(ImVec2(float(x0 + from->x()), float(from->y())),
                       ImVec2(float(x0 + to->x()), float(to->y())), IM_COL32(30, 90, 200, 255),
                       2.0f);
  }
}

void Window::draw_controls() {
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(float(layout_.left), float(layout_.height)));
  ImGui::Begin(session_.scene().name.c_str(), nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  ImGui::Text("t = %.3f s (frame %d)", session_.time(), session_.frame());
  if (ImGui::Button(playing_ ? "Pause" : "Play")) playing_ = !playing_;
  ImGui::SameLine();
  if (ImGui::Button("Step")) step_once_ = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset")) session_.reset();
  ImGui::SameLine();
  if (ImGui::Button("Save")) save(options_.save_path);
  ImGui::SliderFloat("time scale", &time_scale_, 0.05f, 4.0f, "%.2f x real time");
  ImGui::SliderFloat("drag stiffness", &drag_stiffness_, 0.1f, 500.0f, "%.1f N/m",
                     ImGuiSliderFlags_Logarithmic);
  std::vector<std::string> names = {"all, side by side"};
  for (const LiveSolver& live : session_.solvers()) names.push_back(live.solver->name());
  int choice = shown_ + 1;
  if (ImGui::BeginCombo("show", names[static_cast<std::size_t>(choice)].c_str())) {
    for (int k = 0; k < static_cast<int>(names.size()); ++k)
      if (ImGui::Selectable(names[static_cast<std::size_t>(k)].c_str(), k == choice))
        shown_ = k - 1;
    ImGui::EndCombo();
  }
  parameter_sliders();
  ImGui::Text("recorded drags: %zu", session_.recorded().size());
  if (!status_line_.empty()) ImGui::TextWrapped("%s", status_line_.c_str());
  for (const LiveSolver& live : session_.solvers()) {
    const Solver& solver = *live.solver;
    ImGui::Separator();
    ImGui::Text("%s: %s", solver.name().c_str(), solver_status_name(live.status));
    if (live.status != SolverStatus::ok) {
      ImGui::TextWrapped("%s", live.message.c_str());
      continue;
    }
    const ClothMetrics& m = live.metrics;
    ImGui::Text("stretch max %.2f %%  mean %.2f %%", 100.0 * m.max_stretch, 100.0 * m.mean_stretch);
    ImGui::Text("energy %.4g J (kinetic %.3g)",
                m.kinetic_energy + m.spring_energy + m.gravity_energy, m.kinetic_energy);
    if (live.max_penetration) ImGui::Text("penetration %.2f mm", 1000.0 * *live.max_penetration);
    ImGui::Text("%.1f us per step, %d steps per frame", 1e6 * live.wall_seconds_per_step,
                live.spec->steps_per_frame);
    ImGui::PlotLines("max stretch %", live.max_stretch_history.data(),
                     static_cast<int>(live.max_stretch_history.size()), 0, nullptr, 0.0f, FLT_MAX,
                     ImVec2(0, 40));
  }
  ImGui::End();
}

// Sliders for the springs, the contact, the friction and the wind: a change takes effect when the
// slider is let go (the solvers are rebuilt from their present state, live_session.hpp).
void Window::parameter_sliders() {
  if (!ImGui::CollapsingHeader("parameters")) return;
  LiveSession::Parameters p = session_.parameters();
  bool changed = false;
  auto slider = [&](const char* label, double& value, double low, double high, const char* format) {
    float v = static_cast<float>(value);
    ImGui::SliderFloat(label, &v, static_cast<float>(low), static_cast<float>(high), format,
                       ImGuiSliderFlags_Logarithmic);
    if (ImGui::IsItemDeactivatedAfterEdit()) value = v, changed = true;
  };
  slider("stretch ks", p.stretch_ks, 1.0, 1e5, "%.0f N/m");
  slider("shear ks", p.shear_ks, 0.1, 1e4, "%.1f N/m");
  slider("bend ks", p.bend_ks, 0.001, 1e3, "%.3f N/m");
  if (!session_.scene().colliders.empty()) {
    slider("contact stiffness", p.contact_stiffness, 10.0, 1e5, "%.0f N/m");
    float mu = static_cast<float>(p.friction);
    ImGui::SliderFloat("friction", &mu, 0.0f, 2.0f, "%.2f");
    if (ImGui::IsItemDeactivatedAfterEdit()) p.friction = mu, changed = true;
  }
  if (session_.scene().air.enabled) {
    float wind[3] = {float(p.wind.x()), float(p.wind.y()), float(p.wind.z())};
    ImGui::SliderFloat3("wind m/s", wind, -20.0f, 20.0f, "%.1f");
    if (ImGui::IsItemDeactivatedAfterEdit()) p.wind = {wind[0], wind[1], wind[2]}, changed = true;
  }
  if (changed) {
    session_.set_parameters(p);
    status_line_ = "parameters changed: every solver continues from its present state";
  }
}

bool Window::screenshot(const std::string& file) {
  render::Image image(layout_.width, layout_.height, 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  std::vector<std::uint8_t> rows(image.pixels.size());
  glReadPixels(0, 0, layout_.width, layout_.height, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
  const std::size_t stride = std::size_t(layout_.width) * 3;
  for (int y = 0; y < layout_.height; ++y)  // GL's rows go up from the bottom
    std::copy_n(rows.data() + std::size_t(layout_.height - 1 - y) * stride, stride, image.at(0, y));
  try {
    render::write_png(file, image);
  } catch (const std::exception& e) {
    std::cerr << "drapelab view: screenshot: " << e.what() << "\n";
    return false;
  }
  return true;
}

bool Window::save(const std::string& file) {
  try {
    session_.save(file);
    status_line_ = "saved " + file + " (" + std::to_string(session_.recorded().size()) +
                   " recorded drags): drapelab run replays them";
  } catch (const std::exception& e) {
    status_line_ = e.what();
    std::cerr << "drapelab view: save: " << e.what() << "\n";
    return false;
  }
  return true;
}

void Window::apply(const ScriptEvent& event, int* exit_code, bool* quit) {
  switch (event.kind) {
    case ScriptEvent::Kind::press:
      grab(event.x, event.y);
      break;
    case ScriptEvent::Kind::move:
      drag_to(event.x, event.y);
      break;
    case ScriptEvent::Kind::release:
      session_.release();
      break;
    case ScriptEvent::Kind::save:
      if (!save(event.file)) *exit_code = 1;
      break;
    case ScriptEvent::Kind::quit:
      *quit = true;
      break;
    case ScriptEvent::Kind::screenshot:
      break;  // after the frame is drawn
  }
}

int Window::run(const std::vector<ScriptEvent>& script) {
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
  window_ = glfwCreateWindow(options_.width, options_.height,
                             ("drapelab view: " + session_.scene().name).c_str(), nullptr, nullptr);
  if (!window_) {
    const char* display = std::getenv("DISPLAY");
    std::cerr << "drapelab view: cannot open a window on DISPLAY=" << (display ? display : "")
              << ". Render offline instead: drapelab run SCENE --meshes pc2 --out DIR, then "
                 "drapelab render DIR\n";
    return 2;
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(0);  // as fast as it draws: the frame rate measures the viewer, not the screen
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working folder
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL2_Init();
  const render::Bounds framing = start_bounds(session_);
  renderer_ = std::make_unique<render::PanelRenderer>(session_.scene(), session_.model(),
                                                      render::checker_texture(), framing);
  playing_ = !options_.start_paused;
  int exit_code = 0;
  int frame = 0;
  std::size_t next_event = 0;
  bool quit = false;
  const auto start = Clock::now();
  bool framed = false;
  while (!glfwWindowShouldClose(window_) && !quit) {
    glfwPollEvents();
    glfwGetFramebufferSize(window_, &layout_.width, &layout_.height);
    layout_.left = std::min(kControlsWidth, layout_.width / 3);
    layout_.solvers.clear();
    for (int k = 0; k < static_cast<int>(session_.solvers().size()); ++k)
      if (shown_ < 0 || shown_ == k) layout_.solvers.push_back(k);
    if (!framed) {
      const double aspect = double(layout_.x1(0) - layout_.x0(0)) / std::max(1, layout_.height);
      orbit_ = default_orbit(framing, aspect, renderer_->extra_radius());
      framed = true;
    }
    ImGui_ImplOpenGL2_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    for (; next_event < script.size() && script[next_event].frame <= frame; ++next_event)
      if (script[next_event].kind != ScriptEvent::Kind::screenshot)
        apply(script[next_event], &exit_code, &quit);
    if (script.empty()) handle_mouse();
    step_simulation(!script.empty());
    const auto draw_start = Clock::now();
    draw_panels();
    draw_controls();
    ImGui::Render();
    ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());
    for (const ScriptEvent& event : script)
      if (event.kind == ScriptEvent::Kind::screenshot && event.frame == frame &&
          !screenshot(event.file))
        exit_code = 1;
    glfwSwapBuffers(window_);
    draw_seconds_ = std::chrono::duration<double>(Clock::now() - draw_start).count();
    ++frame;
    if (options_.frames > 0 && frame >= options_.frames) break;
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (options_.report)
    std::printf(
        "drapelab view: %d frames in %.2f s: %.1f frames per second; simulated %.3f s, "
        "%.2f x real time (%s, %zu solvers, %d particles)\n",
        frame, seconds, frame / seconds, session_.time(), session_.time() / seconds,
        session_.scene().name.c_str(), session_.solvers().size(),
        session_.model().particle_count());
  ImGui_ImplOpenGL2_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  renderer_.reset();
  glfwDestroyWindow(window_);
  return exit_code;
}

void report_glfw_error(int code, const char* text) {
  std::cerr << "drapelab view: GLFW error " << code << ": " << text << "\n";
}

}  // namespace

int run_view_window(LiveSession& session, const ViewOptions& options) {
  std::vector<ScriptEvent> script;
  if (!options.script.empty()) {
    std::string error;
    const auto events = read_input_script(options.script, &error);
    if (!events) {
      std::cerr << "error: " << error << "\n";
      return 2;
    }
    script = *events;
  }
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display) {
    std::cerr << "drapelab view needs a display, and the DISPLAY variable is not set. Run it on a "
                 "desktop (or under Xvfb), or render offline: drapelab run SCENE --meshes pc2 "
                 "--out DIR, then drapelab render DIR\n";
    return 2;
  }
  glfwSetErrorCallback(report_glfw_error);
  if (!glfwInit()) {
    std::cerr << "drapelab view: cannot open the display DISPLAY=" << display
              << ". Render offline instead: drapelab run SCENE --meshes pc2 --out DIR, then "
                 "drapelab render DIR\n";
    return 2;
  }
  int code = 0;
  {
    Window window(session, options);
    code = window.run(script);
  }
  glfwTerminate();
  return code;
}

}  // namespace drapelab::viewer
