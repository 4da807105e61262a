// What the other processes on the machine use of its cores, measured from outside the solver: the
// machine's busy time (Linux /proc/stat) less this process's CPU time, over a window of wall time.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>

namespace drapelab {

class MachineLoad {
 public:
  // Samples at most once per `window`; call as often as convenient (once a step).
  explicit MachineLoad(std::chrono::milliseconds window = std::chrono::milliseconds(200));

  void sample();
  // Cores the other processes kept busy over the last full window; none before the first window
  // ends, or where the machine's counters cannot be read.
  std::optional<double> other_cores() const { return other_cores_; }

 private:
  struct Reading {
    std::chrono::steady_clock::time_point wall;
    double machine_busy = 0.0;  // s of CPU, every core, since boot
    double process_cpu = 0.0;   // s of CPU of this process
  };
  static std::optional<Reading> read();

  std::chrono::milliseconds window_;
  std::optional<Reading> last_;
  std::optional<double> other_cores_;
};

}  // namespace drapelab
