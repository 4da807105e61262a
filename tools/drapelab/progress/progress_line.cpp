#include "progress/progress_line.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace drapelab::cli {
namespace {

std::string printed(const char* format, double a, double b = 0.0) {
  char text[64];
  std::snprintf(text, sizeof text, format, a, b);
  return text;
}

// Simulated times with three significant digits of the duration: "0.50/2.00 s", "31.5/60.0 s".
std::string simulated_times(double time, double duration) {
  const int decimals =
      duration > 0.0 ? std::clamp(2 - static_cast<int>(std::floor(std::log10(duration))), 0, 6) : 2;
  char text[96];
  std::snprintf(text, sizeof text, "%.*f/%.*f s", decimals, time, decimals, duration);
  return text;
}

}  // namespace

std::optional<double> seconds_left(double wall_seconds, double done, double total) {
  if (!(done > 0.0) || !(wall_seconds >= 0.0)) return std::nullopt;
  return wall_seconds / done * std::max(0.0, total - done);
}

std::string format_wall_time(double seconds) {
  if (!(seconds >= 0.0)) seconds = 0.0;
  if (seconds < 9.95) return printed("%.1f s", seconds);
  const double whole = std::round(seconds);
  if (whole < 60.0) return printed("%.0f s", whole);
  if (whole < 3600.0)
    return printed("%.0f min %02.0f s", std::floor(whole / 60.0), std::fmod(whole, 60.0));
  const double minutes = std::round(seconds / 60.0);
  return printed("%.0f h %02.0f min", std::floor(minutes / 60.0), std::fmod(minutes, 60.0));
}

std::string format_solver_progress(const SolverProgress& solver, std::size_t name_width) {
  std::string name = solver.name + ":";
  if (name.size() < name_width + 1) name.resize(name_width + 1, ' ');
  std::string line = "progress: " + name + " ";
  if (!solver.stopped.empty()) line += solver.stopped + " at ";
  line += "frame " + std::to_string(solver.frames_done) + "/" +
          std::to_string(solver.frames_total) +
          ", t = " + simulated_times(solver.simulated_seconds, solver.duration_seconds) + ", " +
          format_wall_time(solver.wall_seconds) + " wall";
  if (!solver.stopped.empty()) return line;
  if (solver.frames_done >= solver.frames_total) return line + ", done";
  if (const auto left = seconds_left(solver.wall_seconds, solver.frames_done, solver.frames_total))
    line += ", about " + format_wall_time(*left) + " left";
  return line;
}

std::string format_sweep_progress(const SweepProgress& sweep) {
  std::string line =
      "progress: " + std::to_string(sweep.done) + "/" + std::to_string(sweep.total) + " runs done";
  if (sweep.running) line += ", " + std::to_string(*sweep.running) + " running";
  line += ", " + format_wall_time(sweep.wall_seconds) + " wall";
  // The rate counts only the runs finished since the clock started: refused combinations, and
  // those a --collect found finished, took no time of it.
  const double remaining = static_cast<double>(sweep.total - std::min(sweep.done, sweep.total));
  if (remaining > 0.0)
    if (const auto left = seconds_left(sweep.wall_seconds, static_cast<double>(sweep.ran),
                                       static_cast<double>(sweep.ran) + remaining))
      line += ", about " + format_wall_time(*left) + " left";
  return line;
}

}  // namespace drapelab::cli
