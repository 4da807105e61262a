// The other processes' share of the machine (drapelab/machine_load.hpp).
#include "drapelab/machine_load.hpp"

#include <fcntl.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace drapelab {

MachineLoad::MachineLoad(std::chrono::milliseconds window) : window_(window) {}

std::optional<MachineLoad::Reading> MachineLoad::read() {
  // /proc/stat's first line: "cpu  user nice system idle iowait irq softirq steal ...", in clock
  // ticks summed over the cores. Busy is all but idle and iowait. Read into the stack: the step
  // allocates nothing.
  char text[256];
  const int file = open("/proc/stat", O_RDONLY | O_CLOEXEC);
  if (file < 0) return std::nullopt;
  const ssize_t length = ::read(file, text, sizeof(text) - 1);
  close(file);
  if (length <= 4 || std::strncmp(text, "cpu ", 4) != 0) return std::nullopt;
  text[length] = '\0';
  long long field[8] = {};  // user nice system idle iowait irq softirq steal
  char* at = text + 4;
  for (long long& value : field) {
    char* end = nullptr;
    value = std::strtoll(at, &end, 10);
    if (end == at) return std::nullopt;
    at = end;
  }
  const long ticks_per_second = sysconf(_SC_CLK_TCK);
  timespec cpu{};
  if (ticks_per_second <= 0 || clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu) != 0)
    return std::nullopt;
  Reading r;
  r.wall = std::chrono::steady_clock::now();
  const long long busy = field[0] + field[1] + field[2] + field[5] + field[6] + field[7];
  r.machine_busy = static_cast<double>(busy) / static_cast<double>(ticks_per_second);
  r.process_cpu = static_cast<double>(cpu.tv_sec) + 1e-9 * static_cast<double>(cpu.tv_nsec);
  return r;
}

void MachineLoad::sample() {
  const auto now = std::chrono::steady_clock::now();
  if (last_ && now - last_->wall < window_) return;
  const std::optional<Reading> reading = read();
  if (!reading) return;
  if (last_) {
    const double wall = std::chrono::duration<double>(reading->wall - last_->wall).count();
    const double others = (reading->machine_busy - last_->machine_busy) -
                          (reading->process_cpu - last_->process_cpu);  // s of CPU
    other_cores_ = wall > 0.0 ? std::max(0.0, others / wall) : 0.0;
  }
  last_ = reading;
}

}  // namespace drapelab
