// Ctrl-C during a run: drapelab stops after the current step, exits with 130, and leaves every file
// complete (whole CSV rows, a summary.json that parses and says the run was interrupted).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::size_t count_lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(CliInterrupt, CtrlCLeavesCompleteFilesAndExits130) {
  const fs::path folder = fs::temp_directory_path() / ("drapelab_interrupt_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  const fs::path scene = folder / "long.yaml";
  std::ofstream(scene) << "name: long_run\nduration: 600\nframe_rate: 60\n"
                          "cloth: {resolution: [33, 33], mass: 0.25, plane: xy, pins: [top_corners],\n"
                          "        springs: {stretch: {ks: 2000, kd: 0.02}, shear: {ks: 200, kd: 0.01},\n"
                          "                  bend: {ks: 20, kd: 0.002}}}\n"
                          "solvers: [{name: ours, dt: 0.000166666666666666667}]\n";
  const fs::path out = folder / "run";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(DRAPELAB_EXE, DRAPELAB_EXE, "run", scene.c_str(), "--out", out.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Wait until a few frames are on disk, then interrupt.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline &&
         count_lines(read_text(out / "metrics.csv")) < 4)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_EQ(::kill(child, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);

  const std::string metrics = read_text(out / "metrics.csv");
  ASSERT_FALSE(metrics.empty());
  EXPECT_EQ(metrics.back(), '\n');  // whole rows only
  std::istringstream rows(metrics);
  std::string header, row;
  std::getline(rows, header);
  const auto columns = std::count(header.begin(), header.end(), ',');
  std::size_t frames = 0;
  while (std::getline(rows, row)) {
    EXPECT_EQ(std::count(row.begin(), row.end(), ','), columns) << row;
    ++frames;
  }
  EXPECT_GE(frames, 3u);
  EXPECT_LT(frames, 36001u);

  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["run"]["state"], "interrupted");
  EXPECT_EQ(summary["solvers"]["ours"]["frames_recorded"].get<std::size_t>(), frames);
  EXPECT_EQ(summary["run"]["frames_done"].get<std::size_t>() + 1, frames);
  fs::remove_all(folder);
}

// Ctrl-C during drapelab bench --repeat: the cells already measured stay in bench.csv as whole rows,
// and the program exits with 130. The second cell (65 x 65, Bullet's deformable cloth at tens of
// seconds per run) is still running when the signal comes.
TEST(CliInterrupt, CtrlCDuringABenchKeepsTheMeasuredRowsAndExits130) {
  const fs::path folder = fs::temp_directory_path() / ("drapelab_bench_interrupt_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  const fs::path out = folder / "bench";
  const std::string scene = std::string(DRAPELAB_SOURCE_DIR) + "/scenes/sphere_drape.yaml";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(DRAPELAB_EXE, DRAPELAB_EXE, "bench", "--sizes", "5,65", "--repeat", "2", "--duration", "1",
            "--scenes", scene.c_str(), "--out", out.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Wait until the first cell's three rows are on disk, then interrupt.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline && count_lines(read_text(out / "bench.csv")) < 4)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_EQ(::kill(child, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);

  const std::string csv = read_text(out / "bench.csv");
  ASSERT_FALSE(csv.empty());
  EXPECT_EQ(csv.back(), '\n');  // whole rows only
  std::istringstream rows(csv);
  std::string header, row;
  std::getline(rows, header);
  const auto columns = std::count(header.begin(), header.end(), ',');
  std::size_t small_cell = 0;
  while (std::getline(rows, row)) {
    EXPECT_EQ(std::count(row.begin(), row.end(), ','), columns) << row;
    if (row.rfind("sphere_drape,5,", 0) == 0) {
      ++small_cell;
      std::vector<std::string> cells;  // no cell of these rows holds a comma
      std::istringstream fields(row);
      for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
      ASSERT_EQ(cells.size(), 18u) << row;
      EXPECT_EQ(cells[8], "ok") << row;
      EXPECT_EQ(cells[16], "2") << "two runs: " << row;
    }
  }
  EXPECT_EQ(small_cell, 3u);
  EXPECT_TRUE(fs::exists(out / "bench.md"));
  fs::remove_all(folder);
}

}  // namespace
