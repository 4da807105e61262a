// A run folder never loses results: a run writes into a staging folder and moves in when it ends,
// --force touches only drapelab's own files (the manifest's), a second writer is refused, and a
// write error (a full disk, here a file size limit) stops the run on its last whole frame.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fixtures/cli.hpp"

namespace drapelab {
namespace {

using namespace fixtures;  // fixtures/cli.hpp

namespace fs = std::filesystem;

// A sheet that runs in well under a second per 0.1 s of simulated time.
// A finer sheet takes a smaller step: 64 per frame keeps 33 x 33 particles below the stable step.
std::string sheet_scene(double duration, int resolution = 9) {
  const std::string n = std::to_string(resolution);
  return "name: safety_sheet\nduration: " + std::to_string(duration) +
         "\nframe_rate: 60\nseed: 3\n"
         "cloth: {size: [0.4, 0.4], resolution: [" +
         n + ", " + n +
         "], mass: 0.1, plane: xy, pins: [top_corners],\n"
         "        springs: {stretch: {ks: 400, kd: 0.01}, shear: {ks: 40, kd: 0.005},\n"
         "                  bend: {ks: 4, kd: 0.0005}}}\n"
         "solvers: [{name: ours, dt: " +
         std::string(resolution > 9 ? "0.000260416666666666667" : "0.00104166666666666667") +
         "}]\n";
}

std::size_t count_file_lines(const fs::path& path) {
  std::error_code error;
  if (path.empty() || !fs::exists(path, error)) return 0;
  const std::string text = read_text(path);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// Data rows of a CSV file that must end on a whole row, each with the header's number of cells.
std::size_t count_whole_rows(const fs::path& path) {
  const std::string text = read_text(path);
  EXPECT_FALSE(text.empty()) << path;
  if (text.empty()) return 0;
  EXPECT_EQ(text.back(), '\n') << path << " ends inside a row";
  const std::vector<std::string> rows = split_lines(text);
  const std::size_t columns = split_csv(rows.front()).size();
  for (const auto& row : rows) EXPECT_EQ(split_csv(row).size(), columns) << path << ": " << row;
  return rows.size() - 1;
}

std::vector<std::string> files_ending_with(const fs::path& folder, const std::string& suffix) {
  std::vector<std::string> found;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.size() >= suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      found.push_back(entry.path().string());
  }
  return found;
}

class RunFolderSafety : public TempDirTest {
 protected:
  fs::path scene(const std::string& name, const std::string& text) {
    write_text(dir() / name, text);
    return dir() / name;
  }
};

TEST_F(RunFolderSafety, ForceKeepsEveryFileDrapelabDidNotWrite) {
  const fs::path out = dir() / "out";
  fs::create_directories(out / "meshes");
  fs::create_directories(out / "render");
  write_text(out / "notes.txt", "mine");
  write_text(out / "meshes" / "sculpt.obj", "mine too");
  write_text(out / "render" / "poster.png", "and mine");
  const fs::path file = scene("sheet.yaml", sheet_scene(0.05));

  const auto first =
      run_drapelab({"run", file.string(), "--out", out.string(), "--force", "--meshes", "both"});
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_TRUE(fs::is_regular_file(out / "meshes" / "ours_0003.obj"));
  EXPECT_TRUE(fs::is_regular_file(out / "meshes" / "ours.pc2"));

  // A different run without meshes: the first run's meshes go, the user's files stay.
  const auto second = run_drapelab(
      {"run", file.string(), "--out", out.string(), "--force", "--set", "cloth.mass=0.2"});
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_EQ(read_text(out / "notes.txt"), "mine");
  EXPECT_EQ(read_text(out / "meshes" / "sculpt.obj"), "mine too");
  EXPECT_EQ(read_text(out / "render" / "poster.png"), "and mine");
  EXPECT_FALSE(fs::exists(out / "meshes" / "ours_0003.obj"));
  EXPECT_FALSE(fs::exists(out / "meshes" / "ours.pc2"));
  EXPECT_NE(read_text(out / "resolved.yaml").find("mass: 0.2"), std::string::npos);
  // Nothing of the transaction is left but its manifest.
  EXPECT_TRUE(fs::is_regular_file(out / ".drapelab-manifest"));
  EXPECT_FALSE(fs::exists(out / ".drapelab.lock"));
  EXPECT_TRUE(staged_file(out, "metrics.csv").empty());
}

TEST_F(RunFolderSafety, AReportOfAReplacedRunGoesWithIt) {
  const fs::path out = dir() / "out";
  const fs::path file = scene("sheet.yaml", sheet_scene(0.05));
  ASSERT_EQ(run_drapelab({"run", file.string(), "--out", out.string()}).exit_code, 0);
  const auto report = run_drapelab({"report", out.string()});
  ASSERT_EQ(report.exit_code, 0) << report.output;
  ASSERT_TRUE(fs::is_regular_file(out / "report.html"));
  EXPECT_NE(read_text(out / ".drapelab-manifest").find("report.html"), std::string::npos);
  // The same run again keeps nothing stale either: its page describes the previous run.
  ASSERT_EQ(run_drapelab({"run", file.string(), "--out", out.string()}).exit_code, 0);
  EXPECT_FALSE(fs::exists(out / "report.html"));
}

TEST_F(RunFolderSafety, CtrlCOnARerunKeepsTheFinishedRun) {
  const fs::path out = dir() / "out";
  const fs::path short_run = scene("short.yaml", sheet_scene(0.5));
  ASSERT_EQ(run_drapelab({"run", short_run.string(), "--out", out.string()}).exit_code, 0);
  const std::string finished_metrics = read_text(out / "metrics.csv");
  ASSERT_EQ(count_whole_rows(out / "metrics.csv"), 31u);

  // A long run into the same folder; while it runs, the finished run stays whole.
  const fs::path long_run = scene("long.yaml", sheet_scene(600.0));
  bool intact_while_running = true;
  const int exit_code =
      interrupt_drapelab_when({"run", long_run.string(), "--out", out.string(), "--force"}, [&] {
        intact_while_running =
            intact_while_running && read_text(out / "metrics.csv") == finished_metrics;
        return count_file_lines(staged_file(out, "metrics.csv")) >= 6;
      });
  EXPECT_EQ(exit_code, 130);
  EXPECT_TRUE(intact_while_running);
  EXPECT_EQ(read_text(out / "metrics.csv"), finished_metrics);
  EXPECT_EQ(nlohmann::json::parse(read_text(out / "summary.json"))["run"]["state"], "finished");

  // The interrupted run is kept beside it, complete up to its last frame.
  const fs::path kept = out / "interrupted_run";
  const auto summary = nlohmann::json::parse(read_text(kept / "summary.json"));
  EXPECT_EQ(summary["run"]["state"], "interrupted");
  const std::size_t frames = count_whole_rows(kept / "metrics.csv");
  EXPECT_GE(frames, 5u);
  EXPECT_EQ(summary["run"]["frames_done"].get<std::size_t>() + 1, frames);

  // A finished re-run replaces both.
  ASSERT_EQ(run_drapelab({"run", short_run.string(), "--out", out.string(), "--force"}).exit_code,
            0);
  EXPECT_FALSE(fs::exists(kept));
  EXPECT_EQ(read_text(out / "metrics.csv"), finished_metrics);
}

TEST_F(RunFolderSafety, ASecondWriterIsRefusedWithTheHoldersPid) {
  const fs::path out = dir() / "out";
  const fs::path long_run = scene("long.yaml", sheet_scene(600.0));
  CommandResult second;
  bool started = false;
  const int exit_code =
      interrupt_drapelab_when({"run", long_run.string(), "--out", out.string()}, [&] {
        if (count_file_lines(staged_file(out, "metrics.csv")) < 3) return false;
        if (!started) {
          second = run_drapelab({"run", long_run.string(), "--out", out.string(), "--force"});
          started = true;
        }
        return true;
      });
  EXPECT_EQ(exit_code, 130);
  ASSERT_TRUE(started);
  EXPECT_EQ(second.exit_code, 2) << second.output;
  EXPECT_NE(second.output.find("being written by another drapelab run (pid "), std::string::npos)
      << second.output;
  // The first run's files are its own: one summary, its frames, no mix.
  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["run"]["state"], "interrupted");
  EXPECT_EQ(summary["run"]["frames_done"].get<std::size_t>() + 1,
            count_whole_rows(out / "metrics.csv"));
}

TEST_F(RunFolderSafety, AReportTellsARunStillGoingFromAKilledOne) {
  const fs::path out = dir() / "out";
  const fs::path long_run = scene("long.yaml", sheet_scene(600.0));
  CommandResult live;
  fs::path staging;
  const int exit_code = interrupt_drapelab_when(
      {"run", long_run.string(), "--out", out.string()},
      [&] {
        if (count_file_lines(staged_file(out, "metrics.csv")) < 3) return false;
        staging = staged_file(out, "metrics.csv").parent_path();
        live = run_drapelab({"report", staging.string(), "--out", (dir() / "live.html").string()});
        return true;
      },
      std::chrono::seconds(60), SIGKILL);
  EXPECT_EQ(exit_code, -1);  // killed
  EXPECT_EQ(live.exit_code, 1) << live.output;
  EXPECT_NE(live.output.find("still running (pid "), std::string::npos) << live.output;

  const auto killed =
      run_drapelab({"report", staging.string(), "--out", (dir() / "killed.html").string()});
  EXPECT_EQ(killed.exit_code, 1) << killed.output;
  EXPECT_NE(killed.output.find("its writer was killed"), std::string::npos) << killed.output;
  // The next run clears the killed run's staging folder, and says so.
  const fs::path short_run = scene("short.yaml", sheet_scene(0.05));
  const auto next = run_drapelab({"run", short_run.string(), "--out", out.string(), "--force"});
  EXPECT_EQ(next.exit_code, 0) << next.output;
  EXPECT_NE(next.output.find("left by a run that was killed"), std::string::npos) << next.output;
  EXPECT_FALSE(fs::exists(staging));
}

TEST_F(RunFolderSafety, AWriteErrorStopsOnTheLastWholeFrame) {
  // 33 x 33 particles: a 13 KB point cache sample per frame reaches a 1 MB file limit near frame 80
  // of 120, while every other file stays small.
  const fs::path out = dir() / "out";
  const fs::path file = scene("sheet.yaml", sheet_scene(2.0, 33));
  const auto result = run_drapelab_with_file_size_limit(
      1024 * 1024, {"run", file.string(), "--out", out.string(), "--meshes", "pc2"});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("ours.pc2"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("File too large"), std::string::npos) << result.output;

  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["run"]["state"], "write_failed");
  const std::size_t frames = summary["run"]["frames_done"].get<std::size_t>() + 1;
  EXPECT_GT(frames, 10u);
  EXPECT_LT(frames, 121u);
  EXPECT_EQ(count_whole_rows(out / "metrics.csv"), frames);
  EXPECT_EQ(summary["solvers"]["ours"]["frames_recorded"].get<std::size_t>(), frames);
  // The point cache holds exactly those frames: its header count and its size agree.
  const std::string pc2 = read_text(out / "meshes" / "ours.pc2");
  std::int32_t samples = 0;
  ASSERT_GE(pc2.size(), 32u);
  std::copy(pc2.data() + 28, pc2.data() + 32, reinterpret_cast<char*>(&samples));
  EXPECT_EQ(static_cast<std::size_t>(samples), frames);
  EXPECT_EQ(pc2.size(), 32u + frames * 33u * 33u * 12u);
  EXPECT_TRUE(files_ending_with(out, ".partial").empty());
}

TEST_F(RunFolderSafety, AnUnwritableOutputFolderIsAClearError) {
  const fs::path file = scene("sheet.yaml", sheet_scene(0.05));
  const auto inside_proc = run_drapelab({"run", file.string(), "--out", "/proc/drapelab-out"});
  EXPECT_EQ(inside_proc.exit_code, 2) << inside_proc.output;
  EXPECT_NE(inside_proc.output.find("cannot create the output folder /proc/drapelab-out"),
            std::string::npos)
      << inside_proc.output;
  const auto proc = run_drapelab({"run", file.string(), "--out", "/proc", "--force"});
  EXPECT_EQ(proc.exit_code, 2) << proc.output;
  EXPECT_NE(proc.output.find("cannot write into /proc"), std::string::npos) << proc.output;
}

TEST_F(RunFolderSafety, PathsThatAreNotUtf8AreRecordedNotRefused) {
  // Linux file names are bytes; summary.json, which is JSON, shows the stray byte as U+FFFD.
  const fs::path file = scene("sheet\xff.yaml", sheet_scene(0.05));
  const fs::path out = dir() / "out\xfe";
  const auto result = run_drapelab({"run", file.string(), "--out", out.string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["run"]["state"], "finished");
  EXPECT_NE(summary["scene_file"].get<std::string>().find("\xef\xbf\xbd"), std::string::npos);
}

TEST_F(RunFolderSafety, SigtermStopsARunLikeCtrlC) {
  const fs::path out = dir() / "out";
  const fs::path long_run = scene("long.yaml", sheet_scene(600.0));
  const int exit_code = interrupt_drapelab_when(
      {"run", long_run.string(), "--out", out.string()},
      [&] { return count_file_lines(staged_file(out, "metrics.csv")) >= 3; },
      std::chrono::seconds(60), SIGTERM);
  EXPECT_EQ(exit_code, 130);
  EXPECT_EQ(nlohmann::json::parse(read_text(out / "summary.json"))["run"]["state"], "interrupted");
}

}  // namespace
}  // namespace drapelab
