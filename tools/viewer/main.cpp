// drapelab-view: the interactive viewer (`drapelab view` runs it). Loads a scene as `drapelab run`
// does, runs every solver live in a window, lets the mouse grab the cloth, and saves the drags made
// as the scene's `interactions:`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "drapelab/scene/scene_loader.hpp"
#include "live_session.hpp"
#include "view_window.hpp"

int main(int argc, char** argv) {
  // Named as it is typed: users run it as `drapelab view`, never by its own file name.
  CLI::App app{"Play a scene live: every solver side by side, grab the cloth with the mouse",
               "drapelab view"};
  std::string scene_file, size = "1280x720";
  std::vector<std::string> overrides;
  drapelab::viewer::ViewOptions options;
  app.add_option("scene", scene_file, "Scene file (YAML)")->required();
  app.add_option("--set", overrides, "Override a scene key: --set key.path=value (repeatable)");
  app.add_option("--size", size, "Window size WxH in pixels (default 1280x720)");
  app.add_option("--frames", options.frames, "Close after drawing this many frames")
      ->check(CLI::PositiveNumber);
  app.add_flag("--report", options.report, "Print the frame rate measured when the viewer closes");
  app.add_option("--script", options.script,
                 "Input events to play (lines 'at FRAME press X Y', 'move X Y', 'release', "
                 "'screenshot FILE', 'save FILE', 'quit'; docs/viewer.md)");
  app.add_option("--save-as", options.save_path,
                 "Where Save writes the scene with the recorded drags (default NAME_drags.yaml)");
  app.add_flag("--paused", options.start_paused, "Start paused");
  app.footer(
      "Mouse: left drag grabs the cloth, right drag orbits, middle drag pans, wheel zooms.\n"
      "Exit codes: 0 closed, 1 a screenshot or save failed, 2 bad input or no display.");
  CLI11_PARSE(app, argc, argv);
  int width = 0, height = 0;
  char x = 0;
  std::istringstream size_text(size);
  if (!(size_text >> width >> x >> height) || x != 'x' || width < 64 || height < 64 ||
      width > 8192 || height > 8192) {
    std::cerr << "error: --size must be WxH with each side in [64, 8192] pixels, got '" << size
              << "'\n";
    return 2;
  }
  options.width = width;
  options.height = height;
  const auto loaded = drapelab::scene::load_scene_file(scene_file, overrides);
  if (!loaded.ok()) {
    for (const auto& error : loaded.errors) std::cerr << "error: " << error << "\n";
    return 2;
  }
  if (options.save_path.empty()) options.save_path = loaded.scene->name + "_drags.yaml";
  drapelab::viewer::LiveSession session(*loaded.scene, loaded.model);
  return drapelab::viewer::run_view_window(session, options);
}
