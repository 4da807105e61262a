// The text of the progress lines that `drapelab run` and `drapelab sweep` print while they work
// (docs/cli.md, "Progress"): pure functions of counts and times, so that a line reads the same on a
// terminal and in a log, and can be tested without either.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "drapelab/runner/run_progress.hpp"

namespace drapelab::cli {

using runner::SolverProgress;

// One sweep, as its progress line shows it.
struct SweepProgress {
  std::size_t done = 0;                // combinations finished, refused ones included
  std::size_t total = 0;               // combinations in the sweep
  std::size_t ran = 0;                 // combinations finished since the wall clock started
  std::optional<std::size_t> running;  // runs in progress, when known (not for Slurm)
  double wall_seconds = 0.0;           // s since the sweep started running
};

// The time left at the rate so far: wall_seconds / done x (total - done); nothing before the
// first unit of work is done (no rate yet).
std::optional<double> seconds_left(double wall_seconds, double done, double total);

// A wall time for people: "0.4 s", "42 s", "3 min 05 s", "2 h 10 min".
std::string format_wall_time(double seconds);

// "progress: ours  frame 30/120, t = 0.50/2.00 s, 1.2 s wall, about 3.6 s left"; the name padded
// to `name_width` characters so that the lines of several solvers align.
std::string format_solver_progress(const SolverProgress& solver, std::size_t name_width = 0);

// "progress: 3/6 runs done, 2 running, 12 s wall, about 24 s left"
std::string format_sweep_progress(const SweepProgress& sweep);

}  // namespace drapelab::cli
