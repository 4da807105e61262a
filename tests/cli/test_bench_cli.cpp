// drapelab bench --quick as a smoke test: every scene and solver gets a row, plus the reference
// run's; our solver's ratio is 1, the others' ratios are their cost over ours; every row's rms
// distance to the reference is measured (0 for the reference itself) unless --no-reference;
// --repeat keeps the fastest run, and bad sizes and repeat counts are refused. Timings are never
// checked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "fixtures/cli.hpp"

namespace drapelab {
namespace {

using namespace fixtures;  // fixtures/cli.hpp

namespace fs = std::filesystem;

class BenchCli : public TempDirTest {};

// The index of the column `name` in bench.csv's header; throws (failing the test) when absent.
std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  const auto found = std::find(header.begin(), header.end(), name);
  if (found == header.end()) throw std::out_of_range("no column " + name + " in bench.csv");
  return static_cast<std::size_t>(found - header.begin());
}

TEST_F(BenchCli, QuickRunWritesARowPerSceneAndSolver) {
  const fs::path out = dir() / "bench";
  const fs::path source(DRAPELAB_SOURCE_DIR);
  const std::string scenes = (source / "scenes/curtain.yaml").string() + "," +
                             (source / "scenes/sphere_drape.yaml").string();
  const CommandResult result =
      run_drapelab({"bench", "--quick", "--scenes", scenes, "--out", out.string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto lines = split_lines(read_text(out / "bench.csv"));
  ASSERT_EQ(lines.size(), 1u + 2 * 6) << "a header, then 5 solvers and the reference per scene";
  const auto header = split_csv(lines[0]);
  const std::size_t scene_column = column(header, "scene"), solver = column(header, "solver"),
                    setting = column(header, "setting"), dt_column = column(header, "dt"),
                    status = column(header, "status"),
                    cost_column = column(header, "wall_seconds_per_simulated_second"),
                    ms_column = column(header, "ms_per_step"),
                    rms_column = column(header, "rms_to_reference"),
                    ratio_column = column(header, "cost_ratio_to_ours"),
                    second_half_column =
                        column(header, "second_half_wall_seconds_per_simulated_second"),
                    second_half_ratio_column = column(header, "second_half_cost_ratio_to_ours"),
                    runs = column(header, "runs");
  double ours_cost = 0.0, ours_second_half = 0.0;
  int references = 0;
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto cells = split_csv(lines[k]);
    ASSERT_EQ(cells.size(), header.size()) << lines[k];
    EXPECT_EQ(cells[1], "33");
    EXPECT_EQ(cells[status], "ok") << lines[k];
    const double cost = std::stod(cells[cost_column]), ratio = std::stod(cells[ratio_column]);
    const double second_half = std::stod(cells[second_half_column]),
                 second_half_ratio = std::stod(cells[second_half_ratio_column]);
    EXPECT_GT(cost, 0.0);
    EXPECT_GT(second_half, 0.0);
    // Every row ran to the end, and so did the reference: each has its distance to it.
    ASSERT_FALSE(cells[rms_column].empty()) << lines[k];
    const double rms = std::stod(cells[rms_column]);  // m
    EXPECT_TRUE(std::isfinite(rms)) << lines[k];
    EXPECT_GE(rms, 0.0) << lines[k];
    if (cells[solver] == "ours") {
      ours_cost = cost;
      ours_second_half = second_half;
      EXPECT_DOUBLE_EQ(ratio, 1.0);
      EXPECT_DOUBLE_EQ(second_half_ratio, 1.0);
      // Vertex block descent at its default step of 1/120 s, 10 sweeps.
      EXPECT_EQ(cells[setting], "\"vbd (10 sweeps)\"") << "quoted in the CSV";
      EXPECT_NEAR(std::stod(cells[dt_column]), 1.0 / 120.0, 1e-9);
      // Backward Euler falls g h t / 2 further than the fall's g t^2 / 2 (V1): 4.1 mm after 0.1 s
      // at h = 1/120 s, where the reference's quarter step adds a few micrometres. Measured 4.1e-3
      // m on the sphere drape, whose sheet is still falling.
      if (cells[scene_column] == "sphere_drape") {
        EXPECT_NEAR(rms, 9.81 * (1.0 / 120.0) * 0.1 / 2.0, 3e-4) << lines[k];
      }
    } else {
      if (cells[solver] == "ours_explicit") {
        // Adaptive substeps: dt and ms per step are the mean substep's, far below 1/120 s.
        EXPECT_NE(cells[setting].find("symplectic_euler (adaptive substeps)"), std::string::npos)
            << cells[setting];
        const double dt = std::stod(cells[dt_column]), ms_per_step = std::stod(cells[ms_column]);
        EXPECT_GT(dt, 0.0);
        EXPECT_LT(dt, 1.0 / 1200.0);
        EXPECT_NEAR(cost, 1e-3 * ms_per_step / dt, 1e-3 * cost)
            << "wall s per simulated s = step cost / step";
        // The same integrator at 0.9 of its shape's stable step against a quarter of the
        // network's stable step: after 0.1 s the sphere drape's falling sheet is 1.6e-4 m (rms)
        // from the reference, measured. The bound is the distance the sheet falls in those 0.1 s
        // (g t^2 / 2 = 0.049 m): a sheet that did not fall, or fell apart, is beyond it.
        if (cells[scene_column] == "sphere_drape") {
          EXPECT_LT(rms, 0.05) << lines[k];
        }
      }
      EXPECT_NEAR(ratio, cost / ours_cost, 1e-4 * ratio) << lines[k];
      EXPECT_NEAR(second_half_ratio, second_half / ours_second_half, 1e-4 * second_half_ratio)
          << lines[k];
    }
    if (cells[solver] == "reference") {
      ++references;
      EXPECT_EQ(cells[setting], "\"symplectic_euler at 1/4 stable step\"") << "quoted in the CSV";
      EXPECT_EQ(cells[runs], "1");
      EXPECT_EQ(rms, 0.0) << "the reference against itself";
      EXPECT_EQ(k % 6, 0u) << "the last row of its scene and size";
    }
  }
  EXPECT_EQ(references, 2);
  const std::string md = read_text(out / "bench.md");
  EXPECT_NE(md.find("| curtain | 33 x 33 | bullet_classic |"), std::string::npos);
  EXPECT_NE(md.find("| sphere_drape | 33 x 33 | mujoco | cg at its stable step |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| rms to reference (m) |"), std::string::npos);
  EXPECT_NE(md.find("| sphere_drape | 33 x 33 | reference | symplectic_euler at 1/4 stable step |"),
            std::string::npos)
      << md;
}

// --no-reference: no reference run, and the rms column stays empty.
TEST_F(BenchCli, NoReferenceLeavesTheAccuracyColumnEmpty) {
  const fs::path out = dir() / "bench";
  const fs::path source(DRAPELAB_SOURCE_DIR);
  const CommandResult result =
      run_drapelab({"bench", "--quick", "--no-reference", "--scenes",
                    (source / "scenes/curtain.yaml").string(), "--out", out.string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto lines = split_lines(read_text(out / "bench.csv"));
  ASSERT_EQ(lines.size(), 1u + 5) << "a header and the 5 solvers";
  const auto header = split_csv(lines[0]);
  const std::size_t solver = column(header, "solver"), rms = column(header, "rms_to_reference");
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto cells = split_csv(lines[k]);
    ASSERT_EQ(cells.size(), header.size()) << lines[k];
    EXPECT_NE(cells[solver], "reference");
    EXPECT_EQ(cells[rms], "") << lines[k];
  }
}

// --repeat: every solver runs that many times in each cell and the fastest run is the row; the
// reference runs once. Every solver here is deterministic, so the repeats agree on the physics and
// the bench warns of nothing.
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
  ASSERT_EQ(lines.size(), 1u + 6) << "a header, the 5 solvers and the reference";
  const auto header = split_csv(lines[0]);
  ASSERT_EQ(header.size(), 21u);
  const std::size_t solver = column(header, "solver"), runs = column(header, "runs"),
                    spread = column(header, "wall_spread"),
                    max_stretch = column(header, "max_stretch");
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto cells = split_csv(lines[k]);
    ASSERT_EQ(cells.size(), header.size()) << lines[k];
    // The reference runs once per scene and size, whatever --repeat says.
    EXPECT_EQ(cells[runs], cells[solver] == "reference" ? "1" : "2") << lines[k];
    EXPECT_GE(std::stod(cells[spread]), 1.0) << "the slowest run over the fastest: " << lines[k];
    EXPECT_GT(std::stod(cells[max_stretch]), 0.0)
        << "the curtain stretches under its weight: " << lines[k];
    // Every solver's frames are audited: the hanging curtain never crosses itself.
    EXPECT_EQ(cells[column(header, "self_intersections")], "0") << lines[k];
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
