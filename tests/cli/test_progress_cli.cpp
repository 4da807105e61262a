// What drapelab prints around its work, end to end: the progress lines of run and sweep in a pipe
// (plain, flushed, on stderr, never in a file) and on a terminal (redrawn, then erased), -q, a
// misspelt verb, and the viewer's usage line.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "fixtures/cli.hpp"
#include "fixtures/sweep_scene.hpp"

namespace {

namespace fs = std::filesystem;
using drapelab::fixtures::CommandResult;
using drapelab::fixtures::kSweepSheet;
using drapelab::fixtures::read_text;
using drapelab::fixtures::run_drapelab;
using drapelab::fixtures::run_shell;
using drapelab::fixtures::shell_quote;
using drapelab::fixtures::split_lines;
using drapelab::fixtures::write_text;

// Two solvers on the sweep tests' small sheet; the second lets the loader choose its dt, which
// the loader notes.
const std::string kTwoSolvers =
    kSweepSheet + "  - {name: automatic, type: spring_damper, host: none}\n";

// drapelab with `arguments` through /bin/sh; `environment` ("NAME=value ...") before it and
// `redirections` after it.
std::string command(const std::string& environment, const std::vector<std::string>& arguments,
                    const std::string& redirections) {
  std::string text = "env " + environment + " " + shell_quote(DRAPELAB_EXE);
  for (const auto& argument : arguments) text += " " + shell_quote(argument);
  return text + " " + redirections;
}

std::vector<std::string> lines_starting_with(const std::string& text, const std::string& prefix) {
  std::vector<std::string> found;
  for (const auto& line : split_lines(text))
    if (line.rfind(prefix, 0) == 0) found.push_back(line);
  return found;
}

// Every file under `folder` that holds `text`.
std::vector<std::string> files_holding(const fs::path& folder, const std::string& text) {
  std::vector<std::string> found;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.is_regular_file() && read_text(entry.path()).find(text) != std::string::npos)
      found.push_back(entry.path().string());
  return found;
}

class Progress : public drapelab::fixtures::TempDirTest {
 protected:
  fs::path scene() {
    const fs::path path = dir() / "two.yaml";
    write_text(path, kTwoSolvers);
    return path;
  }
  std::vector<std::string> run_arguments(const fs::path& out) {
    return {"run", scene().string(), "--out", out.string()};
  }
};

TEST_F(Progress, APipedRunWritesPlainLinesPerSolverOnStderr) {
  const fs::path out = dir() / "out";
  const fs::path stdout_file = dir() / "stdout.txt";
  const fs::path stderr_file = dir() / "stderr.txt";
  // An interval of 0: a line per solver at every frame, instead of every 5 s.
  const CommandResult result = run_shell(
      command("DRAPELAB_PROGRESS_INTERVAL=0", run_arguments(out),
              ">" + shell_quote(stdout_file.string()) + " 2>" + shell_quote(stderr_file.string())));
  ASSERT_EQ(result.exit_code, 0) << read_text(stderr_file);
  const std::string errors = read_text(stderr_file);
  const std::string output = read_text(stdout_file);
  EXPECT_EQ(errors.find('\r'), std::string::npos) << errors;
  EXPECT_EQ(errors.find('\033'), std::string::npos) << errors;
  // Frames 0..6 of both solvers, frame 0 before any stepping.
  const auto ours = lines_starting_with(errors, "progress: ours:");
  const auto automatic = lines_starting_with(errors, "progress: automatic:");
  ASSERT_EQ(ours.size(), 7u) << errors;
  ASSERT_EQ(automatic.size(), 7u) << errors;
  EXPECT_EQ(ours.front().find("progress: ours:      frame 0/6, t = 0.000/0.100 s"), 0u)
      << ours.front();
  EXPECT_NE(ours.back().find("frame 6/6, t = 0.100/0.100 s"), std::string::npos) << ours.back();
  EXPECT_NE(ours.back().find(" wall, done"), std::string::npos) << ours.back();
  EXPECT_NE(ours[3].find(" left"), std::string::npos) << ours[3];
  // stdout holds the run's own lines only; no file of the run holds a progress line.
  EXPECT_EQ(output.find("progress:"), std::string::npos) << output;
  EXPECT_NE(output.find("running sweep_sheet (6 frames)"), std::string::npos) << output;
  EXPECT_TRUE(files_holding(out, "progress:").empty());
}

TEST_F(Progress, PipedLinesAreFlushedAsTheyAreWritten) {
  // stdout and stderr into one pipe: the "running" line comes before the first progress line (a
  // fully buffered stdout would hold it back to the end).
  const fs::path out = dir() / "out";
  const CommandResult result =
      run_shell(command("DRAPELAB_PROGRESS_INTERVAL=0", run_arguments(out), "2>&1"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto lines = split_lines(result.output);
  std::size_t running = lines.size(), first_progress = lines.size(), outputs = lines.size();
  for (std::size_t k = lines.size(); k-- > 0;) {
    if (lines[k].rfind("running ", 0) == 0) running = k;
    if (lines[k].rfind("progress: ", 0) == 0) first_progress = k;
    if (lines[k].rfind("outputs in ", 0) == 0) outputs = k;
  }
  ASSERT_LT(first_progress, lines.size()) << result.output;
  EXPECT_LT(running, first_progress) << result.output;
  EXPECT_LT(first_progress, outputs) << result.output;
}

TEST_F(Progress, AShortPipedRunPrintsNoProgressAtTheDefaultInterval) {
  // 6 frames of a 5 x 5 sheet end well within the first 5 s.
  const CommandResult result =
      run_shell(command("-u DRAPELAB_PROGRESS_INTERVAL", run_arguments(dir() / "out"), "2>&1"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(result.output.find("progress:"), std::string::npos) << result.output;
}

TEST_F(Progress, NoProgressLeavesTheRestOfTheOutputAsItIs) {
  std::vector<std::string> arguments = run_arguments(dir() / "out");
  arguments.push_back("--no-progress");
  const CommandResult result =
      run_shell(command("DRAPELAB_PROGRESS_INTERVAL=0", arguments, "2>&1"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(result.output.find("progress:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("running sweep_sheet"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("note: "), std::string::npos) << result.output;
}

TEST_F(Progress, QuietPrintsNoNoteAndNoProgress) {
  const fs::path out = dir() / "out";
  const CommandResult loud =
      run_shell(command("DRAPELAB_PROGRESS_INTERVAL=0", run_arguments(dir() / "loud"), "2>&1"));
  ASSERT_EQ(loud.exit_code, 0) << loud.output;
  ASSERT_NE(loud.output.find("note: solver 'automatic': dt chosen automatically"),
            std::string::npos)
      << loud.output;
  ASSERT_NE(loud.output.find("progress:"), std::string::npos) << loud.output;

  std::vector<std::string> arguments = run_arguments(out);
  arguments.push_back("-q");
  const CommandResult quiet = run_shell(command("DRAPELAB_PROGRESS_INTERVAL=0", arguments, "2>&1"));
  EXPECT_EQ(quiet.exit_code, 0);
  EXPECT_EQ(quiet.output, "");
  EXPECT_TRUE(fs::exists(out / "metrics.csv"));
}

TEST_F(Progress, QuietStillPrintsWarnings) {
  // ours at two steps per frame, above its stable step estimate: a warning, which -q keeps, while
  // the other solver's note goes.
  std::vector<std::string> arguments = run_arguments(dir() / "out");
  arguments.insert(arguments.end(), {"-q", "--set", "solvers.0.dt=0.0083333333333333333"});
  const CommandResult result = run_drapelab(arguments);
  EXPECT_NE(result.output.find("warning: "), std::string::npos) << result.output;
  EXPECT_EQ(result.output.find("note: "), std::string::npos) << result.output;
  EXPECT_EQ(result.output.find("progress: "), std::string::npos) << result.output;
}

TEST_F(Progress, ATerminalGetsLinesRedrawnInPlaceAndErasedAtTheEnd) {
  if (run_shell("command -v script >/dev/null 2>&1").exit_code != 0)
    GTEST_SKIP() << "script (util-linux) is not installed";
  // script runs the command on a pseudo-terminal and copies what it shows.
  const std::string inner =
      command("TERM=xterm DRAPELAB_PROGRESS_INTERVAL=0", run_arguments(dir() / "out"), "");
  const CommandResult result =
      run_shell("script -qec " + shell_quote(inner) + " /dev/null </dev/null 2>&1");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const std::string& shown = result.output;
  EXPECT_NE(shown.find("\r\033[Kprogress: ours:"), std::string::npos) << shown;
  EXPECT_NE(shown.find("\033[Kprogress: automatic:"), std::string::npos) << shown;
  // Erased (back to the first of the two lines, then everything below) before the summary.
  const std::size_t erased = shown.rfind("\r\033[1A\033[J");
  ASSERT_NE(erased, std::string::npos) << shown;
  EXPECT_EQ(shown.find("progress:", erased), std::string::npos) << shown;
  EXPECT_NE(shown.find("outputs in ", erased), std::string::npos) << shown;
}

TEST_F(Progress, APipedSweepCountsRunsDoneAndKeepsProgressOutOfTheRunLogs) {
  const fs::path out = dir() / "sweep";
  const fs::path stderr_file = dir() / "stderr.txt";
  const CommandResult result = run_shell(command(
      "DRAPELAB_PROGRESS_INTERVAL=0",
      {"sweep", scene().string(), "--vary", "seed=1,2", "--jobs", "1", "--out", out.string()},
      "2>" + shell_quote(stderr_file.string())));
  ASSERT_EQ(result.exit_code, 0) << result.output << read_text(stderr_file);
  const std::string errors = read_text(stderr_file);
  EXPECT_EQ(errors.find('\r'), std::string::npos) << errors;
  EXPECT_NE(errors.find("progress: 0/2 runs done, 1 running, "), std::string::npos) << errors;
  EXPECT_NE(errors.find("progress: 1/2 runs done, 1 running, "), std::string::npos) << errors;
  EXPECT_EQ(result.output.find("progress:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("[2/2] "), std::string::npos) << result.output;
  // Each run's log (its stdout and stderr) and folder are as without progress.
  EXPECT_TRUE(files_holding(out, "progress:").empty());
}

TEST(UnknownVerb, NamesItselfAndTheNearestVerb) {
  const CommandResult result = run_drapelab({"runn", "x"});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("unknown command 'runn'; did you mean 'run'?"), std::string::npos)
      << result.output;
  EXPECT_EQ(result.output.find("A subcommand is required"), std::string::npos) << result.output;

  const CommandResult cut_short = run_drapelab({"vali", "scene.yaml"});
  EXPECT_EQ(cut_short.exit_code, 2);
  EXPECT_NE(cut_short.output.find("did you mean 'validate'?"), std::string::npos)
      << cut_short.output;
}

TEST(UnknownVerb, FarFromEveryVerbListsThemAll) {
  const CommandResult result = run_drapelab({"simulate", "scene.yaml"});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("unknown command 'simulate'; the commands are run, validate, "),
            std::string::npos)
      << result.output;
  EXPECT_EQ(result.output.find("did you mean"), std::string::npos) << result.output;
}

TEST(UnknownVerb, AKnownVerbsOwnUsageErrorsStayItsOwn) {
  const CommandResult result = run_drapelab({"run", "scene.yaml"});  // no --out
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_EQ(result.output.find("unknown command"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("--out"), std::string::npos) << result.output;
}

TEST(ViewHelp, NamesDrapelabView) {
  const CommandResult result = run_drapelab({"view", "--help"});
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("Usage: drapelab view [OPTIONS] scene"), std::string::npos)
      << result.output;
}

}  // namespace
