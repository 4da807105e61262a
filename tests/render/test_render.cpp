// `drapelab render` end to end: a tiny scene (a 9 x 9 cloth falling onto a sphere for 0.2 s, ours
// and Bullet's classic cloth) is run once with point caches, then rendered at 320 x 240. The PNG
// files are read back with libpng here and checked: their size, that the flat first frame differs
// from the draped last one, and that the cloth's pixels lie where the projection of its particles
// (read from the point cache here, projected with a pinhole written here) says. Also: a run without
// point caches is refused, the video is encoded by whatever `ffmpeg` is on PATH, with the right
// arguments, and without one the verb says how to get it.
#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "fixtures/cli.hpp"

namespace {

namespace fs = std::filesystem;
using drapelab::fixtures::read_text;
using drapelab::fixtures::run_drapelab;
using drapelab::fixtures::write_text;

// The cloth starts 5 cm above the ball: it lands at t = 0.1 s and drapes for the last 0.1 s. Seven
// frames at 30 frames per second (0 to 6).
const std::string kScene =
    "name: render_drape\n"
    "duration: 0.2\n"
    "frame_rate: 30\n"
    "cloth:\n"
    "  shape: grid\n"
    "  size: [0.6, 0.6]\n"
    "  resolution: [9, 9]\n"
    "  plane: xz\n"
    "  center: [0, 0.75, 0]\n"
    "  mass: 0.1\n"
    "  springs:\n"
    "    stretch: {ks: 500, kd: 0.01}\n"
    "    shear: {ks: 50, kd: 0.005}\n"
    "    bend: {ks: 2, kd: 0.001}\n"
    "colliders:\n"
    "  - {name: ball, type: sphere, center: [0, 0.5, 0], radius: 0.2}\n"
    "  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 1, 0]}\n"
    "contact: {stiffness: 1000, damping: 0.2}\n"
    "solvers:\n"
    "  - {name: ours, type: spring_damper, integrator: symplectic_euler}\n"
    "  - {name: classic, type: bullet_softbody}\n";
constexpr int kFrames = 7;
constexpr int kParticles = 81;
constexpr int kWidth = 320, kHeight = 240, kPanels = 2;

// A camera seen steeply from the front, so nothing hides the cloth lying on the ball, and the cloth
// stays in the middle of the panel, clear of the legends at the top and bottom.
const Eigen::Vector3d kEye(0.0, 2.4, 0.6), kTarget(0.0, 0.65, 0.0);
constexpr double kFovDegrees = 40.0;
const std::string kCamera = "eye=0,2.4,0.6; target=0,0.65,0; fov=40";

struct Rgba {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // RGBA, top row first
  const std::uint8_t* at(int x, int y) const {
    return pixels.data() + (std::size_t(y) * width + x) * 4;
  }
};

Rgba read_png(const fs::path& path) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    throw std::runtime_error("cannot read " + path.string());
  png.format = PNG_FORMAT_RGBA;
  Rgba image;
  image.width = static_cast<int>(png.width);
  image.height = static_cast<int>(png.height);
  image.pixels.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.pixels.data(), 0, nullptr))
    throw std::runtime_error("cannot decode " + path.string());
  return image;
}

void write_flat_png(const fs::path& path, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  std::vector<std::uint8_t> pixels;
  for (int k = 0; k < 16 * 16; ++k) pixels.insert(pixels.end(), {r, g, b});
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = png.height = 16;
  png.format = PNG_FORMAT_RGB;
  ASSERT_TRUE(png_image_write_to_file(&png, path.c_str(), 0, pixels.data(), 16 * 3, nullptr));
}

// Frame `frame` of a PC2 point cache: header of 32 bytes, then frames of points x 3 float32.
Eigen::Matrix3Xd read_pc2_frame(const fs::path& path, int frame) {
  const std::string bytes = read_text(path);
  std::int32_t points = 0, samples = 0;
  std::memcpy(&points, bytes.data() + 16, 4);
  std::memcpy(&samples, bytes.data() + 28, 4);
  EXPECT_EQ(points, kParticles);
  EXPECT_GT(samples, frame);
  Eigen::Matrix3Xd x(3, points);
  for (int i = 0; i < points; ++i)
    for (int c = 0; c < 3; ++c) {
      float value = 0;
      std::memcpy(&value, bytes.data() + 32 + (std::size_t(frame) * points * 3 + i * 3 + c) * 4, 4);
      x(c, i) = value;
    }
  return x;
}

// A pinhole camera (vertical fov, y up) mapping a world point to pixel coordinates of a panel
// width x height (x right, y down), written here independently of the renderer's matrices.
Eigen::Vector2d project(const Eigen::Vector3d& p, int width, int height) {
  const Eigen::Vector3d forward = (kTarget - kEye).normalized();
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitY()).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  const Eigen::Vector3d d = p - kEye;
  const double half_height = std::tan(kFovDegrees / 2 * std::numbers::pi / 180.0) * d.dot(forward);
  const double half_width = half_height * width / height;
  return {0.5 * width * (1.0 + d.dot(right) / half_width),
          0.5 * height * (1.0 - d.dot(up) / half_height)};
}

struct Box {
  double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
  int count = 0;
  void add(double x, double y) {
    x0 = std::min(x0, x);
    y0 = std::min(y0, y);
    x1 = std::max(x1, x);
    y1 = std::max(y1, y);
    ++count;
  }
};

// Pixels of a flat green cloth, lit or in shade: green clearly above red and blue. Nothing else in
// the picture is green (grey floor, blue-grey ball and background, white legends).
bool is_cloth(const std::uint8_t* p) { return p[1] > 40 && p[1] > 1.6 * p[0] && p[1] > 1.6 * p[2]; }

class RenderCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ =
        new fs::path(fs::temp_directory_path() / ("drapelab_render_" + std::to_string(::getpid())));
    fs::remove_all(*root_);
    fs::create_directories(*root_);
    write_text(*root_ / "scene.yaml", kScene);
    run_result_ = new drapelab::fixtures::CommandResult(
        run_drapelab({"run", (*root_ / "scene.yaml").string(), "--out", run_dir().string(),
                      "--meshes", "pc2", "-q"}));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
    delete run_result_;
  }
  void SetUp() override {
    ASSERT_EQ(run_result_->exit_code, 0) << run_result_->output;
    saved_path_ = std::getenv("PATH") ? std::getenv("PATH") : "";
  }
  void TearDown() override { ::setenv("PATH", saved_path_.c_str(), 1); }

  static fs::path run_dir() { return *root_ / "run"; }
  static fs::path root() { return *root_; }
  // An empty folder as the whole PATH: no ffmpeg (the harness starts drapelab by its full path).
  void without_ffmpeg() {
    fs::create_directories(root() / "empty_bin");
    ::setenv("PATH", (root() / "empty_bin").c_str(), 1);
  }

 private:
  static inline fs::path* root_ = nullptr;
  static inline drapelab::fixtures::CommandResult* run_result_ = nullptr;
  std::string saved_path_;
};

TEST_F(RenderCli, WritesOneImageOfTheRequestedSizePerFrame) {
  without_ffmpeg();
  const fs::path out = root() / "frames";
  const auto result =
      run_drapelab({"render", run_dir().string(), "--out", out.string(), "--size", "320x240"});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (int frame = 0; frame < kFrames; ++frame) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", frame);
    ASSERT_TRUE(fs::exists(out / name)) << name << "\n" << result.output;
    const Rgba image = read_png(out / name);
    EXPECT_EQ(image.width, kWidth);
    EXPECT_EQ(image.height, kHeight);
  }
  EXPECT_FALSE(fs::exists(out / "frame_0007.png"));
  // No ffmpeg: no video, and one line saying how to make one.
  EXPECT_FALSE(fs::exists(out / "video.mp4"));
  EXPECT_NE(result.output.find("apt-get install ffmpeg"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("ffmpeg -nostdin -y"), std::string::npos) << result.output;
}

TEST_F(RenderCli, DefaultFolderIsInsideTheRunAndEveryNthFrame) {
  without_ffmpeg();
  const auto result =
      run_drapelab({"render", run_dir().string(), "--size", "200x100", "--every", "3"});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(run_dir() / "render"))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names,
            (std::vector<std::string>{"frame_0000.png", "frame_0003.png", "frame_0006.png"}));
  // A second render into the same folder replaces the first one's frames.
  ASSERT_EQ(
      run_drapelab({"render", run_dir().string(), "--size", "200x100", "--every", "4"}).exit_code,
      0);
  names.clear();
  for (const auto& entry : fs::directory_iterator(run_dir() / "render"))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"frame_0000.png", "frame_0004.png"}));
  fs::remove_all(run_dir() / "render");
}

TEST_F(RenderCli, ClothPixelsAreWhereTheParticlesProject) {
  without_ffmpeg();
  write_flat_png(root() / "green.png", 0, 255, 0);
  const fs::path out = root() / "green";
  const auto result =
      run_drapelab({"render", run_dir().string(), "--out", out.string(), "--size", "320x240",
                    "--camera", kCamera, "--texture", (root() / "green.png").string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const int panel_width = kWidth / kPanels;
  const std::vector<std::string> solvers{"ours", "classic"};  // summary.json's order, left to right
  for (const int frame : {0, kFrames - 1}) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", frame);
    const Rgba image = read_png(out / name);
    for (int panel = 0; panel < kPanels; ++panel) {
      SCOPED_TRACE(solvers[panel] + " at frame " + std::to_string(frame));
      Box rendered, projected;
      for (int y = 0; y < kHeight; ++y)
        for (int x = panel * panel_width; x < (panel + 1) * panel_width; ++x)
          if (is_cloth(image.at(x, y))) rendered.add(x - panel * panel_width, y);
      const Eigen::Matrix3Xd particles =
          read_pc2_frame(run_dir() / "meshes" / (solvers[panel] + ".pc2"), frame);
      for (int i = 0; i < particles.cols(); ++i) {
        const Eigen::Vector2d p = project(particles.col(i), panel_width, kHeight);
        projected.add(p.x(), p.y());
      }
      ASSERT_GT(rendered.count, 500) << "too few cloth pixels";
      // Pixel x covers [x, x + 1): the box of covered pixels spans [x0, x1 + 1). Within a pixel:
      // the antialiased border is partly background (a 1 degree error in the field of view moves
      // the edges by 2 pixels here).
      constexpr double kTolerance = 1.0;
      EXPECT_NEAR(rendered.x0, projected.x0, kTolerance);
      EXPECT_NEAR(rendered.x1 + 1, projected.x1, kTolerance);
      EXPECT_NEAR(rendered.y0, projected.y0, kTolerance);
      EXPECT_NEAR(rendered.y1 + 1, projected.y1, kTolerance);
    }
  }
}

TEST_F(RenderCli, FlatAndDrapedFramesDiffer) {
  without_ffmpeg();
  const fs::path out = root() / "compare";
  ASSERT_EQ(run_drapelab({"render", run_dir().string(), "--out", out.string(), "--size", "320x240"})
                .exit_code,
            0);
  const Rgba flat = read_png(out / "frame_0000.png");
  const Rgba draped = read_png(out / "frame_0006.png");
  const Rgba almost_flat = read_png(out / "frame_0001.png");
  auto changed_pixels = [](const Rgba& a, const Rgba& b) {
    int count = 0;
    for (std::size_t k = 0; k < a.pixels.size(); k += 4) {
      int difference = 0;
      for (int c = 0; c < 3; ++c)
        difference = std::max(difference, std::abs(a.pixels[k + c] - b.pixels[k + c]));
      count += difference > 40;
    }
    return count;
  };
  // The cloth has fallen onto the ball and its sides hang down: thousands of pixels change, far
  // more than between the first two frames, where it has fallen 5 mm in free flight.
  const int draped_change = changed_pixels(flat, draped);
  EXPECT_GT(draped_change, kWidth * kHeight / 50);
  EXPECT_GT(draped_change, 4 * changed_pixels(flat, almost_flat));
}

TEST_F(RenderCli, VideoIsEncodedByTheFfmpegOnPath) {
  // A stand-in ffmpeg that records its arguments and writes the output file it was given last.
  const fs::path bin = root() / "fake_bin";
  fs::create_directories(bin);
  write_text(bin / "ffmpeg", "#!/bin/sh\nprintf '%s\\n' \"$@\" > \"" +
                                 (root() / "ffmpeg_arguments.txt").string() +
                                 "\"\nfor last; do :; done\necho video > \"$last\"\n");
  fs::permissions(bin / "ffmpeg", fs::perms::owner_all);
  ::setenv("PATH", (bin.string() + ":/usr/bin:/bin").c_str(), 1);
  const fs::path out = root() / "video";
  const auto result = run_drapelab(
      {"render", run_dir().string(), "--out", out.string(), "--size", "64x32", "--every", "2"});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  ASSERT_TRUE(fs::exists(out / "video.mp4")) << result.output;
  const std::string arguments = read_text(root() / "ffmpeg_arguments.txt");
  // Every second frame of a 30 frames/s run plays at 15 frames/s.
  EXPECT_NE(arguments.find("-framerate\n15\n"), std::string::npos) << arguments;
  EXPECT_NE(arguments.find("-i\n" + (out / "frame_*.png").string() + "\n"), std::string::npos)
      << arguments;
  EXPECT_NE(arguments.find("-c:v\nlibx264\n"), std::string::npos) << arguments;
  EXPECT_NE(arguments.find("-pix_fmt\nyuv420p\n"), std::string::npos) << arguments;

  // An ffmpeg that fails: exit code 1, the frames stay.
  write_text(bin / "ffmpeg", "#!/bin/sh\nexit 3\n");
  const auto failed =
      run_drapelab({"render", run_dir().string(), "--out", out.string(), "--size", "64x32"});
  EXPECT_EQ(failed.exit_code, 1) << failed.output;
  EXPECT_NE(failed.output.find("ffmpeg failed (exit status 3)"), std::string::npos)
      << failed.output;
  EXPECT_TRUE(fs::exists(out / "frame_0006.png"));
}

TEST_F(RenderCli, RunWithoutPointCachesIsRefused) {
  const fs::path bare = root() / "bare";
  ASSERT_EQ(run_drapelab({"run", (root() / "scene.yaml").string(), "--out", bare.string(), "-q",
                          "--set", "duration=0.0333333333333333333"})
                .exit_code,
            0);
  const auto result = run_drapelab({"render", bare.string()});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("--meshes pc2"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(bare / "render"));
}

TEST_F(RenderCli, BadArgumentsAreBadInput) {
  for (const std::vector<std::string>& extra : {std::vector<std::string>{"--size", "320"},
                                                {"--size", "8x8"},
                                                {"--camera", "eye=1,2"},
                                                {"--camera", "fov=200"},
                                                {"--camera", "zoom=2"},
                                                {"--every", "0"},
                                                {"--texture", (root() / "missing.png").string()}}) {
    std::vector<std::string> arguments{"render", run_dir().string(), "--out",
                                       (root() / "bad").string()};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    const auto result = run_drapelab(arguments);
    EXPECT_EQ(result.exit_code, 2) << extra[0] << " " << extra[1] << "\n" << result.output;
  }
  EXPECT_EQ(run_drapelab({"render", (root() / "no_such_run").string()}).exit_code, 2);
}

}  // namespace

namespace {

// A copy of the test's run folder, for tests that damage it.
fs::path copy_of_run(const fs::path& root, const std::string& name) {
  const fs::path copy = root / name;
  fs::remove_all(copy);
  fs::copy(root / "run", copy, fs::copy_options::recursive);
  fs::remove_all(copy / "render");
  return copy;
}

TEST_F(RenderCli, APointCacheCutShortIsRefusedNamingTheFrames) {
  const fs::path run = copy_of_run(root(), "cut_pc2");
  const fs::path cache = run / "meshes" / "ours.pc2";
  // Cut the file in the middle of its last frames: the header still counts every frame.
  fs::resize_file(cache, fs::file_size(cache) - 1000);
  const auto result = run_drapelab({"render", run.string(), "--size", "64x64"});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("ours.pc2 is cut short"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("whole frames"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(run / "render" / "frame_0000.png"));
}

TEST_F(RenderCli, APointCacheWithFewerFramesThanTheRunRecordedIsRefused) {
  const fs::path run = copy_of_run(root(), "short_pc2");
  const fs::path cache = run / "meshes" / "ours.pc2";
  // Drop the last two frames and make the header agree: summary.json still counts them.
  const auto bytes = fs::file_size(cache);
  const int points = 9 * 9;
  fs::resize_file(cache, bytes - 2 * 12 * points);
  std::fstream file(cache, std::ios::binary | std::ios::in | std::ios::out);
  const std::int32_t samples =
      static_cast<std::int32_t>((bytes - 2 * 12 * points - 32) / (12 * points));
  file.seekp(28);  // the sample count, after the signature, version, points, start and rate
  file.write(reinterpret_cast<const char*>(&samples), 4);
  file.close();
  const auto result = run_drapelab({"render", run.string(), "--size", "64x64"});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("holds " + std::to_string(samples) + " frames"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("recorded " + std::to_string(samples + 2)), std::string::npos)
      << result.output;
}

TEST_F(RenderCli, AKilledRunIsDrawnAndSaidIncomplete) {
  const fs::path run = copy_of_run(root(), "killed");
  std::string summary = read_text(run / "summary.json");
  summary.replace(summary.find("\"finished\""), 10, "\"running\"");
  drapelab::fixtures::write_text(run / "summary.json", summary);
  without_ffmpeg();
  const auto result = run_drapelab({"render", run.string(), "--size", "64x64", "--every", "4"});
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("the run is incomplete"), std::string::npos) << result.output;
  EXPECT_TRUE(fs::exists(run / "render" / "frame_0000.png"));
}

TEST_F(RenderCli, SizesAboveTheBoundAreRefusedBeforeAnyAllocation) {
  const auto result = run_drapelab({"render", run_dir().string(), "--size", "16384x16384"});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("8192"), std::string::npos) << result.output;
}

}  // namespace
