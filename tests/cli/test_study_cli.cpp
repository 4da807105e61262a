// `drapelab stability` and `drapelab study` end to end on tiny scenes written by the tests (the
// step search alone: test_step_search.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "fixtures/cli.hpp"

namespace {

namespace fs = std::filesystem;
using drapelab::fixtures::read_text;
using drapelab::fixtures::run_drapelab;
using drapelab::fixtures::split_csv;
using drapelab::fixtures::split_lines;
using drapelab::fixtures::write_text;

// One undamped spring: a 1 x 2 chain, the top particle pinned, the lower one (m = 0.01 kg) hanging
// on a stretch spring of ks = 9000 N/m under gravity. Its only mode has omega = sqrt(ks / m) =
// 948.7 rad/s, and symplectic Euler is stable exactly while omega h < 2, h < 2.108e-3 s. With a
// frame period of 0.1 s the steps are 0.1 / k: k = 48 (2.083e-3 s) is the largest stable step, k =
// 47 (2.128e-3 s) the smallest unstable one, 2 % apart. Gravity starts the oscillation (amplitude m
// g / ks = 1.1e-5 m, a stretch of 1e-4): just above the limit it grows by about 30 % per step, far
// past a stretch of 1 within the 0.2 s (two frames) of a trial; just below it stays bounded.
constexpr double kSpringKs = 9000.0;    // N/m
constexpr double kParticleMass = 0.01;  // kg, the free particle's (the total is split equally)
const std::string kOneSpring =
    "name: one_spring\n"
    "duration: 0.2\n"
    "frame_rate: 10\n"
    "cloth:\n"
    "  size: [0.1, 0.1]\n"
    "  resolution: [1, 2]\n"
    "  plane: xy\n"
    "  center: [0, 1, 0]\n"
    "  mass: 0.02\n"
    "  springs:\n"
    "    stretch: {ks: 9000, kd: 0}\n"
    "    shear: {ks: 0, kd: 0}\n"
    "    bend: {ks: 0, kd: 0}\n"
    "  pins: [top_corners]\n"
    "solvers:\n"
    "  - {name: ours, type: spring_damper, integrator: symplectic_euler, dt: 0.001, host: none}\n";

// A 5 x 5 sheet pinned at its corners, 0.2 s at 60 frames/s (12 frames), 64 steps per frame. Its
// springs are damped enough (kd / ks = 1e-3 s, four times the step) for explicit Euler to be stable
// at the base step; at 64 times the step (one step per frame) every explicit scheme blows up.
const std::string kSheet =
    "name: small_sheet\n"
    "duration: 0.2\n"
    "frame_rate: 60\n"
    "seed: 3\n"
    "cloth:\n"
    "  size: [0.2, 0.2]\n"
    "  resolution: [5, 5]\n"
    "  mass: 0.05\n"
    "  perturbation: 0.001\n"
    "  springs:\n"
    "    stretch: {ks: 100, kd: 0.1}\n"
    "    shear: {ks: 10, kd: 0.01}\n"
    "    bend: {ks: 1, kd: 0.001}\n"
    "  pins: [corners]\n"
    "solvers:\n"
    "  - {name: ours, type: spring_damper, dt: 0.00026041666666666666, host: none}\n";

class StudyCli : public drapelab::fixtures::TempDirTest {
 protected:
  fs::path scene(const std::string& name, const std::string& text) {
    const fs::path path = dir() / name;
    write_text(path, text);
    return path;
  }
};

TEST_F(StudyCli, StabilityOfOneUndampedSpringIsTwoOverOmega) {
  const fs::path file = scene("spring.yaml", kOneSpring);
  const fs::path json_file = dir() / "stability.json";
  const auto result =
      run_drapelab({"stability", file.string(), "--tolerance", "0", "--json", json_file.string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("largest stable dt: "), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("smallest unstable: "), std::string::npos) << result.output;

  const auto j = nlohmann::json::parse(read_text(json_file));
  const double limit = 2.0 / std::sqrt(kSpringKs / kParticleMass);  // s
  ASSERT_TRUE(j["largest_stable_dt"].is_number()) << j.dump(2);
  ASSERT_TRUE(j["smallest_unstable_dt"].is_number()) << j.dump(2);
  const double stable = j["largest_stable_dt"], unstable = j["smallest_unstable_dt"];
  // Tolerance 0: the search ends on neighbouring steps per frame, which straddle 2 / omega.
  EXPECT_EQ(j["largest_stable_steps_per_frame"].get<int>(),
            j["smallest_unstable_steps_per_frame"].get<int>() + 1);
  EXPECT_LT(stable, limit);
  EXPECT_GT(unstable, limit);
  EXPECT_LE(std::abs(stable - limit), unstable - stable);
  EXPECT_LT((unstable - stable) / stable, 0.03);  // the bracket is tight: 2 %

  // Every trial is recorded; stable ones ran both frames and stayed below a stretch of 1.
  std::set<int> tried;
  for (const auto& trial : j["trials"]) {
    EXPECT_TRUE(tried.insert(trial["steps_per_frame"].get<int>()).second)
        << "a step was tried twice";
    const double dt = trial["dt"];
    EXPECT_EQ(trial["stable"].get<bool>(), dt < limit) << "dt = " << dt;
    if (trial["stable"].get<bool>()) {
      EXPECT_EQ(trial["frames_recorded"].get<int>(), 3);
      EXPECT_LT(trial["max_stretch"].get<double>(), 1.0);
    } else {
      EXPECT_FALSE(trial["message"].get<std::string>().empty());
    }
  }
  EXPECT_TRUE(tried.count(100)) << "the search starts from the scene's step";
}

TEST_F(StudyCli, StabilityMaxDtCapsTheSearch) {
  const fs::path file = scene("spring.yaml", kOneSpring);
  // Every step up to 1e-3 s is stable: the answer is the cap itself, with no unstable step.
  const auto result = run_drapelab({"stability", file.string(), "--max-dt", "0.001"});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find(
                "largest stable dt: 0.001 s (100 steps per frame); smallest unstable: none"),
            std::string::npos)
      << result.output;
}

// Both solver-choosing verbs on the sheet with `options` exit 2, say every one of `expected`, and
// write nothing.
void expect_both_verbs_refuse(const fs::path& sheet, const fs::path& out,
                              const std::vector<std::string>& options,
                              const std::vector<std::string>& expected) {
  for (const std::string verb : {"stability", "study"}) {
    std::vector<std::string> arguments = {verb, sheet.string()};
    arguments.insert(arguments.end(), options.begin(), options.end());
    if (verb == "study") arguments.insert(arguments.end(), {"--out", out.string()});
    const auto result = run_drapelab(arguments);
    EXPECT_EQ(result.exit_code, 2) << verb << ": " << result.output;
    for (const auto& text : expected)
      EXPECT_NE(result.output.find(text), std::string::npos) << result.output;
  }
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(StudyCli, UnknownSolverIsBadInputNamingTheChoices) {
  expect_both_verbs_refuse(scene("sheet.yaml", kSheet), dir() / "out", {"--solver", "nosuch"},
                           {"'nosuch'", "ours (spring_damper)"});
}

TEST_F(StudyCli, AdaptiveSolverIsBadInputForTheStepVaryingVerbs) {
  expect_both_verbs_refuse(scene("sheet.yaml", kSheet), dir() / "out",
                           {"--set", "solvers.0.adaptive_substeps=true"},
                           {"adaptive_substeps: true", "solvers.0.adaptive_substeps=false"});
}

TEST_F(StudyCli, OtherBadInputExits2) {
  const fs::path file = scene("sheet.yaml", kSheet);
  const auto integrator = run_drapelab(
      {"study", file.string(), "--integrators", "rk5", "--out", (dir() / "o").string()});
  EXPECT_EQ(integrator.exit_code, 2) << integrator.output;
  EXPECT_NE(integrator.output.find("'rk5'"), std::string::npos) << integrator.output;
  EXPECT_NE(integrator.output.find("implicit_euler"), std::string::npos) << integrator.output;
  // 1e-3 s does not divide 1/60 s.
  const auto dt =
      run_drapelab({"study", file.string(), "--dt", "0.001", "--out", (dir() / "o").string()});
  EXPECT_EQ(dt.exit_code, 2) << dt.output;
  EXPECT_NE(dt.output.find("frame period"), std::string::npos) << dt.output;
  // duration x frame_rate must stay whole.
  EXPECT_EQ(run_drapelab({"stability", file.string(), "--duration", "0.01"}).exit_code, 2);
  EXPECT_FALSE(fs::exists(dir() / "o"));
}

// study.csv as rows of column -> cell.
std::vector<std::map<std::string, std::string>> read_rows(const fs::path& path) {
  const auto lines = split_lines(read_text(path));
  std::vector<std::map<std::string, std::string>> rows;
  if (lines.empty()) return rows;
  const auto header = split_csv(lines[0]);
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto cells = split_csv(lines[k]);
    EXPECT_EQ(cells.size(), header.size()) << lines[k];
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < header.size() && c < cells.size(); ++c) row[header[c]] = cells[c];
    rows.push_back(row);
  }
  return rows;
}

TEST_F(StudyCli, StudyWritesOneRowPerIntegratorAndStep) {
  const fs::path file = scene("sheet.yaml", kSheet);
  const fs::path out = dir() / "study";
  const auto result =
      run_drapelab({"study", file.string(), "--integrators", "explicit_euler,symplectic_euler,rk4",
                    "--factors", "1,3,64", "--out", out.string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  // 3 x 1/3840 s does not divide 1/60 s: skipped, and said so.
  EXPECT_NE(result.output.find("factor 3 skipped"), std::string::npos) << result.output;

  const auto header = split_csv(split_lines(read_text(out / "study.csv")).at(0));
  const std::vector<std::string> columns = {"integrator",
                                            "factor",
                                            "dt",
                                            "steps_per_frame",
                                            "status",
                                            "stopped_at",
                                            "wall_seconds_per_simulated_second",
                                            "ms_per_step",
                                            "force_evaluations_per_step",
                                            "max_stretch",
                                            "error_rms_final",
                                            "error_rms_max",
                                            "error_max_distance",
                                            "cg_iterations_mean"};
  EXPECT_EQ(header, columns);
  const auto rows = read_rows(out / "study.csv");
  ASSERT_EQ(rows.size(), 6u) << read_text(out / "study.csv");
  std::map<std::pair<std::string, std::string>, std::map<std::string, std::string>> by_key;
  for (const auto& row : rows) by_key[{row.at("integrator"), row.at("factor")}] = row;
  for (const std::string integrator : {"explicit_euler", "symplectic_euler", "rk4"})
    for (const std::string factor : {"1", "64"})
      ASSERT_TRUE(by_key.count({integrator, factor})) << integrator << factor;

  const auto& rk4 = by_key[{"rk4", "1"}];
  const auto& euler = by_key[{"explicit_euler", "1"}];
  ASSERT_EQ(rk4.at("status"), "ok");
  ASSERT_EQ(euler.at("status"), "ok");
  EXPECT_EQ(rk4.at("steps_per_frame"), "64");
  EXPECT_EQ(rk4.at("force_evaluations_per_step"), "4");
  EXPECT_EQ(euler.at("force_evaluations_per_step"), "1");
  const double rk4_error = std::stod(rk4.at("error_rms_final"));
  const double euler_error = std::stod(euler.at("error_rms_final"));
  EXPECT_GT(euler_error, 0.0);
  EXPECT_LT(rk4_error, 1e-3 * euler_error);  // fourth order against first order, at the same step
  EXPECT_LE(std::stod(rk4.at("error_rms_final")), std::stod(rk4.at("error_rms_max")));
  EXPECT_LE(std::stod(rk4.at("error_rms_max")), std::stod(rk4.at("error_max_distance")));
  EXPECT_TRUE(rk4.at("stopped_at").empty());

  // One step per frame blows up the symplectic scheme: a row with status unstable and no errors.
  const auto& wild = by_key[{"symplectic_euler", "64"}];
  EXPECT_EQ(wild.at("status"), "unstable");
  EXPECT_EQ(wild.at("steps_per_frame"), "1");
  EXPECT_TRUE(wild.at("error_rms_final").empty());
  EXPECT_TRUE(wild.at("error_rms_max").empty());
  EXPECT_FALSE(wild.at("stopped_at").empty());

  const std::string markdown = read_text(out / "study.md");
  EXPECT_NE(markdown.find("| integrator | h (s) |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("reference, rk4 at h = "), std::string::npos) << markdown;
  int table_lines = 0;  // the header row and one row per csv row (the separator starts with "|-")
  for (const auto& line : split_lines(markdown)) table_lines += line.rfind("| ", 0) == 0 ? 1 : 0;
  EXPECT_EQ(table_lines, 1 + 6) << markdown;
}

TEST_F(StudyCli, StudyOfImplicitEulerReportsConjugateGradientIterations) {
  const fs::path file = scene("sheet.yaml", kSheet);
  const fs::path out = dir() / "study";
  const auto result =
      run_drapelab({"study", file.string(), "--integrators", "implicit_euler,leapfrog", "--factors",
                    "4", "--out", out.string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto rows = read_rows(out / "study.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("integrator"), "implicit_euler");
  EXPECT_EQ(rows[0].at("status"), "ok");
  EXPECT_GT(std::stod(rows[0].at("cg_iterations_mean")),
            0.0);  // the solve ran (a warm start may need none)
  EXPECT_TRUE(rows[1].at("cg_iterations_mean").empty());  // leapfrog has no linear solve
}

}  // namespace
