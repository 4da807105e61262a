// drapelab sweep --engine slurm on a one-node Slurm cluster (tools/slurm-local.sh): the same
// sweep.csv as a local sweep but for the cost columns; a crashed task, a Ctrl-C (scancel) and an
// outside scancel each leave a row per combination and valid files; --force is refused while the
// job runs; a refused submission leaves nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "drapelab/run_folder/csv.hpp"
#include "drapelab/sweep/files.hpp"
#include "fixtures/cli.hpp"
#include "fixtures/sweep_scene.hpp"

namespace {

namespace fs = std::filesystem;
using drapelab::fixtures::CommandResult;
using drapelab::fixtures::interrupt_drapelab_when;
using drapelab::fixtures::kSweepSheet;
using drapelab::fixtures::read_text;
using drapelab::fixtures::run_drapelab;
using drapelab::fixtures::staged_file;
using drapelab::fixtures::write_text;
using drapelab::run_folder::CsvTable;
using drapelab::run_folder::parse_csv;

// A shell command's output, stderr included.
CommandResult run_shell(const std::string& command) {
  return drapelab::fixtures::run_shell(command + " 2>&1");
}

nlohmann::json read_json(const fs::path& file) { return nlohmann::json::parse(read_text(file)); }

// The same sheet with one of Bullet's cloths beside ours: the rows of two solvers per combination.
std::string two_solver_sheet() {
  return kSweepSheet + "  - {name: classic, type: bullet_softbody}\n";
}

// Every cell of sweep.csv but the cost columns (they differ from machine to machine).
std::vector<std::vector<std::string>> without_costs(const CsvTable& table) {
  const auto& timing = drapelab::sweep::sweep_timing_columns();
  std::vector<std::vector<std::string>> kept;
  for (const auto& row : table.rows) {
    std::vector<std::string> cells;
    for (std::size_t c = 0; c < table.header.size(); ++c)
      if (std::find(timing.begin(), timing.end(), table.header[c]) == timing.end())
        cells.push_back(table.header[c] + "=" + row[c]);
    kept.push_back(cells);
  }
  return kept;
}

CsvTable read_sweep_table(const fs::path& sweep) {
  const CsvTable table = parse_csv(read_text(sweep / "sweep.csv"));
  EXPECT_FALSE(table.header.empty()) << sweep / "sweep.csv";
  return table;
}

std::string cell(const CsvTable& table, std::size_t row, const std::string& column) {
  return table.text(row, table.column(column));
}

// The process id of the `drapelab run` writing into `folder` (its --out argument), or 0.
pid_t run_process(const fs::path& folder) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "cmdline");
    std::string argument;
    std::vector<std::string> arguments;
    while (std::getline(in, argument, '\0')) arguments.push_back(argument);
    if (arguments.size() < 4 || arguments[1] != "run") continue;
    for (const auto& a : arguments)
      if (a == folder.string()) return static_cast<pid_t>(std::stol(name));
  }
  return 0;
}

// Waits until `ready` holds (true) or `seconds` pass (false).
bool wait_until(const std::function<bool()>& ready, int seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

// Task `folder_part`'s run is stepping: its staged metrics.csv holds a few frames.
bool run_is_stepping(const fs::path& sweep, const std::string& folder) {
  std::error_code ec;
  const fs::path metrics = staged_file(sweep / "runs" / folder, "metrics.csv");
  return !metrics.empty() && fs::exists(metrics, ec) && fs::file_size(metrics, ec) > 2000;
}

class SlurmSweep : public drapelab::fixtures::TempDirTest {
 protected:
  // The cluster: started by the suite's CTest fixture (slurm.cluster_start); started here too when
  // the suite runs alone (the script does nothing when it is running already).
  static void SetUpTestSuite() {
    const CommandResult started = run_shell(std::string("bash ") + DRAPELAB_SLURM_LOCAL + " start");
    const auto line = started.output.find("export SLURM_CONF=");
    if (started.exit_code != 0 || line == std::string::npos) {
      cluster_problem_ = "tools/slurm-local.sh start failed (exit code " +
                         std::to_string(started.exit_code) + "):\n" + started.output;
      return;
    }
    const auto begin = line + std::string("export SLURM_CONF=").size();
    const std::string conf = started.output.substr(begin, started.output.find('\n', begin) - begin);
    ::setenv("SLURM_CONF", conf.c_str(), 1);
  }

  void SetUp() override {
    TempDirTest::SetUp();
    ASSERT_TRUE(cluster_problem_.empty()) << cluster_problem_;
  }

  fs::path scene(const std::string& text = kSweepSheet) {
    const fs::path path = dir() / "sheet.yaml";
    write_text(path, text);
    return path;
  }

  static std::string job_of(const fs::path& sweep) {
    return read_json(sweep / "sweep.json").at("slurm_job").get<std::string>();
  }

  static void expect_job_gone(const std::string& job) {
    const CommandResult queue = run_shell("squeue --noheader --array --jobs=" + job);
    EXPECT_TRUE(queue.output.empty() || queue.output.find("Invalid job id") != std::string::npos)
        << queue.output;
  }

  static inline std::string cluster_problem_;
};

TEST_F(SlurmSweep, GivesTheLocalSweepCsvButForTheCostColumns) {
  const fs::path sheet = scene(two_solver_sheet());
  const std::vector<std::string> sweep{"sweep",  sheet.string(),
                                       "--vary", "cloth.springs.bend.ks=0.5,2",
                                       "--vary", "cloth.springs.stretch.kd=0.05,0.2"};
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> all = sweep;
    all.insert(all.end(), more.begin(), more.end());
    return all;
  };
  const CommandResult local = run_drapelab(with({"--out", (dir() / "local").string()}));
  ASSERT_EQ(local.exit_code, 0) << local.output;
  const CommandResult slurm =
      run_drapelab(with({"--out", (dir() / "slurm").string(), "--engine", "slurm"}));
  ASSERT_EQ(slurm.exit_code, 0) << slurm.output;
  EXPECT_NE(slurm.output.find("submitted Slurm job"), std::string::npos) << slurm.output;

  const CsvTable local_table = read_sweep_table(dir() / "local");
  const CsvTable slurm_table = read_sweep_table(dir() / "slurm");
  ASSERT_EQ(slurm_table.rows.size(), 8u);  // 2 x 2 combinations x 2 solvers
  EXPECT_EQ(slurm_table.header, local_table.header);
  EXPECT_EQ(without_costs(slurm_table), without_costs(local_table));
  // The cost columns hold measured times in both.
  EXPECT_FALSE(cell(slurm_table, 0, "ms_per_step").empty());

  const auto record = read_json(dir() / "slurm" / "sweep.json");
  EXPECT_EQ(record.at("engine"), "slurm");
  EXPECT_EQ(record.at("state"), "complete");
  EXPECT_EQ(record.at("combinations_ok"), 4);
  EXPECT_EQ(read_json(dir() / "local" / "sweep.json").at("engine"), "local");
  // Each task's status file, and the run folders a local sweep writes.
  for (int task = 0; task < 4; ++task)
    EXPECT_TRUE(fs::exists(dir() / "slurm" / "slurm" / "status" / (std::to_string(task) + ".txt")));
  EXPECT_TRUE(fs::exists(dir() / "slurm" / "runs" /
                         "000_cloth.springs.bend.ks=0.5_cloth.springs.stretch.kd=0.05" /
                         "metrics.csv"));
  expect_job_gone(job_of(dir() / "slurm"));
}

TEST_F(SlurmSweep, ACrashedTaskIsARowAndDetachedSweepsAreCollected) {
  // One task at a time (--jobs 1): the first (600 s) is killed with SIGKILL, as a crash or the
  // out-of-memory killer would; the second (0.05 s) still runs.
  const fs::path out = dir() / "sweep";
  const CommandResult submitted =
      run_drapelab({"sweep", scene().string(), "--vary", "duration=600,0.05", "--jobs", "1",
                    "--out", out.string(), "--engine", "slurm", "--detach"});
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  EXPECT_NE(submitted.output.find("drapelab sweep --collect"), std::string::npos);
  EXPECT_EQ(read_json(out / "sweep.json").at("state"), "submitted");
  ASSERT_TRUE(wait_until([&] { return run_is_stepping(out, "000_duration=600"); }, 60))
      << "the first task never started";
  // While its tasks run, --force may not replace the sweep (they would write into the new one).
  const CommandResult forced = run_drapelab(
      {"sweep", scene().string(), "--vary", "duration=0.05", "--out", out.string(), "--force"});
  EXPECT_EQ(forced.exit_code, 2) << forced.output;
  EXPECT_NE(forced.output.find("before --force"), std::string::npos) << forced.output;

  // The full path: another test's sweep may run a folder of the same name at the same time.
  const pid_t run = run_process(out / "runs" / "000_duration=600");
  ASSERT_GT(run, 0);
  ASSERT_EQ(::kill(run, SIGKILL), 0);

  const CommandResult collected = run_drapelab({"sweep", "--collect", out.string()});
  EXPECT_EQ(collected.exit_code, 1) << collected.output;
  const CsvTable table = read_sweep_table(out);
  ASSERT_EQ(table.rows.size(), 2u) << read_text(out / "sweep.csv");
  EXPECT_EQ(cell(table, 0, "status"), "crashed");
  EXPECT_EQ(cell(table, 0, "exit_code"), "");
  EXPECT_NE(cell(table, 0, "message").find("signal 9"), std::string::npos)
      << cell(table, 0, "message");
  EXPECT_EQ(cell(table, 1, "status"), "ok");
  EXPECT_EQ(cell(table, 1, "solver"), "ours");
  EXPECT_EQ(read_json(out / "sweep.json").at("state"), "complete");
  expect_job_gone(job_of(out));
}

TEST_F(SlurmSweep, CtrlCCancelsTheArrayAndEveryCombinationIsARow) {
  // One task at a time: the first runs when Ctrl-C comes, the other two wait in the queue.
  const fs::path out = dir() / "sweep";
  const int status = interrupt_drapelab_when(
      {"sweep", scene().string(), "--vary", "duration=600,601,602", "--jobs", "1", "--out",
       out.string(), "--engine", "slurm"},
      [&] { return run_is_stepping(out, "000_duration=600"); }, std::chrono::seconds(60));
  EXPECT_EQ(status, 130);
  const CsvTable table = read_sweep_table(out);
  ASSERT_EQ(table.rows.size(), 3u) << read_text(out / "sweep.csv");
  EXPECT_EQ(cell(table, 0, "status"), "interrupted") << cell(table, 0, "message");
  EXPECT_EQ(cell(table, 0, "exit_code"), "130");
  for (std::size_t row = 1; row < 3; ++row) {
    EXPECT_EQ(cell(table, row, "status"), "cancelled");
    EXPECT_NE(cell(table, row, "message").find("scancel"), std::string::npos);
  }
  const auto record = read_json(out / "sweep.json");
  EXPECT_EQ(record.at("state"), "interrupted");
  // The interrupted run's folder is whole: summary.json says so, and metrics.csv ends on a row.
  const fs::path run = out / "runs" / "000_duration=600";
  EXPECT_EQ(read_json(run / "summary.json").at("run").at("state"), "interrupted");
  const std::string metrics = read_text(run / "metrics.csv");
  ASSERT_FALSE(metrics.empty());
  EXPECT_EQ(metrics.back(), '\n');
  const auto lines = drapelab::fixtures::split_lines(metrics);
  EXPECT_GE(lines.size(), 3u);  // the header and frames 0 and 1 at least
  const auto commas = [](const std::string& line) {
    return std::count(line.begin(), line.end(), ',');
  };
  for (const auto& line : lines) EXPECT_EQ(commas(line), commas(lines.front())) << line;
  expect_job_gone(job_of(out));
}

TEST_F(SlurmSweep, AnOutsideScancelLeavesValidFilesAndARowPerCombination) {
  const fs::path out = dir() / "sweep";
  const CommandResult submitted =
      run_drapelab({"sweep", scene().string(), "--vary", "duration=600,601", "--jobs", "1", "--out",
                    out.string(), "--engine", "slurm", "--detach"});
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  ASSERT_TRUE(wait_until([&] { return run_is_stepping(out, "000_duration=600"); }, 60));
  const std::string job = job_of(out);
  const CommandResult cancelled = run_shell("scancel " + job);
  ASSERT_EQ(cancelled.exit_code, 0) << cancelled.output;

  // The second task never ran and wrote no status: it is lost once --lost-after has passed.
  const CommandResult collected =
      run_drapelab({"sweep", "--collect", out.string(), "--lost-after", "3"});
  EXPECT_EQ(collected.exit_code, 1) << collected.output;
  const CsvTable table = read_sweep_table(out);
  ASSERT_EQ(table.rows.size(), 2u) << read_text(out / "sweep.csv");
  EXPECT_EQ(cell(table, 0, "status"), "interrupted");
  EXPECT_NE(cell(table, 0, "message").find("Slurm stopped the task"), std::string::npos)
      << cell(table, 0, "message");
  EXPECT_EQ(cell(table, 1, "status"), "lost");
  const fs::path run = out / "runs" / "000_duration=600";
  EXPECT_EQ(read_json(run / "summary.json").at("run").at("state"), "interrupted");
  EXPECT_EQ(read_json(out / "sweep.json").at("state"), "complete");
}

TEST_F(SlurmSweep, ARefusedSubmissionLeavesNothing) {
  const fs::path out = dir() / "sweep";
  const CommandResult refused =
      run_drapelab({"sweep", scene().string(), "--vary", "duration=0.05,0.1", "--out", out.string(),
                    "--engine", "slurm", "--partition", "no_such_partition"});
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("sbatch"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("nothing was run"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(out / "sweep.csv"));
  EXPECT_FALSE(fs::exists(out / "sweep.json"));
  EXPECT_FALSE(fs::exists(out / "slurm"));
}

TEST_F(SlurmSweep, WithoutSlurmOnPathNothingIsWritten) {
  const fs::path out = dir() / "sweep";
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", "/nonexistent", 1);
  const CommandResult refused =
      run_drapelab({"sweep", scene().string(), "--vary", "duration=0.05,0.1", "--out", out.string(),
                    "--engine", "slurm"});
  ::setenv("PATH", path.c_str(), 1);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("needs Slurm's sbatch on PATH"), std::string::npos)
      << refused.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(SlurmSweep, SlurmOptionsNeedTheSlurmEngine) {
  const CommandResult refused =
      run_drapelab({"sweep", scene().string(), "--vary", "duration=0.05", "--out",
                    (dir() / "sweep").string(), "--partition", "short"});
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("need --engine slurm"), std::string::npos) << refused.output;
  const CommandResult not_slurm = run_drapelab({"sweep", "--collect", dir().string()});
  EXPECT_EQ(not_slurm.exit_code, 2) << not_slurm.output;
  EXPECT_NE(not_slurm.output.find("submission.json is missing"), std::string::npos);
}

}  // namespace
