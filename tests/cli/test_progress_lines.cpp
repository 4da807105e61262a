// The progress lines of drapelab run and sweep without a terminal: their text (progress_line.hpp)
// and what the display writes in each mode (progress_display.hpp), at chosen times.
#include <gtest/gtest.h>

#include <chrono>
#include <sstream>
#include <string>
#include <vector>

#include "progress/progress_display.hpp"
#include "progress/progress_line.hpp"

namespace {

using drapelab::cli::format_solver_progress;
using drapelab::cli::format_sweep_progress;
using drapelab::cli::format_wall_time;
using drapelab::cli::ProgressDisplay;
using drapelab::cli::ProgressMode;
using drapelab::cli::seconds_left;
using drapelab::cli::SolverProgress;
using drapelab::cli::SweepProgress;
using namespace std::chrono_literals;

SolverProgress solver_at(int frames_done, double wall_seconds) {
  SolverProgress solver;
  solver.name = "ours";
  solver.frames_done = frames_done;
  solver.frames_total = 120;
  solver.simulated_seconds = frames_done / 60.0;
  solver.duration_seconds = 2.0;
  solver.wall_seconds = wall_seconds;
  return solver;
}

TEST(ProgressLine, WallTimesReadAsPeopleSayThem) {
  EXPECT_EQ(format_wall_time(0.0), "0.0 s");
  EXPECT_EQ(format_wall_time(0.42), "0.4 s");
  EXPECT_EQ(format_wall_time(9.9), "9.9 s");
  EXPECT_EQ(format_wall_time(42.4), "42 s");
  EXPECT_EQ(format_wall_time(59.6), "1 min 00 s");
  EXPECT_EQ(format_wall_time(185.0), "3 min 05 s");
  EXPECT_EQ(format_wall_time(7800.0), "2 h 10 min");
  EXPECT_EQ(format_wall_time(-1.0), "0.0 s");  // a clock that went back is no time
}

TEST(ProgressLine, TimeLeftIsTheRateSoFarOverWhatRemains) {
  EXPECT_FALSE(seconds_left(3.0, 0.0, 10.0));  // no rate before the first unit is done
  EXPECT_DOUBLE_EQ(*seconds_left(3.0, 30.0, 120.0), 9.0);
  EXPECT_DOUBLE_EQ(*seconds_left(3.0, 120.0, 120.0), 0.0);
}

TEST(ProgressLine, ASolverLineGivesFramesTimesAndTheTimeLeft) {
  EXPECT_EQ(format_solver_progress(solver_at(30, 1.2)),
            "progress: ours: frame 30/120, t = 0.50/2.00 s, 1.2 s wall, about 3.6 s left");
  // Frame 0 alone: no rate yet, so no estimate.
  EXPECT_EQ(format_solver_progress(solver_at(0, 0.0)),
            "progress: ours: frame 0/120, t = 0.00/2.00 s, 0.0 s wall");
  EXPECT_EQ(format_solver_progress(solver_at(120, 4.8)),
            "progress: ours: frame 120/120, t = 2.00/2.00 s, 4.8 s wall, done");
}

TEST(ProgressLine, AStoppedSolverSaysWhyAndWhereWithoutAnEstimate) {
  SolverProgress wild = solver_at(3, 0.01);
  wild.name = "wild";
  wild.stopped = "unstable";
  EXPECT_EQ(format_solver_progress(wild),
            "progress: wild: unstable at frame 3/120, t = 0.05/2.00 s, 0.0 s wall");
}

TEST(ProgressLine, NamesArePaddedSoThatSeveralSolversAlign) {
  SolverProgress classic = solver_at(30, 1.2);
  classic.name = "bullet_classic";
  const std::string ours = format_solver_progress(solver_at(30, 1.2), classic.name.size());
  const std::string bullet = format_solver_progress(classic, classic.name.size());
  EXPECT_EQ(ours.find("frame"), bullet.find("frame")) << ours << "\n" << bullet;
}

TEST(ProgressLine, SimulatedTimesKeepThreeDigitsOfTheDuration) {
  SolverProgress solver = solver_at(1, 0.1);
  solver.duration_seconds = 0.1;
  EXPECT_NE(format_solver_progress(solver).find("t = 0.017/0.100 s"), std::string::npos);
  solver.duration_seconds = 60.0;
  solver.simulated_seconds = 31.5;
  EXPECT_NE(format_solver_progress(solver).find("t = 31.5/60.0 s"), std::string::npos);
}

TEST(ProgressLine, ASweepLineCountsRunsAndEstimatesFromTheRunsItRan) {
  SweepProgress sweep;
  sweep.done = 3;
  sweep.total = 6;
  sweep.ran = 3;
  sweep.running = 2;
  sweep.wall_seconds = 12.0;
  EXPECT_EQ(format_sweep_progress(sweep),
            "progress: 3/6 runs done, 2 running, 12 s wall, about 12 s left");
  // Two combinations refused by validation took none of the time: the rate is 12 s per run.
  sweep.ran = 1;
  sweep.running.reset();  // Slurm: queued and running are not told apart
  EXPECT_EQ(format_sweep_progress(sweep), "progress: 3/6 runs done, 12 s wall, about 36 s left");
  sweep.ran = 0;
  EXPECT_EQ(format_sweep_progress(sweep), "progress: 3/6 runs done, 12 s wall");
}

TEST(ProgressDisplay, PlainLinesAreWholeLinesAtMostEveryInterval) {
  std::ostringstream out;
  ProgressDisplay display(ProgressMode::plain, out, 5s);
  const auto start = ProgressDisplay::Clock::now();  // the interval counts from the display's start
  display.update({"progress: a", "progress: b"}, start + 1s);
  EXPECT_EQ(out.str(), "");  // the first line waits one interval
  display.update({"progress: a", "progress: b"}, start + 5s);
  EXPECT_EQ(out.str(), "progress: a\nprogress: b\n");
  display.update({"progress: c"}, start + 9s);
  EXPECT_EQ(out.str(), "progress: a\nprogress: b\n");
  display.update({"progress: c"}, start + 10s);
  display.clear();  // plain lines stay: they are the log
  EXPECT_EQ(out.str(), "progress: a\nprogress: b\nprogress: c\n");
  EXPECT_EQ(out.str().find('\r'), std::string::npos);
  EXPECT_EQ(out.str().find('\033'), std::string::npos);
}

TEST(ProgressDisplay, TerminalLinesAreRedrawnInPlaceAndErasedAtTheEnd) {
  std::ostringstream out;
  const auto start = ProgressDisplay::Clock::now();
  ProgressDisplay display(ProgressMode::terminal, out, 5s);
  display.update({"one", "two"}, start);  // at once
  EXPECT_EQ(out.str(), "\r\033[Kone\n\033[Ktwo");
  out.str("");
  display.update({"ONE", "TWO"}, start + 50ms);  // too soon to redraw
  EXPECT_EQ(out.str(), "");
  display.update({"ONE", "TWO"}, start + 150ms);  // back up one line, rewrite both
  EXPECT_EQ(out.str(), "\r\033[1A\033[KONE\n\033[KTWO");
  out.str("");
  display.update({"only"}, start + 300ms);  // fewer lines: the rest below is erased
  EXPECT_EQ(out.str(), "\r\033[1A\033[Konly\033[J");
  out.str("");
  display.clear();
  EXPECT_EQ(out.str(), "\r\033[J");
  out.str("");
  display.clear();  // nothing drawn: nothing to erase
  EXPECT_EQ(out.str(), "");
}

TEST(ProgressDisplay, NoneWritesNothing) {
  std::ostringstream out;
  {
    ProgressDisplay display(ProgressMode::none, out, 0s);
    display.update({"progress: a"});
    display.clear();
  }
  EXPECT_EQ(out.str(), "");
}

TEST(ProgressDisplay, IsErasedWhenItEnds) {
  std::ostringstream out;
  {
    ProgressDisplay display(ProgressMode::terminal, out, 5s);
    display.update({"one"});
  }
  EXPECT_EQ(out.str(), "\r\033[Kone\r\033[J");
}

}  // namespace
