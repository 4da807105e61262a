// End-to-end tests of the drapelab binary: help, run (every output file of docs/outputs.md),
// validate, exit codes, the run folder's safety rules, determinism and unstable runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixtures/cli.hpp"

namespace {

namespace fs = std::filesystem;
using drapelab::fixtures::CommandResult;
using drapelab::fixtures::read_text;
using drapelab::fixtures::run_drapelab;
using drapelab::fixtures::split_csv;
using drapelab::fixtures::split_lines;
using drapelab::fixtures::write_text;
using nlohmann::json;

// A 9 x 9 sheet pinned at its corners, 0.1 s at 60 frames/s (6 frames after frame 0), 16 steps per
// frame, well below the stable step (about 1.6e-3 s).
const std::string kSmall =
    "# A small sheet for the command-line tests.\n"                        // 1
    "name: cli_small\n"                                                    // 2
    "duration: 0.1\n"                                                      // 3
    "seed: 7\n"                                                            // 4
    "cloth:\n"                                                             // 5
    "  size: [0.4, 0.4]\n"                                                 // 6
    "  resolution: [9, 9]\n"                                               // 7
    "  mass: 0.1\n"                                                        // 8
    "  perturbation: 0.001\n"                                              // 9
    "  springs:\n"                                                         // 10
    "    stretch: {ks: 200, kd: 0.01}\n"                                   // 11
    "    shear: {ks: 20, kd: 0.005}\n"                                     // 12
    "    bend: {ks: 2, kd: 0.001}\n"                                       // 13
    "  pins:\n"                                                            // 14
    "    - corners\n"                                                      // 15
    "solvers:\n"                                                           // 16
    "  - {name: ours, type: spring_damper, dt: 0.0010416666666666667}\n";  // 17

constexpr int kParticles = 81;
constexpr int kTriangles = 2 * 8 * 8;
constexpr int kFrames = 6;  // duration x frame_rate; frame 0 is recorded too
constexpr int kStepsPerFrame = 16;

// Two stable solvers side by side.
const std::string kTwoSolvers =
    kSmall + "  - {name: fine, type: spring_damper, dt: 0.00052083333333333333}\n";

// One stable solver and one that explodes: explicit Euler at a quarter of a frame per step.
const std::string kOneUnstable = kSmall +
                                 "  - {name: wild, type: spring_damper, integrator: "
                                 "explicit_euler, dt: 0.0041666666666666667}\n";

const std::vector<std::string> kMetricsColumns = {"solver",
                                                  "frame",
                                                  "time",
                                                  "kinetic_energy",
                                                  "gravity_energy",
                                                  "spring_energy",
                                                  "max_stretch",
                                                  "mean_stretch",
                                                  "min_clearance",
                                                  "max_penetration",
                                                  "contact_count",
                                                  "centroid_x",
                                                  "centroid_y",
                                                  "centroid_z",
                                                  "lowest_y",
                                                  "projected_area",
                                                  "drape_coefficient",
                                                  "drape_nodes",
                                                  "self_intersections",
                                                  "triangle_penetration",
                                                  "constraint_error",
                                                  "elastic_energy",
                                                  "contact_energy",
                                                  "constraint_energy",
                                                  "total_energy",
                                                  "external_work",
                                                  "dissipated",
                                                  "energy_error",
                                                  "self_contact_energy"};
const std::vector<std::string> kCompareColumns = {
    "solver_a", "solver_b", "frame", "time", "rms_distance", "max_distance", "hausdorff_distance"};
const std::vector<std::string> kContactsColumns = {
    "solver",        "frame",        "time",           "collider",
    "contact_count", "normal_force", "friction_force", "max_penetration"};
// Empty while the scene has no colliders and no drape support.
const std::vector<std::string> kEmptyMetricsColumns = {
    "min_clearance",     "max_penetration",      "contact_count",    "drape_coefficient",
    "drape_nodes",       "triangle_penetration", "constraint_error", "contact_energy",
    "constraint_energy", "self_contact_energy"};

// A parsed CSV file: header and rows, each row a map from column name to cell.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  std::size_t column(const std::string& name) const {
    for (std::size_t k = 0; k < header.size(); ++k)
      if (header[k] == name) return k;
    throw std::out_of_range("no column " + name);
  }
  const std::string& cell(std::size_t row, const std::string& name) const {
    return rows.at(row).at(column(name));
  }
  std::vector<std::size_t> rows_of(const std::string& key, const std::string& value) const {
    std::vector<std::size_t> picked;
    for (std::size_t r = 0; r < rows.size(); ++r)
      if (cell(r, key) == value) picked.push_back(r);
    return picked;
  }
};

Csv read_csv(const fs::path& path) {
  Csv csv;
  const auto lines = split_lines(read_text(path));
  if (lines.empty()) return csv;
  csv.header = split_csv(lines[0]);
  for (std::size_t k = 1; k < lines.size(); ++k) csv.rows.push_back(split_csv(lines[k]));
  return csv;
}

// Every row has exactly the header's number of cells, and the file ends with a newline.
void ExpectWellFormedCsv(const fs::path& path) {
  const std::string text = read_text(path);
  ASSERT_FALSE(text.empty()) << path;
  EXPECT_EQ(text.back(), '\n') << path << " ends in the middle of a row";
  const Csv csv = read_csv(path);
  for (std::size_t r = 0; r < csv.rows.size(); ++r)
    EXPECT_EQ(csv.rows[r].size(), csv.header.size()) << path << " row " << r + 1;
}

bool is_number(const std::string& cell) {
  if (cell.empty()) return false;
  char* end = nullptr;
  const double value = std::strtod(cell.c_str(), &end);
  return end == cell.c_str() + cell.size() && std::isfinite(value);
}

std::string all_output(const CommandResult& result) {
  return "exit code " + std::to_string(result.exit_code) + ", output:\n" + result.output;
}

template <typename T>
T read_binary(const std::string& bytes, std::size_t offset) {
  T value{};
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;
}

std::size_t count_lines_starting_with(const std::string& text, const std::string& prefix) {
  std::size_t count = 0;
  for (const auto& line : split_lines(text))
    if (line.rfind(prefix, 0) == 0) ++count;
  return count;
}

class Cli : public drapelab::fixtures::TempDirTest {
 protected:
  fs::path scene(const std::string& name, const std::string& text) {
    const fs::path path = dir() / name;
    write_text(path, text);
    return path;
  }
  CommandResult run(const fs::path& scene_file, const fs::path& out,
                    std::vector<std::string> extra = {}) {
    std::vector<std::string> arguments = {"run", scene_file.string(), "--out", out.string()};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    return run_drapelab(arguments);
  }
  // Every regular file under `folder`, relative path -> contents.
  static std::map<std::string, std::string> snapshot(const fs::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder))
      if (entry.is_regular_file())
        files[fs::relative(entry.path(), folder).string()] = read_text(entry.path());
    return files;
  }
};

// ---------------------------------------------------------------------------------------------
// Help and usage errors

TEST_F(Cli, HelpShowsTheVerbsAndAnExample) {
  const auto result = run_drapelab({"--help"});
  EXPECT_EQ(result.exit_code, 0) << all_output(result);
  EXPECT_NE(result.output.find("Example"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("run"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("validate"), std::string::npos) << result.output;
}

TEST_F(Cli, EachVerbHasHelpWithAnExample) {
  for (const char* verb : {"run", "validate"}) {
    const auto result = run_drapelab({verb, "--help"});
    EXPECT_EQ(result.exit_code, 0) << verb << ": " << all_output(result);
    EXPECT_NE(result.output.find("Example"), std::string::npos) << verb << ": " << result.output;
    EXPECT_NE(result.output.find(std::string("drapelab ") + verb), std::string::npos)
        << verb << ": " << result.output;
  }
  EXPECT_NE(run_drapelab({"run", "--help"}).output.find("--out"), std::string::npos);
  EXPECT_NE(run_drapelab({"validate", "--help"}).output.find("--print-resolved"),
            std::string::npos);
}

TEST_F(Cli, UnknownOptionIsBadInput) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  const auto result = run(file, out, {"--frobnicate"});
  EXPECT_EQ(result.exit_code, 2) << all_output(result);
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, OtherUsageErrorsAreBadInput) {
  const fs::path file = scene("small.yaml", kSmall);
  EXPECT_EQ(run_drapelab({}).exit_code, 2);                                 // no verb
  EXPECT_EQ(run_drapelab({"simulate", file.string()}).exit_code, 2);        // unknown verb
  EXPECT_EQ(run_drapelab({"run", file.string()}).exit_code, 2);             // no --out
  EXPECT_EQ(run(file, dir() / "out", {"--meshes", "maybe"}).exit_code, 2);  // not a choice
  EXPECT_FALSE(fs::exists(dir() / "out"));
}

// ---------------------------------------------------------------------------------------------
// A good run: every file

TEST_F(Cli, RunWritesEveryFileOfTheContract) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  const auto result = run(file, out);
  ASSERT_EQ(result.exit_code, 0) << all_output(result);

  for (const char* name : {"scene.yaml", "resolved.yaml", "metrics.csv", "compare.csv",
                           "contacts.csv", "summary.json"})
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
  EXPECT_FALSE(fs::exists(out / "meshes")) << "meshes are written on request only";
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_EQ(entry.path().extension().string().find("partial"), std::string::npos)
        << "a temporary file was left behind: " << entry.path();

  // scene.yaml: the scene as given, byte for byte.
  EXPECT_EQ(read_text(out / "scene.yaml"), kSmall);
}

TEST_F(Cli, MetricsCsvHasEveryColumnAndOneRowPerFrame) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  ASSERT_EQ(run(file, out).exit_code, 0);
  ExpectWellFormedCsv(out / "metrics.csv");
  const Csv csv = read_csv(out / "metrics.csv");
  for (const auto& column : kMetricsColumns)
    EXPECT_NE(std::find(csv.header.begin(), csv.header.end(), column), csv.header.end())
        << "missing " << column;
  EXPECT_EQ(std::set<std::string>(csv.header.begin(), csv.header.end()).size(), csv.header.size())
      << "a column appears twice";

  ASSERT_EQ(csv.rows.size(), static_cast<std::size_t>(kFrames + 1))
      << "one row per frame, frame 0 included";
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    SCOPED_TRACE("row " + std::to_string(r + 1));
    EXPECT_EQ(csv.cell(r, "solver"), "ours");
    EXPECT_EQ(csv.cell(r, "frame"), std::to_string(r));
    EXPECT_NEAR(std::stod(csv.cell(r, "time")), static_cast<double>(r) / 60.0, 1e-12);
    for (const auto& column : kEmptyMetricsColumns) EXPECT_EQ(csv.cell(r, column), "") << column;
    for (const auto& column : kMetricsColumns) {
      if (column == "solver" || std::find(kEmptyMetricsColumns.begin(), kEmptyMetricsColumns.end(),
                                          column) != kEmptyMetricsColumns.end())
        continue;
      EXPECT_TRUE(is_number(csv.cell(r, column))) << column << " = [" << csv.cell(r, column) << "]";
    }
  }
  // A sheet hanging from its corners does not pass through itself.
  for (std::size_t r = 0; r < csv.rows.size(); ++r)
    EXPECT_EQ(csv.cell(r, "self_intersections"), "0");
  // Frame 0 is the initial state: at rest, springs unstretched (the 1 mm perturbation aside).
  EXPECT_EQ(std::stod(csv.cell(0, "kinetic_energy")), 0.0);
  EXPECT_EQ(std::stod(csv.cell(0, "time")), 0.0);
  // The cloth falls: its centroid is lower at the last frame than at frame 0.
  EXPECT_LT(std::stod(csv.cell(kFrames, "centroid_y")), std::stod(csv.cell(0, "centroid_y")));
  // The balance: energy_error is total + dissipated - external work less its start (nothing
  // drives this sheet), and small beside the kinetic energy the fall gave.
  const double start = std::stod(csv.cell(0, "total_energy"));  // J
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    const double total = std::stod(csv.cell(r, "total_energy"));
    const double dissipated = std::stod(csv.cell(r, "dissipated"));
    EXPECT_EQ(std::stod(csv.cell(r, "external_work")), 0.0);
    EXPECT_NEAR(std::stod(csv.cell(r, "energy_error")), total + dissipated - start,
                1e-12 * std::abs(start));
  }
  const double dissipated = std::stod(csv.cell(kFrames, "dissipated"));
  EXPECT_GT(dissipated, 0.0);
  EXPECT_LT(std::abs(std::stod(csv.cell(kFrames, "energy_error"))),
            0.05 * std::stod(csv.cell(kFrames, "kinetic_energy")));
}

// The mesh audits for every solver: the sheet of kSmall, free, on a sphere 5 mm (its thickness)
// below it, under our cloth and both of Bullet's.
TEST_F(Cli, MeshAuditColumnsAreWrittenForEverySolver) {
  const std::string text =
      "name: cli_audit\n"
      "duration: 0.1\n"
      "cloth: {size: [0.4, 0.4], resolution: [9, 9], mass: 0.1, center: [0, 0.5, 0], plane: xz,\n"
      "        perturbation: 0, thickness: 0.005,\n"
      "        springs: {stretch: {ks: 200, kd: 0.01}, shear: {ks: 20, kd: 0.005},\n"
      "                  bend: {ks: 2, kd: 0.001}}}\n"
      "colliders:\n"
      "  - {name: ball, type: sphere, center: [0, 0.3, 0], radius: 0.195}\n"
      "contact: {stiffness: 500, damping: 0.05}\n"
      "solvers:\n"
      "  - {name: ours, type: spring_damper}\n"
      "  - {name: classic, type: bullet_softbody}\n"
      "  - {name: deformable, type: bullet_deformable}\n";
  const fs::path out = dir() / "out";
  const auto result = run(scene("audit.yaml", text), out);
  ASSERT_EQ(result.exit_code, 0) << all_output(result);
  const Csv csv = read_csv(out / "metrics.csv");
  std::map<std::string, int> rows_per_solver;
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    const std::string solver = csv.cell(r, "solver");
    SCOPED_TRACE(solver + " frame " + csv.cell(r, "frame"));
    ++rows_per_solver[solver];
    const std::string crossings = csv.cell(r, "self_intersections");
    ASSERT_FALSE(crossings.empty());
    EXPECT_EQ(crossings.find_first_not_of("0123456789"), std::string::npos) << crossings;
    ASSERT_TRUE(is_number(csv.cell(r, "triangle_penetration")));
    const double reach = std::stod(csv.cell(r, "triangle_penetration"));
    EXPECT_GE(reach, 0.0);
    // A triangle holds its corners: it reaches at least as deep as any particle does.
    EXPECT_GE(reach, std::stod(csv.cell(r, "max_penetration")) - 1e-9);
    // A cloth this close to the sphere is never more than its thickness plus 5 mm into it.
    EXPECT_LT(reach, 0.01);
  }
  EXPECT_EQ(rows_per_solver,
            (std::map<std::string, int>{
                {"ours", kFrames + 1}, {"classic", kFrames + 1}, {"deformable", kFrames + 1}}));
  // Frame 0: the sheet lies 5 mm (one thickness) above the sphere's top, plus a rounding.
  EXPECT_NEAR(std::stod(csv.cell(0, "triangle_penetration")), 0.0, 1e-9);
}

TEST_F(Cli, CompareAndContactsCsvHaveTheirHeaders) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  ASSERT_EQ(run(file, out).exit_code, 0);
  ExpectWellFormedCsv(out / "compare.csv");
  ExpectWellFormedCsv(out / "contacts.csv");
  const Csv compare = read_csv(out / "compare.csv");
  const Csv contacts = read_csv(out / "contacts.csv");
  EXPECT_EQ(compare.header, kCompareColumns);
  EXPECT_EQ(contacts.header, kContactsColumns);
  EXPECT_TRUE(compare.rows.empty()) << "one solver: no pair to compare";
  EXPECT_TRUE(contacts.rows.empty()) << "no colliders: no contact rows";
}

TEST_F(Cli, SummaryJsonHasStatusStepsAndFinalMetrics) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  ASSERT_EQ(run(file, out).exit_code, 0);
  const json summary = json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary.at("scene"), "cli_small");
  EXPECT_TRUE(summary.contains("drapelab_version"));
  ASSERT_TRUE(summary.at("solvers").contains("ours"));
  EXPECT_EQ(summary.at("solvers").size(), 1u);
  const json& ours = summary.at("solvers").at("ours");
  EXPECT_EQ(ours.at("type"), "spring_damper");
  EXPECT_EQ(ours.at("status"), "ok");
  EXPECT_EQ(ours.at("message"), "");
  EXPECT_EQ(ours.at("steps").get<long long>(), kFrames * kStepsPerFrame);
  ASSERT_TRUE(ours.at("ms_per_step").is_number());
  EXPECT_GE(ours.at("ms_per_step").get<double>(), 0.0);
  ASSERT_TRUE(ours.at("wall_seconds").is_number());
  EXPECT_GE(ours.at("wall_seconds").get<double>(), 0.0);

  // The final metrics are the last recorded frame's row of metrics.csv, to the last bit.
  const json& final_metrics = ours.at("final");
  const Csv csv = read_csv(out / "metrics.csv");
  const std::size_t last = csv.rows.size() - 1;
  for (const char* key : {"kinetic_energy", "gravity_energy", "spring_energy", "max_stretch",
                          "mean_stretch", "lowest_y", "projected_area"}) {
    ASSERT_TRUE(final_metrics.contains(key)) << key;
    ASSERT_TRUE(final_metrics.at(key).is_number()) << key;
    EXPECT_EQ(final_metrics.at(key).get<double>(), std::stod(csv.cell(last, key))) << key;
  }
  for (const char* key : {"max_penetration", "drape_coefficient", "triangle_penetration"}) {
    ASSERT_TRUE(final_metrics.contains(key)) << key;
    EXPECT_TRUE(final_metrics.at(key).is_null()) << key << " has no collider or support to measure";
  }
}

TEST_F(Cli, ResolvedYamlValidatesAndReproducesTheRun) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  ASSERT_EQ(run(file, out).exit_code, 0);
  const fs::path resolved = out / "resolved.yaml";
  const std::string text = read_text(resolved);
  for (const char* expected :
       {"frame_rate: 60", "gravity: [0, -9.81, 0]", "thickness: 0.005", "seed: 7"})
    EXPECT_NE(text.find(expected), std::string::npos) << expected << " missing from\n" << text;

  const auto validated = run_drapelab({"validate", resolved.string()});
  EXPECT_EQ(validated.exit_code, 0) << all_output(validated);
  const fs::path again = dir() / "again";
  const auto rerun = run(resolved, again);
  ASSERT_EQ(rerun.exit_code, 0) << all_output(rerun);
  // The run folder alone reproduces the run.
  EXPECT_EQ(read_text(again / "metrics.csv"), read_text(out / "metrics.csv"));
}

// Adaptive substeps through the program: counted in summary.json, recorded in resolved.yaml (whose
// rerun reproduces the run), and shown by validate.
TEST_F(Cli, AdaptiveSubstepsAreCountedRecordedAndShown) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  const auto result = run(file, out, {"--set", "solvers.0.adaptive_substeps=true"});
  ASSERT_EQ(result.exit_code, 0) << all_output(result);
  const json summary = json::parse(read_text(out / "summary.json"));
  const json& ours = summary.at("solvers").at("ours");
  ASSERT_TRUE(ours.contains("integrator_statistics")) << ours.dump();
  const auto& counts = ours.at("integrator_statistics");
  EXPECT_GE(counts.at("substeps").get<double>(), ours.at("steps").get<double>());
  EXPECT_GE(counts.at("substeps_per_step_max").get<double>(),
            counts.at("substeps_per_step_min").get<double>());
  EXPECT_TRUE(ours.at("phase_seconds").contains("step_bound")) << ours.dump();
  EXPECT_NE(read_text(out / "resolved.yaml").find("adaptive_substeps: true"), std::string::npos);
  const fs::path again = dir() / "again";
  ASSERT_EQ(run(out / "resolved.yaml", again).exit_code, 0);
  EXPECT_EQ(read_text(again / "metrics.csv"), read_text(out / "metrics.csv"));
  const auto validated =
      run_drapelab({"validate", file.string(), "--set", "solvers.0.adaptive_substeps=true"});
  EXPECT_EQ(validated.exit_code, 0) << all_output(validated);
  EXPECT_NE(validated.output.find("adaptive substeps: 0.9 x the shape's stable step"),
            std::string::npos)
      << validated.output;
}

TEST_F(Cli, QuietRunPrintsNothingWhenAllIsWell) {
  const fs::path file = scene("small.yaml", kSmall);
  const auto result = run(file, dir() / "out", {"-q"});
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_EQ(result.output, "");
}

// ---------------------------------------------------------------------------------------------
// Two solvers

TEST_F(Cli, TwoSolversGetOneCompareRowPerFrame) {
  const fs::path file = scene("two.yaml", kTwoSolvers);
  const fs::path out = dir() / "out";
  const auto result = run(file, out);
  ASSERT_EQ(result.exit_code, 0) << all_output(result);

  ExpectWellFormedCsv(out / "compare.csv");
  const Csv compare = read_csv(out / "compare.csv");
  ASSERT_EQ(compare.rows.size(), static_cast<std::size_t>(kFrames + 1));
  for (std::size_t r = 0; r < compare.rows.size(); ++r) {
    EXPECT_EQ(compare.cell(r, "solver_a"), "ours");
    EXPECT_EQ(compare.cell(r, "solver_b"), "fine");
    EXPECT_EQ(compare.cell(r, "frame"), std::to_string(r));
    EXPECT_TRUE(is_number(compare.cell(r, "rms_distance")));
    EXPECT_TRUE(is_number(compare.cell(r, "max_distance")));
    EXPECT_LE(std::stod(compare.cell(r, "rms_distance")),
              std::stod(compare.cell(r, "max_distance")));
  }
  EXPECT_EQ(std::stod(compare.cell(0, "max_distance")), 0.0) << "both start from the same state";
  EXPECT_GT(std::stod(compare.cell(kFrames, "max_distance")), 0.0)
      << "different steps give different states";

  const Csv metrics = read_csv(out / "metrics.csv");
  EXPECT_EQ(metrics.rows_of("solver", "ours").size(), static_cast<std::size_t>(kFrames + 1));
  EXPECT_EQ(metrics.rows_of("solver", "fine").size(), static_cast<std::size_t>(kFrames + 1));

  const json summary = json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary.at("solvers").at("ours").at("steps").get<long long>(),
            kFrames * kStepsPerFrame);
  EXPECT_EQ(summary.at("solvers").at("fine").at("steps").get<long long>(),
            kFrames * 2 * kStepsPerFrame);
}

// ---------------------------------------------------------------------------------------------
// Meshes

TEST_F(Cli, MeshesBothWritesRestObjPointCacheAndFrameObjs) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  const auto result = run(file, out, {"--meshes", "both"});
  ASSERT_EQ(result.exit_code, 0) << all_output(result);
  const fs::path meshes = out / "meshes";

  // rest.obj: one vertex and one UV per particle, the grid's triangles.
  const std::string rest = read_text(meshes / "rest.obj");
  EXPECT_EQ(count_lines_starting_with(rest, "v "), static_cast<std::size_t>(kParticles));
  EXPECT_EQ(count_lines_starting_with(rest, "vt "), static_cast<std::size_t>(kParticles));
  EXPECT_EQ(count_lines_starting_with(rest, "f "), static_cast<std::size_t>(kTriangles));
  for (const auto& line : split_lines(rest)) {
    if (line.rfind("f ", 0) != 0) continue;
    std::istringstream in(line.substr(2));
    for (std::string corner; in >> corner;) {
      const int v = std::stoi(corner.substr(0, corner.find('/')));
      EXPECT_GE(v, 1);
      EXPECT_LE(v, kParticles);
    }
  }

  // ours.pc2: the PC2 header, then (frames + 1) samples of every particle's position.
  const std::string pc2 = read_text(meshes / "ours.pc2");
  ASSERT_GE(pc2.size(), 32u);
  EXPECT_EQ(std::memcmp(pc2.data(), "POINTCACHE2\0", 12), 0);
  EXPECT_EQ(read_binary<std::int32_t>(pc2, 12), 1) << "version";
  EXPECT_EQ(read_binary<std::int32_t>(pc2, 16), kParticles) << "points";
  EXPECT_EQ(read_binary<float>(pc2, 20), 0.0f) << "start frame";
  EXPECT_EQ(read_binary<float>(pc2, 24), 1.0f) << "sample rate";
  EXPECT_EQ(read_binary<std::int32_t>(pc2, 28), kFrames + 1) << "samples";
  EXPECT_EQ(pc2.size(), 32u + static_cast<std::size_t>(kFrames + 1) * kParticles * 12u);
  // The first sample is the initial state: within the 1 mm perturbation of rest.obj.
  std::size_t k = 0;
  for (const auto& line : split_lines(rest)) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream in(line.substr(2));
    double x = 0, y = 0, z = 0;
    in >> x >> y >> z;
    EXPECT_NEAR(read_binary<float>(pc2, 32 + 12 * k + 0), x, 1e-6) << "particle " << k;
    EXPECT_NEAR(read_binary<float>(pc2, 32 + 12 * k + 4), y, 1.001e-3) << "particle " << k;
    EXPECT_NEAR(read_binary<float>(pc2, 32 + 12 * k + 8), z, 1e-6) << "particle " << k;
    ++k;
  }
  EXPECT_EQ(k, static_cast<std::size_t>(kParticles));

  // One OBJ per recorded frame, numbered from 0000.
  for (int frame = 0; frame <= kFrames; ++frame) {
    char name[32];
    std::snprintf(name, sizeof name, "ours_%04d.obj", frame);
    ASSERT_TRUE(fs::is_regular_file(meshes / name)) << name;
    const std::string obj = read_text(meshes / name);
    EXPECT_EQ(count_lines_starting_with(obj, "v "), static_cast<std::size_t>(kParticles)) << name;
    EXPECT_EQ(count_lines_starting_with(obj, "f "), static_cast<std::size_t>(kTriangles)) << name;
  }
  EXPECT_FALSE(fs::exists(meshes / "ours_0007.obj"));
}

TEST_F(Cli, MeshesPc2WritesNoFrameObjs) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  ASSERT_EQ(run(file, out, {"--meshes", "pc2"}).exit_code, 0);
  EXPECT_TRUE(fs::is_regular_file(out / "meshes" / "rest.obj"));
  EXPECT_TRUE(fs::is_regular_file(out / "meshes" / "ours.pc2"));
  EXPECT_FALSE(fs::exists(out / "meshes" / "ours_0000.obj"));
}

// ---------------------------------------------------------------------------------------------
// Bad input: exit 2, nothing written

TEST_F(Cli, BadSceneIsExit2WithFileLineAndKeyAndNoOutputFolder) {
  std::string bad = kSmall;
  bad.replace(bad.find("{ks: 200,"), 9, "{ks: -3,");  // line 11
  const fs::path file = scene("bad.yaml", bad);
  const fs::path out = dir() / "out";
  const auto result = run(file, out);
  EXPECT_EQ(result.exit_code, 2) << all_output(result);
  EXPECT_NE(result.output.find(file.string() + ":11:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("cloth.springs.stretch.ks"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("must be > 0"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(out)) << "nothing may be written for a bad scene";
}

TEST_F(Cli, BadSetIsExit2) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  const auto result = run(file, out, {"--set", "cloth.springs.stretch.ks=-3"});
  EXPECT_EQ(result.exit_code, 2) << all_output(result);
  EXPECT_NE(result.output.find("--set cloth.springs.stretch.ks=-3"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("cloth.springs.stretch.ks must be > 0"), std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(out));

  const auto malformed = run(file, out, {"--set", "seed"});
  EXPECT_EQ(malformed.exit_code, 2) << all_output(malformed);
  EXPECT_NE(malformed.output.find("key.path=value"), std::string::npos) << malformed.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, GoodSetChangesTheRun) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  const auto result =
      run(file, out, {"--set", "gravity=[0,-1.62,0]", "--set", "cloth.resolution=[5,7]"});
  ASSERT_EQ(result.exit_code, 0) << all_output(result);
  const std::string resolved = read_text(out / "resolved.yaml");
  EXPECT_NE(resolved.find("gravity: [0, -1.62, 0]"), std::string::npos) << resolved;
  EXPECT_NE(resolved.find("resolution: [5, 7]"), std::string::npos) << resolved;
  EXPECT_EQ(read_text(out / "scene.yaml"), kSmall) << "scene.yaml stays the scene as given";
  const json summary = json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary.at("model").at("particles").get<int>(), 35);
}

TEST_F(Cli, MissingSceneFileIsExit2) {
  const fs::path out = dir() / "out";
  const auto result = run(dir() / "nowhere.yaml", out);
  EXPECT_EQ(result.exit_code, 2) << all_output(result);
  EXPECT_NE(result.output.find("nowhere.yaml"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("cannot be read"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(out));
}

// ---------------------------------------------------------------------------------------------
// Determinism and the run folder's rules

TEST_F(Cli, RunningTwiceGivesByteIdenticalTables) {
  const fs::path file = scene("two.yaml", kTwoSolvers);
  ASSERT_EQ(run(file, dir() / "first").exit_code, 0);
  ASSERT_EQ(run(file, dir() / "second").exit_code, 0);
  const std::string metrics = read_text(dir() / "first" / "metrics.csv");
  EXPECT_EQ(read_text(dir() / "second" / "metrics.csv"), metrics);
  EXPECT_EQ(read_text(dir() / "second" / "compare.csv"),
            read_text(dir() / "first" / "compare.csv"));
  // ...and the seed matters: another seed perturbs the sheet differently.
  ASSERT_EQ(run(file, dir() / "third", {"--set", "seed=8"}).exit_code, 0);
  EXPECT_NE(read_text(dir() / "third" / "metrics.csv"), metrics);
}

TEST_F(Cli, DifferentRunInTheFolderNeedsForce) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  ASSERT_EQ(run(file, out).exit_code, 0);
  const auto before = snapshot(out);

  const auto refused = run(file, out, {"--set", "cloth.mass=0.2"});
  EXPECT_EQ(refused.exit_code, 2) << all_output(refused);
  EXPECT_NE(refused.output.find("--force"), std::string::npos) << refused.output;
  EXPECT_EQ(snapshot(out), before) << "the previous run's files must stay untouched";

  const auto forced = run(file, out, {"--set", "cloth.mass=0.2", "--force"});
  EXPECT_EQ(forced.exit_code, 0) << all_output(forced);
  EXPECT_NE(read_text(out / "resolved.yaml").find("mass: 0.2"), std::string::npos);
  EXPECT_NE(read_text(out / "metrics.csv"), before.at("metrics.csv"));
}

TEST_F(Cli, SameRunCanBeRepeatedInItsFolder) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  ASSERT_EQ(run(file, out).exit_code, 0);
  const std::string metrics = read_text(out / "metrics.csv");
  const auto again = run(file, out);
  EXPECT_EQ(again.exit_code, 0) << all_output(again);
  EXPECT_EQ(read_text(out / "metrics.csv"), metrics);
}

TEST_F(Cli, FolderWithOtherFilesIsRefusedWithoutForce) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  fs::create_directories(out);
  write_text(out / "notes.txt", "mine");
  const auto result = run(file, out);
  EXPECT_EQ(result.exit_code, 2) << all_output(result);
  EXPECT_EQ(read_text(out / "notes.txt"), "mine");
  EXPECT_FALSE(fs::exists(out / "metrics.csv"));
}

TEST_F(Cli, ForceReplacesOnlyDrapelabsOwnFiles) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  ASSERT_EQ(run(file, out, {"--meshes", "both"}).exit_code, 0);
  write_text(out / "notes.txt", "mine");
  const auto forced = run(file, out, {"--set", "cloth.mass=0.2", "--force"});
  EXPECT_EQ(forced.exit_code, 0) << all_output(forced);
  EXPECT_EQ(read_text(out / "notes.txt"), "mine");
  EXPECT_FALSE(fs::exists(out / "meshes")) << "the previous run's meshes belong to a different run";
}

TEST_F(Cli, OutputPathThatIsAFileIsBadInput) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "occupied";
  write_text(out, "not a folder");
  const auto result = run(file, out);
  EXPECT_EQ(result.exit_code, 2) << all_output(result);
  EXPECT_NE(result.output.find("not a folder"), std::string::npos) << result.output;
  EXPECT_EQ(read_text(out), "not a folder");
}

// ---------------------------------------------------------------------------------------------
// Unstable runs

TEST_F(Cli, UnstableRunIsExit1WithAHelpfulMessageAndValidFiles) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  // One step per frame: ten times the stable step of these springs.
  const auto result = run(file, out, {"--set", "solvers.0.dt=0.016666666666666666"});
  EXPECT_EQ(result.exit_code, 1) << all_output(result);
  EXPECT_NE(result.output.find("unstable"), std::string::npos) << result.output;

  const json summary =
      json::parse(read_text(out / "summary.json"));  // throws (fails) if not valid JSON
  const json& ours = summary.at("solvers").at("ours");
  EXPECT_EQ(ours.at("status"), "unstable");
  const std::string message = ours.at("message");
  EXPECT_NE(message.find("particle"), std::string::npos) << message;
  EXPECT_NE(message.find("step"), std::string::npos) << message;
  EXPECT_NE(message.find("Try"), std::string::npos) << message;
  EXPECT_LT(ours.at("steps").get<long long>(), kFrames)
      << "the solver stops when it becomes unstable";

  ExpectWellFormedCsv(out / "metrics.csv");
  ExpectWellFormedCsv(out / "compare.csv");
  ExpectWellFormedCsv(out / "contacts.csv");
  const Csv metrics = read_csv(out / "metrics.csv");
  EXPECT_EQ(metrics.header.size(), kMetricsColumns.size());
  EXPECT_GE(metrics.rows.size(), 1u) << "frame 0 is always recorded";
  EXPECT_LE(metrics.rows.size(), static_cast<std::size_t>(kFrames + 1));
}

TEST_F(Cli, ExplicitEulerWithABigStepIsUnstable) {
  const fs::path file = scene("small.yaml", kSmall);
  const fs::path out = dir() / "out";
  const auto result = run(file, out,
                          {"--set", "solvers.0.integrator=explicit_euler", "--set",
                           "solvers.0.dt=0.0041666666666666667"});
  EXPECT_EQ(result.exit_code, 1) << all_output(result);
  const json summary = json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary.at("solvers").at("ours").at("status"), "unstable");
  EXPECT_NE(
      summary.at("solvers").at("ours").at("message").get<std::string>().find("symplectic_euler"),
      std::string::npos)
      << "the advice names the stable integrator";
}

TEST_F(Cli, OneUnstableSolverStopsAloneAndTheOtherFinishes) {
  const fs::path file = scene("mixed.yaml", kOneUnstable);
  const fs::path out = dir() / "out";
  const auto result = run(file, out);
  EXPECT_EQ(result.exit_code, 1) << all_output(result);

  const json summary = json::parse(read_text(out / "summary.json"));
  const json& ours = summary.at("solvers").at("ours");
  const json& wild = summary.at("solvers").at("wild");
  EXPECT_EQ(ours.at("status"), "ok");
  EXPECT_EQ(ours.at("steps").get<long long>(), kFrames * kStepsPerFrame);
  EXPECT_EQ(wild.at("status"), "unstable");
  EXPECT_NE(wild.at("message").get<std::string>().find("Try"), std::string::npos);

  ExpectWellFormedCsv(out / "metrics.csv");
  ExpectWellFormedCsv(out / "compare.csv");
  const Csv metrics = read_csv(out / "metrics.csv");
  const auto ours_rows = metrics.rows_of("solver", "ours");
  ASSERT_EQ(ours_rows.size(), static_cast<std::size_t>(kFrames + 1))
      << "every frame of the stable solver";
  for (std::size_t k = 0; k < ours_rows.size(); ++k)
    EXPECT_EQ(metrics.cell(ours_rows[k], "frame"), std::to_string(k));
  const auto wild_rows = metrics.rows_of("solver", "wild");
  EXPECT_GE(wild_rows.size(), 1u);
  EXPECT_LT(wild_rows.size(), static_cast<std::size_t>(kFrames + 1));
  // The comparison stops with the unstable solver.
  EXPECT_LE(read_csv(out / "compare.csv").rows.size(), wild_rows.size());
}

// ---------------------------------------------------------------------------------------------
// validate

TEST_F(Cli, ValidateGoodSceneIsExit0AndWritesNothing) {
  const fs::path file = scene("small.yaml", kSmall);
  const auto result = run_drapelab({"validate", file.string()});
  EXPECT_EQ(result.exit_code, 0) << all_output(result);
  EXPECT_NE(result.output.find("ok"), std::string::npos) << result.output;
  std::size_t entries = 0;
  for (const auto& entry : fs::directory_iterator(dir())) {
    (void)entry;
    ++entries;
  }
  EXPECT_EQ(entries, 1u) << "validate writes no file";
}

TEST_F(Cli, ValidateBadSceneIsExit2WithFileAndLine) {
  std::string bad = kSmall;
  bad.replace(bad.find("resolution: [9, 9]"), 18, "resolution: [9]");  // line 7
  const fs::path file = scene("bad.yaml", bad);
  const auto result = run_drapelab({"validate", file.string()});
  EXPECT_EQ(result.exit_code, 2) << all_output(result);
  EXPECT_NE(result.output.find(file.string() + ":7:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("cloth.resolution"), std::string::npos) << result.output;

  const auto bad_set =
      run_drapelab({"validate", scene("good.yaml", kSmall).string(), "--set", "duration=-1"});
  EXPECT_EQ(bad_set.exit_code, 2) << all_output(bad_set);
  EXPECT_NE(bad_set.output.find("--set duration=-1"), std::string::npos) << bad_set.output;
}

// validate states the cloth model; for the continuum, its parameters and its elements.
TEST_F(Cli, ValidateStatesTheClothModel) {
  const auto springs = run_drapelab({"validate", scene("small.yaml", kSmall).string()});
  EXPECT_EQ(springs.exit_code, 0) << all_output(springs);
  EXPECT_NE(springs.output.find("cloth model: springs"), std::string::npos) << springs.output;

  std::string text = kSmall;  // lines 10 to 13, the springs, become the continuum's keys
  const std::size_t first = text.find("  springs:"), last = text.find("  pins:");
  text.replace(first, last - first,
               "  model: continuum\n"
               "  continuum: {stretch_modulus: 400, poisson: 0.25, bending_rigidity: 2e-5, "
               "damping: 0.005}\n");
  const fs::path file = scene("membrane.yaml", text);
  const auto continuum = run_drapelab({"validate", file.string()});
  EXPECT_EQ(continuum.exit_code, 0) << all_output(continuum);
  // 2 x 8 x 8 triangles; a hinge on each of the 8 x 9 + 9 x 8 + 64 - 4 x 8 = 176 interior edges.
  EXPECT_NE(continuum.output.find("cloth model: continuum (stretch modulus 400 N/m, Poisson ratio "
                                  "0.25, bending rigidity 2e-05 N*m, damping 0.005 s): " +
                                  std::to_string(kTriangles) + " membrane triangles, 176 hinges"),
            std::string::npos)
      << continuum.output;

  const auto bad =
      run_drapelab({"validate", file.string(), "--set", "cloth.continuum.poisson=0.5"});
  EXPECT_EQ(bad.exit_code, 2) << all_output(bad);
  EXPECT_NE(bad.output.find("--set cloth.continuum.poisson=0.5: cloth.continuum.poisson must be < "
                            "0.5"),
            std::string::npos)
      << bad.output;
}

TEST_F(Cli, ValidatePrintResolvedGivesALoadableScene) {
  const fs::path file = scene("small.yaml", kSmall);
  const auto result =
      run_drapelab({"validate", file.string(), "--print-resolved", "--set", "seed=11"});
  ASSERT_EQ(result.exit_code, 0) << all_output(result);
  EXPECT_NE(result.output.find("seed: 11"), std::string::npos) << result.output;
  const fs::path printed = scene("printed.yaml", result.output);
  const auto again = run_drapelab({"validate", printed.string()});
  EXPECT_EQ(again.exit_code, 0) << all_output(again);
}

}  // namespace
