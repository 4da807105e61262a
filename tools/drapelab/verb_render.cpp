// drapelab render RUN_DIR: every recorded frame of a run as a PNG (one panel per solver, side by
// side), and a video when ffmpeg is installed. Offscreen GL (OSMesa): no display or GPU needed.
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <regex>

#include "drapelab/render/camera.hpp"
#include "drapelab/render/frame_image.hpp"
#include "drapelab/render/offscreen_context.hpp"
#include "drapelab/render/panel_renderer.hpp"
#include "drapelab/render/png_io.hpp"
#include "drapelab/render/run_frames.hpp"
#include "drapelab/render/text.hpp"
#include "drapelab/render/texture.hpp"
#include "drapelab/render/video.hpp"
#include "drapelab/report/run_completeness.hpp"
#include "drapelab/run_folder/run_transaction.hpp"
#include "drapelab/runner/run_scene.hpp"
#include "interrupt.hpp"
#include "verbs.hpp"

namespace drapelab::cli {

namespace fs = std::filesystem;

void add_render_options(CLI::App& verb, RenderArguments& arguments) {
  verb.add_option("run_dir", arguments.run_dir,
                  "Run folder written by drapelab run with --meshes pc2 (or obj)")
      ->required();
  verb.add_option("--out,-o", arguments.out,
                  "Folder for frame_NNNN.png and video.mp4 (default RUN_DIR/render)");
  verb.add_option("--size", arguments.size,
                  "Image size WxH in pixels, all panels together (default 480 x 480 per solver)");
  verb.add_option(
      "--camera", arguments.camera,
      "Camera: \"eye=x,y,z;target=x,y,z;fov=deg\" (m, vertical degrees; any subset, the rest from "
      "the default 3/4 view from above)");
  verb.add_option("--texture", arguments.texture,
                  "PNG mapped onto the cloth through its UVs (default: a checker)");
  verb.add_option("--every", arguments.every,
                  "Render every Nth recorded frame (frames 0, N, 2N, ...)")
      ->check(CLI::PositiveNumber);
  verb.footer(
      "Example:\n  drapelab run scenes/sphere_drape.yaml --out out/sphere_drape --meshes pc2\n"
      "  drapelab render out/sphere_drape --size 1280x480\n"
      "--size is at most 8192 pixels a side, and refused when its frame needs more memory than "
      "is available.\nExit codes: 0 done, 1 rendering or ffmpeg failed, or the run is incomplete "
      "(killed: drawn as far as it goes, and said on stderr), 2 bad input (not a run folder, a "
      "point cache cut short, a bad option; nothing rendered), 130 interrupted.");
}

namespace {

constexpr int kSupersample = 2;         // rendered at 2x and averaged down: antialiased edges
constexpr int kDefaultPanelSize = 480;  // pixels, square panels by default
constexpr int kMinimumSize = 16;        // pixels, smallest width or height accepted
// Pixels, the largest width or height accepted, and the largest buffer side rendered (larger
// images skip supersampling). At 8192 x 8192 a frame needs about 1.5 GB (estimated_bytes).
constexpr int kMaximumSize = 8192;

// Bytes a frame needs at its peak: per rendered pixel the GL colour (4) and depth (4) buffers,
// the read-back copy (3), the flipped image (3) and the image handed to the downsampling (3); per
// output pixel the downsampled image and the one written to PNG (3 + 3).
double estimated_bytes(int width, int height, int supersample) {
  const double rendered = double(width) * supersample * height * supersample;
  return 17.0 * rendered + 6.0 * double(width) * height;
}

// Bytes of memory available to a new allocation (MemAvailable of /proc/meminfo); nullopt when
// unknown.
std::optional<double> available_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kilobytes = 0.0;
  std::string unit;
  while (meminfo >> key >> kilobytes >> unit)
    if (key == "MemAvailable:") return kilobytes * 1024.0;
  return std::nullopt;
}

std::optional<std::pair<int, int>> parse_size(const std::string& text) {
  std::smatch match;
  static const std::regex pattern(R"(\s*(\d{1,5})\s*[xX]\s*(\d{1,5})\s*)");
  if (!std::regex_match(text, match, pattern)) return std::nullopt;
  return std::make_pair(std::stoi(match[1]), std::stoi(match[2]));
}

// frame_0007.png: zero-padded to `digits`, so names sort in frame order (ffmpeg's glob sorts by
// name).
// Records the render's files in the run folder's manifest (when they are inside it), so that the
// next run into the folder removes frames that show a different run.
void record_render(const fs::path& run_dir, const fs::path& out) {
  static const std::regex frame_name(R"(frame_\d+\.png)");
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(out, ec)) {
    const std::string name = entry.path().filename().string();
    if (std::regex_match(name, frame_name) || name == "video.mp4") files.push_back(entry.path());
  }
  if (const auto problem = run_folder::add_to_manifest(run_dir, files))
    std::cerr << "warning: the render is not in the run folder's manifest: " << *problem << "\n";
}

std::string frame_file_name(int frame, int digits) {
  std::string number = std::to_string(frame);
  if (static_cast<int>(number.size()) < digits) number.insert(0, digits - number.size(), '0');
  return "frame_" + number + ".png";
}

// Removes a previous render's frames and video from the output folder (only names this verb
// writes), so the folder holds one render and ffmpeg's glob sees only its frames.
void remove_previous_render(const fs::path& folder) {
  static const std::regex frame_name(R"(frame_\d+\.png)");
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (std::regex_match(name, frame_name) || name == "video.mp4") fs::remove(entry.path(), ec);
  }
}

}  // namespace

namespace {

int render_run(const RenderArguments& arguments, const std::atomic<bool>& interrupt) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  std::string error;
  const auto camera_spec = render::parse_camera_spec(arguments.camera, &error);
  if (!camera_spec) {
    std::cerr << "error: " << error << "\nnothing was rendered\n";
    return kExitBadInput;
  }
  std::optional<std::pair<int, int>> size;
  if (!arguments.size.empty()) {
    size = parse_size(arguments.size);
    const int limit = std::min(kMaximumSize, render::OffscreenContext::max_size());
    if (!size || size->first < kMinimumSize || size->second < kMinimumSize || size->first > limit ||
        size->second > limit) {
      std::cerr << "error: --size must be WxH with each between " << kMinimumSize << " and "
                << limit << " pixels, e.g. 1280x480; got '" << arguments.size
                << "'\nnothing was rendered\n";
      return kExitBadInput;
    }
  }

  render::RunFrames run;
  render::Image texture;
  try {
    run = render::load_run_frames(arguments.run_dir);
    texture = arguments.texture.empty() ? render::checker_texture()
                                        : render::load_texture(arguments.texture);
  } catch (const std::exception& e) {  // RunInputError and unreadable files: bad input either way
    std::cerr << "error: " << e.what() << "\nnothing was rendered\n";
    return kExitBadInput;
  }
  const int panel_count = static_cast<int>(run.solvers.size());
  const int width = size ? size->first : kDefaultPanelSize * panel_count;
  const int height = size ? size->second : kDefaultPanelSize;
  if (width < panel_count * kMinimumSize) {
    std::cerr << "error: --size " << arguments.size << " leaves less than " << kMinimumSize
              << " pixels per panel for " << panel_count << " solvers\nnothing was rendered\n";
    return kExitBadInput;
  }
  const fs::path out =
      arguments.out.empty() ? fs::path(arguments.run_dir) / "render" : fs::path(arguments.out);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (!fs::is_directory(out)) {
    std::cerr << "error: cannot create the output folder " << out.string()
              << "\nnothing was rendered\n";
    return kExitBadInput;
  }
  // Supersampling needs a buffer twice the size; large images render at 1x.
  const int supersample = std::max(width, height) * kSupersample <=
                                  std::min(kMaximumSize, render::OffscreenContext::max_size())
                              ? kSupersample
                              : 1;
  const double needed = estimated_bytes(width, height, supersample);
  if (const auto available = available_bytes(); available && needed > *available) {
    std::cerr << "error: a " << width << " x " << height << " image needs about "
              << std::round(needed / 1e8) / 10 << " GB of memory, and "
              << std::round(*available / 1e8) / 10
              << " GB is available; choose a smaller --size\nnothing was rendered\n";
    return kExitBadInput;
  }
  // A run that did not end whole is drawn as far as it goes, and said so.
  const report::RunCompleteness completeness = report::inspect_run(arguments.run_dir);
  for (const auto& line : completeness.notices())
    std::cerr << (completeness.incomplete() ? "warning: " : "note: ") << line << "\n";
  remove_previous_render(out);
  const PollingSection polling;  // Ctrl-C stops after the current frame

  try {
    render::OffscreenContext context(width * supersample, height * supersample);
    const render::Bounds framing = render::framing_bounds(run);
    const render::PanelRenderer renderer(run.scene, run.model, texture, framing);
    const double panel_aspect = double(width) / panel_count / height;
    const render::Camera camera =
        render::frame_camera(framing, panel_aspect, *camera_spec, renderer.extra_radius());
    render::Font font(render::default_font_file());

    const int digits =
        std::max<int>(4, static_cast<int>(std::to_string(run.frame_count - 1).size()));
    int written = 0;
    for (int frame = 0; frame < run.frame_count; frame += arguments.every) {
      if (interrupt.load(std::memory_order_relaxed)) {
        std::cerr << "interrupted after " << written << " frames; " << out.string()
                  << " holds them\n";
        record_render(arguments.run_dir, out);
        return runner::kExitInterrupted;
      }
      const double time = frame / run.scene.frame_rate;  // s
      std::vector<Eigen::Matrix3Xd> positions(run.solvers.size());
      std::vector<render::Panel> panels(run.solvers.size());
      for (std::size_t s = 0; s < run.solvers.size(); ++s) {
        const auto& solver = run.solvers[s];
        // A solver that stopped early (unstable) is shown at its last recorded frame.
        const int shown = std::min(frame, solver.source->frame_count() - 1);
        positions[s] = solver.source->positions(shown);
        const auto metrics = solver.metrics.find(shown);
        panels[s].title =
            solver.name +
            (solver.status == "ok" || solver.status.empty() ? "" : " (" + solver.status + ")");
        panels[s].legend = render::legend_lines(
            time, frame, metrics == solver.metrics.end() ? nullptr : &metrics->second);
        if (shown < frame) {
          char note[64];
          std::snprintf(note, sizeof note, "stopped after t = %.3f s",
                        shown / run.scene.frame_rate);
          panels[s].legend.push_back(note);
        }
        panels[s].cloth = &positions[s];
        const auto bodies = solver.bodies.find(shown);
        if (bodies != solver.bodies.end()) panels[s].bodies = &bodies->second;
      }
      const render::Image image =
          render::render_frame(context, renderer, camera, panels, time, supersample, font);
      render::write_png(out / frame_file_name(frame, digits), image);
      ++written;
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::cout << "rendered " << written << " frames of " << run.scene.name << " (" << width << " x "
              << height << ", " << panel_count << (panel_count == 1 ? " panel" : " panels")
              << ") into " << out.string() << " in " << std::round(seconds * 10) / 10 << " s ("
              << context.description() << ")\n";
    std::cout << "camera: eye=" << camera.eye.x() << "," << camera.eye.y() << "," << camera.eye.z()
              << ";target=" << camera.target.x() << "," << camera.target.y() << ","
              << camera.target.z() << ";fov=" << camera.fov_degrees << "\n";
  } catch (const std::bad_alloc&) {
    std::cerr << "error: out of memory while rendering " << width << " x " << height
              << " images; choose a smaller --size\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  record_render(arguments.run_dir, out);
  const int done = completeness.incomplete() ? 1 : 0;  // an incomplete run: drawn, but not whole

  // The video, at the rate the frames were recorded (every Nth frame: rate / N).
  const double fps = run.scene.frame_rate / arguments.every;
  const fs::path video = out / "video.mp4";
  const auto ffmpeg_arguments = render::ffmpeg_arguments(out, fps, video);
  const auto ffmpeg = render::find_on_path("ffmpeg");
  if (!ffmpeg) {
    std::cout << "no video: ffmpeg is not on PATH; to make one, apt-get install ffmpeg, then run: "
              << render::shell_command("ffmpeg", ffmpeg_arguments) << "\n";
    return done;
  }
  const int status = render::run_program(*ffmpeg, ffmpeg_arguments, &error);
  if (status != 0) {
    std::cerr << "error: ffmpeg failed ("
              << (status < 0 ? error : "exit status " + std::to_string(status))
              << "); the frames are in " << out.string()
              << "; the command was: " << render::shell_command(ffmpeg->string(), ffmpeg_arguments)
              << "\n";
    return 1;
  }
  std::cout << "video: " << video.string() << " (H.264, " << fps << " frames per second)\n";
  record_render(arguments.run_dir, out);
  return done;
}

}  // namespace

int render_verb(const RenderArguments& arguments, const std::atomic<bool>& interrupt) {
  try {
    return render_run(arguments, interrupt);
  } catch (const std::bad_alloc&) {
    std::cerr << "error: drapelab render ran out of memory\n";
    return 1;
  } catch (const std::exception& e) {  // reading the run folder: bad input
    std::cerr << "error: " << e.what() << "\nnothing was rendered\n";
    return kExitBadInput;
  }
}

}  // namespace drapelab::cli
