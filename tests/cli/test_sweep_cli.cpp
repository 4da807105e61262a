// `drapelab sweep` end to end on a tiny scene written by the tests: every combination once, in
// odometer order, failed runs as rows, unknown keys refused before anything runs, the same table
// whatever --jobs, Ctrl-C (its parts alone: test_sweep_plan.cpp).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "fixtures/cli.hpp"
#include "fixtures/sweep_scene.hpp"

namespace {

namespace fs = std::filesystem;
using drapelab::fixtures::interrupt_drapelab_when;
using drapelab::fixtures::kSweepSheet;
using drapelab::fixtures::kSweepUnstableDt;
using drapelab::fixtures::read_text;
using drapelab::fixtures::run_drapelab;
using drapelab::fixtures::staged_file;
using drapelab::fixtures::write_text;

// RFC 4180 CSV: quoted cells may hold commas and doubled quotes (sweep.csv's message and values).
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string cell;
  bool quoted = false;
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (quoted) {
      if (c == '"' && k + 1 < text.size() && text[k + 1] == '"') {
        cell += '"';
        ++k;
      } else if (c == '"') {
        quoted = false;
      } else {
        cell += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      row.push_back(cell);
      cell.clear();
    } else if (c == '\n') {
      row.push_back(cell);
      cell.clear();
      rows.push_back(row);
      row.clear();
    } else {
      cell += c;
    }
  }
  EXPECT_FALSE(quoted) << "a quoted cell is left open";
  EXPECT_TRUE(cell.empty() && row.empty()) << "the last row has no line end";
  return rows;
}

// sweep.csv as a header and rows of column -> cell.
struct Table {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
};

Table read_table(const fs::path& file) {
  const auto records = parse_csv(read_text(file));
  Table table;
  if (records.empty()) return table;
  table.header = records.front();
  for (std::size_t r = 1; r < records.size(); ++r) {
    EXPECT_EQ(records[r].size(), table.header.size()) << "row " << r << " of " << file;
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < table.header.size() && c < records[r].size(); ++c)
      row[table.header[c]] = records[r][c];
    table.rows.push_back(row);
  }
  return table;
}

class SweepCli : public drapelab::fixtures::TempDirTest {
 protected:
  fs::path scene() {
    const fs::path path = dir() / "sheet.yaml";
    if (!fs::exists(path)) write_text(path, kSweepSheet);
    return path;
  }
};

TEST_F(SweepCli, RunsEveryCombinationOnceInOdometerOrder) {
  const fs::path out = dir() / "sweep";
  const auto result =
      run_drapelab({"sweep", scene().string(), "--vary", "cloth.springs.bend.ks=1,10", "--vary",
                    "cloth.resolution=[5,5],[3,3],[4,4]", "--out", out.string(), "--jobs", "2"});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const Table table = read_table(out / "sweep.csv");
  const std::vector<std::string> leading{"combination",
                                         "cloth.springs.bend.ks",
                                         "cloth.resolution",
                                         "solver",
                                         "type",
                                         "status",
                                         "exit_code",
                                         "message"};
  ASSERT_GE(table.header.size(), leading.size());
  EXPECT_TRUE(std::equal(leading.begin(), leading.end(), table.header.begin()));
  for (const char* column :
       {"max_stretch", "projected_area", "settle_time", "ms_per_step", "run_folder"})
    EXPECT_NE(std::find(table.header.begin(), table.header.end(), column), table.header.end())
        << column;
  // The last key changes fastest.
  const std::vector<std::pair<double, int>> expected{{1, 5},  {1, 3},  {1, 4},
                                                     {10, 5}, {10, 3}, {10, 4}};
  ASSERT_EQ(table.rows.size(), expected.size()) << read_text(out / "sweep.csv");
  std::set<std::string> folders;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const auto& row = table.rows[k];
    EXPECT_EQ(row.at("combination"), std::to_string(k));
    EXPECT_EQ(std::stod(row.at("cloth.springs.bend.ks")), expected[k].first);
    const std::string side = std::to_string(expected[k].second);
    EXPECT_EQ(row.at("cloth.resolution"), "[" + side + "," + side + "]");
    EXPECT_EQ(row.at("solver"), "ours");
    EXPECT_EQ(row.at("type"), "spring_damper");
    EXPECT_EQ(row.at("status"), "ok");
    EXPECT_EQ(row.at("exit_code"), "0");
    EXPECT_FALSE(row.at("max_stretch").empty());
    // Each run folder is a whole `drapelab run` of exactly this combination.
    const fs::path run = out / row.at("run_folder");
    EXPECT_EQ(row.at("run_folder").rfind("runs/00" + std::to_string(k) + "_", 0), 0u)
        << row.at("run_folder");
    EXPECT_TRUE(folders.insert(row.at("run_folder")).second);
    ASSERT_TRUE(fs::exists(run / "summary.json")) << run;
    const auto summary = nlohmann::json::parse(read_text(run / "summary.json"));
    EXPECT_EQ(summary["model"]["particles"].get<int>(), expected[k].second * expected[k].second);
    const YAML::Node resolved = YAML::LoadFile((run / "resolved.yaml").string());
    EXPECT_EQ(resolved["cloth"]["springs"]["bend"]["ks"].as<double>(), expected[k].first);
    EXPECT_EQ(resolved["cloth"]["resolution"][0].as<int>(), expected[k].second);
    EXPECT_EQ(resolved["cloth"]["resolution"][1].as<int>(), expected[k].second);
  }
  const auto sweep = nlohmann::json::parse(read_text(out / "sweep.json"));
  EXPECT_EQ(sweep["state"], "complete");
  ASSERT_EQ(sweep["varied"].size(), 2u);
  EXPECT_EQ(sweep["varied"][1]["key"], "cloth.resolution");
  EXPECT_EQ(sweep["varied"][1]["values"], nlohmann::json({"[5,5]", "[3,3]", "[4,4]"}));
  ASSERT_EQ(sweep["combinations"].size(), 6u);
  for (const auto& c : sweep["combinations"]) EXPECT_EQ(c["status"], "ok");
  EXPECT_NE(result.output.find((out / "sweep.csv").string()), std::string::npos) << result.output;
}

TEST_F(SweepCli, FailedRunsAreRowsAndExitOne) {
  const fs::path out = dir() / "sweep";
  // ks = -1 is out of range (bad input, refused before running); dt = 1/60 s blows up (unstable).
  const auto result = run_drapelab(
      {"sweep", scene().string(), "--vary", "cloth.springs.bend.ks=1,-1", "--vary",
       "solvers.0.dt=0.00026041666666666666," + kSweepUnstableDt, "--out", out.string()});
  EXPECT_EQ(result.exit_code, 1) << result.output;
  const Table table = read_table(out / "sweep.csv");
  ASSERT_EQ(table.rows.size(), 4u) << read_text(out / "sweep.csv");
  EXPECT_EQ(table.rows[0].at("status"), "ok");
  EXPECT_EQ(table.rows[1].at("status"), "unstable");
  EXPECT_EQ(table.rows[1].at("solver"), "ours");
  EXPECT_EQ(table.rows[1].at("exit_code"), "1");
  EXPECT_FALSE(table.rows[1].at("message").empty());
  for (const std::size_t k : {2u, 3u}) {
    const auto& row = table.rows[k];
    EXPECT_EQ(row.at("combination"), std::to_string(k));
    EXPECT_EQ(row.at("status"), "bad_input");
    EXPECT_EQ(row.at("solver"), "");
    EXPECT_EQ(row.at("exit_code"), "2");
    EXPECT_NE(row.at("message").find("cloth.springs.bend.ks"), std::string::npos)
        << row.at("message");
    EXPECT_NE(row.at("message").find("-1"), std::string::npos) << row.at("message");
  }
  const auto sweep = nlohmann::json::parse(read_text(out / "sweep.json"));
  EXPECT_EQ(sweep["combinations"][1]["status"], "unstable");
  EXPECT_EQ(sweep["combinations"][3]["status"], "bad_input");
}

TEST_F(SweepCli, UnknownKeyExitsTwoBeforeAnyRun) {
  for (const std::string key : {"cloth.sprngs.bend.ks", "cloth.springs.bend.kz", "solvers.4.dt"}) {
    const fs::path out = dir() / "never";
    const auto result = run_drapelab({"sweep", scene().string(), "--vary", key + "=1,2", "--vary",
                                      "duration=0.05", "--out", out.string()});
    EXPECT_EQ(result.exit_code, 2) << key << ": " << result.output;
    EXPECT_NE(result.output.find("--vary " + key), std::string::npos) << result.output;
    EXPECT_FALSE(fs::exists(out)) << "nothing is written for " << key;
  }
  // Bad arguments: an open bracket, an empty value, a key both set and varied.
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--vary", "cloth.resolution=[5,5"},
        {"--vary", "duration=0.1,,0.2"},
        {"--vary", "duration=0.1", "--set", "duration=0.2"}}) {
    std::vector<std::string> arguments{"sweep", scene().string(), "--out",
                                       (dir() / "never").string()};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    const auto result = run_drapelab(arguments);
    EXPECT_EQ(result.exit_code, 2) << result.output;
    EXPECT_FALSE(fs::exists(dir() / "never"));
  }
}

TEST_F(SweepCli, SameTableWhateverTheJobCount) {
  std::map<int, Table> tables;
  for (const int jobs : {1, 2}) {
    const fs::path out = dir() / ("jobs" + std::to_string(jobs));
    const auto result =
        run_drapelab({"sweep", scene().string(), "--vary", "cloth.springs.stretch.ks=50,100,200",
                      "--vary", "solvers.0.dt=0.00026041666666666666," + kSweepUnstableDt, "--out",
                      out.string(), "--jobs", std::to_string(jobs)});
    EXPECT_EQ(result.exit_code, 1) << result.output;  // the unstable rows
    tables[jobs] = read_table(out / "sweep.csv");
  }
  ASSERT_EQ(tables[1].header, tables[2].header);
  ASSERT_EQ(tables[1].rows.size(), 6u);
  ASSERT_EQ(tables[2].rows.size(), 6u);
  std::size_t unstable = 0;
  for (std::size_t r = 0; r < 6; ++r) {
    for (const auto& column : tables[1].header) {
      if (column == "ms_per_step" || column == "wall_seconds_per_simulated_second")
        continue;  // wall clock
      EXPECT_EQ(tables[1].rows[r].at(column), tables[2].rows[r].at(column))
          << "row " << r << " " << column;
    }
    unstable += tables[1].rows[r].at("status") == "unstable";
  }
  EXPECT_EQ(unstable, 3u);
}

TEST_F(SweepCli, ForceReplacesAPreviousSweep) {
  const fs::path out = dir() / "sweep";
  const std::vector<std::string> arguments{"sweep",         scene().string(), "--vary",
                                           "duration=0.05", "--out",          out.string()};
  ASSERT_EQ(run_drapelab(arguments).exit_code, 0);
  const auto again = run_drapelab(arguments);
  EXPECT_EQ(again.exit_code, 2) << again.output;
  EXPECT_NE(again.output.find("--force"), std::string::npos) << again.output;
  auto forced = arguments;
  forced.push_back("--force");
  EXPECT_EQ(run_drapelab(forced).exit_code, 0);
  EXPECT_EQ(read_table(out / "sweep.csv").rows.size(), 1u);
}

TEST_F(SweepCli, ForceKeepsFilesTheSweepDidNotWrite) {
  const fs::path out = dir() / "sweep";
  const std::vector<std::string> arguments{"sweep", scene().string(), "--vary", "duration=0.05,0.1",
                                           "--out", out.string()};
  ASSERT_EQ(run_drapelab(arguments).exit_code, 0);
  const fs::path first_run = out / "runs" / "000_duration=0.05";
  ASSERT_TRUE(fs::is_regular_file(first_run / "metrics.csv"));
  write_text(out / "runs" / "notes.txt", "mine");
  write_text(first_run / "plot.py", "mine too");
  // A narrower sweep: the second run's folder goes, the user's files stay.
  auto forced = std::vector<std::string>{"sweep", scene().string(), "--vary", "duration=0.05",
                                         "--out", out.string(),     "--force"};
  const auto again = run_drapelab(forced);
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(read_text(out / "runs" / "notes.txt"), "mine");
  EXPECT_EQ(read_text(first_run / "plot.py"), "mine too");
  EXPECT_TRUE(fs::is_regular_file(first_run / "metrics.csv"));
  EXPECT_FALSE(fs::exists(out / "runs" / "001_duration=0.1"));
  EXPECT_EQ(read_table(out / "sweep.csv").rows.size(), 1u);
}

TEST_F(SweepCli, CtrlCStopsTheRunsAndKeepsTheTableValid) {
  // Runs of 600 s, two at a time: Ctrl-C arrives while both run and the third waits.
  const fs::path out = dir() / "sweep";
  // Interrupted once both runs have written frames (the sweep only, not its children).
  const auto frames_written = [&] {
    std::size_t running = 0;
    std::error_code ec;
    if (!fs::is_directory(out / "runs", ec)) return false;
    for (const auto& entry : fs::directory_iterator(out / "runs", ec)) {
      if (!entry.is_directory()) continue;
      const fs::path metrics = staged_file(entry.path(), "metrics.csv");  // the run's, as it runs
      std::error_code size_error;
      if (!metrics.empty() && fs::exists(metrics) && fs::file_size(metrics, size_error) > 2000)
        ++running;
    }
    return running == 2;
  };
  EXPECT_EQ(interrupt_drapelab_when({"sweep", scene().string(), "--vary", "duration=600,601,602",
                                     "--jobs", "2", "--out", out.string()},
                                    frames_written),
            130);
  const Table table = read_table(out / "sweep.csv");
  ASSERT_EQ(table.rows.size(), 2u);
  for (const auto& row : table.rows) {
    EXPECT_EQ(row.at("status"), "interrupted");
    EXPECT_EQ(row.at("exit_code"), "130");  // each child stopped itself cleanly after SIGINT
    const auto summary =
        nlohmann::json::parse(read_text(out / row.at("run_folder") / "summary.json"));
    EXPECT_EQ(summary["run"]["state"], "interrupted");
  }
  const auto sweep = nlohmann::json::parse(read_text(out / "sweep.json"));
  EXPECT_EQ(sweep["state"], "interrupted");
  EXPECT_EQ(sweep["combinations"][2]["status"], "not_run");
  EXPECT_FALSE(fs::exists(out / "runs" / "002_duration=602"));
}

// The ids of the processes whose parent is `parent` (from /proc/PID/stat: "pid (name) state ppid").
std::vector<pid_t> children_of(pid_t parent) {
  std::vector<pid_t> children;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "stat");
    std::string stat;
    std::getline(in, stat);
    const auto close = stat.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(stat.substr(close + 1));
    char state = 0;
    long ppid = 0;
    if (rest >> state >> ppid && ppid == parent)
      children.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return children;
}

TEST_F(SweepCli, ACrashedRunIsARowAndTheSweepGoesOn) {
  // One run at a time: the first (600 s) is killed from outside with SIGKILL, as a crash or the
  // out-of-memory killer would; the second (0.05 s) still runs.
  const fs::path out = dir() / "sweep";
  const pid_t sweep = ::fork();
  ASSERT_GE(sweep, 0);
  if (sweep == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(DRAPELAB_EXE, DRAPELAB_EXE, "sweep", scene().c_str(), "--vary", "duration=600,0.05",
            "--jobs", "1", "--out", out.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const fs::path first_run = out / "runs" / "000_duration=600";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::vector<pid_t> runs;
  while (std::chrono::steady_clock::now() < deadline) {
    runs = children_of(sweep);
    std::error_code ec;
    const fs::path first_metrics = staged_file(first_run, "metrics.csv");  // while it runs
    if (runs.size() == 1 && !first_metrics.empty() && fs::exists(first_metrics, ec) &&
        fs::file_size(first_metrics, ec) > 2000)
      break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_EQ(runs.size(), 1u) << "the sweep's one running child";
  ASSERT_EQ(::kill(runs.front(), SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(sweep, &status, 0), sweep);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const Table table = read_table(out / "sweep.csv");
  ASSERT_EQ(table.rows.size(), 2u) << read_text(out / "sweep.csv");
  EXPECT_EQ(table.rows[0].at("status"), "crashed");
  EXPECT_EQ(table.rows[0].at("solver"), "");
  EXPECT_EQ(table.rows[0].at("exit_code"), "");
  EXPECT_NE(table.rows[0].at("message").find("signal 9"), std::string::npos)
      << table.rows[0].at("message");
  EXPECT_EQ(table.rows[1].at("status"), "ok");
  EXPECT_EQ(table.rows[1].at("solver"), "ours");
}

}  // namespace
