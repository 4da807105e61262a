// drapelab view in a window: under Xvfb (a virtual X server the test starts), a scripted mouse drag
// grabs the cloth and moves it (the screenshots before and after differ where the cloth is), the
// drag is saved as the scene's interactions, and the viewer exits 0. Without a display it exits 2
// naming DISPLAY and the offline way.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "drapelab/render/png_io.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "fixtures/cli.hpp"

namespace drapelab {
namespace {

namespace fs = std::filesystem;
using fixtures::run_drapelab;

// A virtual X server on a free display number, for the life of the object.
class Xvfb {
 public:
  Xvfb() {
    int pipe_fds[2];
    if (::pipe(pipe_fds) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::close(pipe_fds[0]);
      const std::string fd = std::to_string(pipe_fds[1]);
      ::execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1280x720x24", "-nolisten",
               "tcp", static_cast<char*>(nullptr));
      ::_exit(127);  // not installed
    }
    ::close(pipe_fds[1]);
    // Xvfb writes "N\n" once it listens, possibly in more than one write: read up to the newline.
    std::string number;
    char c = 0;
    while (::read(pipe_fds[0], &c, 1) == 1 && c != '\n') number += c;
    ::close(pipe_fds[0]);
    if (!number.empty()) display_ = ":" + number;
  }
  ~Xvfb() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  const std::string& display() const { return display_; }  // empty: Xvfb did not start

 private:
  pid_t pid_ = -1;
  std::string display_;
};

// The fraction of pixels of the rectangle [x0, x1) x [y0, y1) that differ between two images.
double changed_fraction(const render::Image& a, const render::Image& b, int x0, int x1, int y0,
                        int y1) {
  int changed = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t* p = a.at(x, y);
      const std::uint8_t* q = b.at(x, y);
      int d = 0;
      for (int c = 0; c < 3; ++c) d += std::abs(int(p[c]) - int(q[c]));
      if (d > 30) ++changed;
    }
  return double(changed) / ((x1 - x0) * (y1 - y0));
}

class ViewWindow : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("drapelab_view_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(ViewWindow, AScriptedDragMovesTheClothAndIsSaved) {
  const Xvfb server;
  ASSERT_FALSE(server.display().empty())
      << "Xvfb did not start: install it (bash tools/install-deps.sh installs xvfb)";
  ::setenv("DISPLAY", server.display().c_str(), 1);
  // The curtain, small, with our cloth: the default view centres it, so the window's centre is on
  // the cloth. Press there, pull up and to the left over 30 frames, screenshot, let go, save.
  const fs::path script = dir_ / "drag.script";
  const fs::path before = dir_ / "before.png", after = dir_ / "after.png";
  const fs::path saved = dir_ / "saved.yaml";
  std::ofstream(script) << "at 3 screenshot " << before.string() << "\n"
                        << "at 5 press 530 300\n"
                        << "at 6 move 520 250\n"
                        << "at 20 move 450 150\n"
                        << "at 40 screenshot " << after.string() << "\n"
                        << "at 41 release\n"
                        << "at 42 save " << saved.string() << "\n";
  const auto result = run_drapelab(
      {"view", (fs::path(DRAPELAB_SOURCE_DIR) / "scenes" / "curtain.yaml").string(), "--set",
       "cloth.resolution=[17, 17]", "--set", "solvers.0.dt=0.0005555555555555556", "--size",
       "800x600", "--frames", "45", "--script", script.string(), "--report"});
  ::unsetenv("DISPLAY");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("frames per second"), std::string::npos) << result.output;
  const render::Image a = render::read_png_rgba(before), b = render::read_png_rgba(after);
  ASSERT_EQ(a.width, 800);
  // Where the cloth hangs (the panel right of the controls): it moved.
  EXPECT_GT(changed_fraction(a, b, 300, 780, 50, 550), 0.05);
  const auto loaded = scene::load_scene_file(saved, {});
  ASSERT_TRUE(loaded.ok()) << (loaded.errors.empty() ? "" : loaded.errors.front());
  ASSERT_EQ(loaded.scene->interactions.size(), 1u);
  const scene::DragSpec& drag = loaded.scene->interactions.front();
  EXPECT_FALSE(loaded.model->is_pinned(drag.particle));
  ASSERT_GE(drag.keyframes.size(), 30u);  // one per frame held
  // The target followed the cursor up (the window's y grows down, the world's y up).
  EXPECT_GT(drag.keyframes.back().target.y(), drag.keyframes.front().target.y() + 0.1);
}

TEST_F(ViewWindow, WithoutADisplayItSaysSoAndExits2) {
  ::unsetenv("DISPLAY");
  const auto result =
      run_drapelab({"view", (fs::path(DRAPELAB_SOURCE_DIR) / "scenes" / "curtain.yaml").string()});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("DISPLAY"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("drapelab render"), std::string::npos) << result.output;
}

TEST_F(ViewWindow, ABadScriptLineIsNamed) {
  const fs::path script = dir_ / "bad.script";
  std::ofstream(script) << "at 3 press 10\n";
  const auto result =
      run_drapelab({"view", (fs::path(DRAPELAB_SOURCE_DIR) / "scenes" / "curtain.yaml").string(),
                    "--script", script.string()});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("bad.script:1: press needs the pixel X Y"), std::string::npos)
      << result.output;
}

}  // namespace
}  // namespace drapelab
