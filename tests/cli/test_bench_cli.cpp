// drapelab bench --quick as a smoke test: every scene and solver gets a row, our solver's ratio is
// 1, the others' ratios are their cost over ours, --repeat keeps the fastest run, and bad sizes and
// repeat counts are refused. Timings are never checked.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "fixtures/cli.hpp"

namespace drapelab {
namespace {

using namespace fixtures;  // fixtures/cli.hpp

namespace fs = std::filesystem;

class BenchCli : public TempDirTest {};

TEST_F(BenchCli, QuickRunWritesARowPerSceneAndSolver) {
  const fs::path out = dir() / "bench";
  const fs::path source(DRAPELAB_SOURCE_DIR);
  const std::string scenes = (source / "scenes/curtain.yaml").string() + "," +
                             (source / "scenes/sphere_drape.yaml").string();
  const CommandResult result =
      run_drapelab({"bench", "--quick", "--scenes", scenes, "--out", out.string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto lines = split_lines(read_text(out / "bench.csv"));
  ASSERT_EQ(lines.size(), 1u + 2 * 3) << "a header and 3 solvers for each of 2 scenes";
  const auto header = split_csv(lines[0]);
  ASSERT_EQ(header[13], "cost_ratio_to_ours");
  ASSERT_EQ(header[14], "second_half_wall_seconds_per_simulated_second");
  ASSERT_EQ(header[15], "second_half_cost_ratio_to_ours");
  double ours_cost = 0.0, ours_second_half = 0.0;
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto cells = split_csv(lines[k]);
    ASSERT_EQ(cells.size(), header.size()) << lines[k];
    EXPECT_EQ(cells[1], "33");
    EXPECT_EQ(cells[8], "ok") << lines[k];
    const double cost = std::stod(cells[9]), ratio = std::stod(cells[13]);
    const double second_half = std::stod(cells[14]), second_half_ratio = std::stod(cells[15]);
    EXPECT_GT(cost, 0.0);
    EXPECT_GT(second_half, 0.0);
    if (cells[4] == "ours") {
      ours_cost = cost;
      ours_second_half = second_half;
      EXPECT_DOUBLE_EQ(ratio, 1.0);
      EXPECT_DOUBLE_EQ(second_half_ratio, 1.0);
      // Adaptive substeps: dt and ms per step are the mean substep's, far below the 1/120 s step.
      EXPECT_NE(cells[6].find("symplectic_euler (adaptive substeps)"), std::string::npos)
          << cells[6];
      const double dt = std::stod(cells[7]), ms_per_step = std::stod(cells[10]);
      EXPECT_GT(dt, 0.0);
      EXPECT_LT(dt, 1.0 / 1200.0);
      EXPECT_NEAR(cost, 1e-3 * ms_per_step / dt, 1e-3 * cost)
          << "wall s per simulated s = step cost / step";
    } else {
      EXPECT_NEAR(ratio, cost / ours_cost, 1e-4 * ratio) << lines[k];
      EXPECT_NEAR(second_half_ratio, second_half / ours_second_half, 1e-4 * second_half_ratio)
          << lines[k];
    }
  }
  EXPECT_NE(read_text(out / "bench.md").find("| curtain | 33 x 33 | bullet_classic |"),
            std::string::npos);
}

// --repeat: every solver runs that many times in each cell and the fastest run is the row. Every
// solver here is deterministic, so the repeats agree on the physics and the bench warns of nothing.
TEST_F(BenchCli, RepeatReportsTheFastestOfTheRunsAndTheirSpread) {
  const fs::path out = dir() / "bench";
  const fs::path source(DRAPELAB_SOURCE_DIR);
  const CommandResult result =
      run_drapelab({"bench", "--quick", "--repeat", "2", "--scenes",
                    (source / "scenes/curtain.yaml").string(), "--out", out.string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(result.output.find("warning:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("fastest of 2 runs"), std::string::npos) << result.output;
  const auto lines = split_lines(read_text(out / "bench.csv"));
  ASSERT_EQ(lines.size(), 1u + 3);
  const auto header = split_csv(lines[0]);
  ASSERT_EQ(header.size(), 18u);
  ASSERT_EQ(header[16], "runs");
  ASSERT_EQ(header[17], "wall_spread");
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto cells = split_csv(lines[k]);
    ASSERT_EQ(cells.size(), header.size()) << lines[k];
    EXPECT_EQ(cells[16], "2") << lines[k];
    EXPECT_GE(std::stod(cells[17]), 1.0) << "the slowest run over the fastest: " << lines[k];
    EXPECT_GT(std::stod(cells[11]), 0.0) << "the curtain stretches under its weight: " << lines[k];
  }
}

TEST_F(BenchCli, BadRepeatIsRefused) {
  const CommandResult result =
      run_drapelab({"bench", "--quick", "--repeat", "0", "--out", (dir() / "b").string()});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("--repeat: 0 runs is outside 1..100"), std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(dir() / "b" / "bench.csv")) << "nothing written for bad arguments";
}

TEST_F(BenchCli, BadSizeIsRefused) {
  const CommandResult result =
      run_drapelab({"bench", "--sizes", "1", "--out", (dir() / "b").string()});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("--sizes: 1 particles per side is outside 2..2000"),
            std::string::npos)
      << result.output;
}

}  // namespace
}  // namespace drapelab
