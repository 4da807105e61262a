// Ctrl-C during a run: drapelab stops after the current step, exits with 130, and leaves every file
// complete (whole CSV rows, a summary.json that parses and says the run was interrupted).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "fixtures/cli.hpp"

namespace drapelab {
namespace {

using namespace fixtures;  // fixtures/cli.hpp

namespace fs = std::filesystem;

std::size_t count_lines(const fs::path& path) {
  if (path.empty() || !fs::exists(path)) return 0;
  const std::string text = read_text(path);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// The data rows of a CSV file after checking that it ends with a whole row and that every row has
// the header's number of cells.
std::vector<std::string> whole_rows(const fs::path& path) {
  const std::string text = read_text(path);
  EXPECT_FALSE(text.empty());
  if (text.empty()) return {};
  EXPECT_EQ(text.back(), '\n');  // whole rows only
  std::vector<std::string> rows = split_lines(text);
  const std::size_t columns = split_csv(rows.front()).size();
  rows.erase(rows.begin());
  for (const auto& row : rows) EXPECT_EQ(split_csv(row).size(), columns) << row;
  return rows;
}

class CliInterrupt : public TempDirTest {};

TEST_F(CliInterrupt, CtrlCLeavesCompleteFilesAndExits130) {
  const fs::path scene = dir() / "long.yaml";
  std::ofstream(scene)
      << "name: long_run\nduration: 600\nframe_rate: 60\n"
         "cloth: {resolution: [33, 33], mass: 0.25, plane: xy, pins: [top_corners],\n"
         "        springs: {stretch: {ks: 2000, kd: 0.02}, shear: {ks: 200, kd: 0.01},\n"
         "                  bend: {ks: 20, kd: 0.002}}}\n"
         "solvers: [{name: ours, dt: 0.000166666666666666667}]\n";
  const fs::path out = dir() / "run";
  // Interrupted once a few frames are on disk.
  const int exit_code =
      interrupt_drapelab_when({"run", scene.string(), "--out", out.string()},
                              [&] { return count_lines(staged_file(out, "metrics.csv")) >= 4; });
  EXPECT_EQ(exit_code, 130);
  const std::size_t frames = whole_rows(out / "metrics.csv").size();
  EXPECT_GE(frames, 3u);
  EXPECT_LT(frames, 36001u);

  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["run"]["state"], "interrupted");
  EXPECT_EQ(summary["solvers"]["ours"]["frames_recorded"].get<std::size_t>(), frames);
  EXPECT_EQ(summary["run"]["frames_done"].get<std::size_t>() + 1, frames);
}

// Ctrl-C during drapelab bench --repeat: the cells already measured stay in bench.csv as whole
// rows, and the program exits with 130. The second cell (65 x 65, Bullet's deformable cloth at tens
// of seconds per run) is still running when the signal comes.
TEST_F(CliInterrupt, CtrlCDuringABenchKeepsTheMeasuredRowsAndExits130) {
  const fs::path out = dir() / "bench";
  const std::string scene = std::string(DRAPELAB_SOURCE_DIR) + "/scenes/sphere_drape.yaml";
  // Interrupted once the first cell's six rows (five solvers and the reference) are on disk.
  const int exit_code = interrupt_drapelab_when(
      {"bench", "--sizes", "5,65", "--repeat", "2", "--duration", "1", "--scenes", scene, "--out",
       out.string()},
      [&] { return count_lines(out / "bench.csv") >= 7; }, std::chrono::seconds(120));
  EXPECT_EQ(exit_code, 130);
  std::size_t small_cell = 0;
  for (const auto& row : whole_rows(out / "bench.csv")) {
    const auto cells = split_csv(row);
    if (cells[0] != "sphere_drape" || cells[1] != "5") continue;
    ++small_cell;
    ASSERT_EQ(cells.size(), 21u) << row;
    EXPECT_EQ(cells[8], "ok") << row;
    EXPECT_EQ(cells[17], cells[4] == "reference" ? "1" : "2")
        << "two runs, the reference one: " << row;
  }
  EXPECT_EQ(small_cell, 6u);
  EXPECT_TRUE(fs::exists(out / "bench.md"));
}

}  // namespace
}  // namespace drapelab
