// How many threads the loops use, and the share of the machine they may take
// (drapelab/loop_threads.hpp).
#include "drapelab/loop_threads.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace drapelab::kernels {
namespace {

// The most threads the loops may use, 0 before it is read: every core then. Fixed when
// set_thread_count gave it: share_machine then leaves it.
std::atomic<int> ceiling{0};
std::atomic<bool> fixed{false};

void use_threads(int threads) {
#ifdef _OPENMP
  omp_set_num_threads(std::max(1, threads));
#else
  (void)threads;
#endif
}

}  // namespace

void set_thread_count(int threads) {
  ceiling = std::max(1, threads);
  fixed = true;
  use_threads(ceiling);
}

int thread_count() {
  // Every core unless told otherwise, read before share_machine lowers OpenMP's own count.
  if (ceiling == 0) {
#ifdef _OPENMP
    int expected = 0;
    ceiling.compare_exchange_strong(expected, omp_get_max_threads());
#else
    ceiling = 1;
#endif
  }
  return ceiling;
}

int threads_for_load(int most, double other_cores) {
  // Up to 0.4 of a core used by others is noise (daemons, the terminal, and the clock ticks the
  // machine's counters count in); above it, one thread
  // per core they take, rounded up: a thread that shares its core waits at every barrier.
  const int taken = static_cast<int>(std::ceil(std::max(0.0, other_cores - 0.4)));
  return std::clamp(most - taken, 1, std::max(1, most));
}

void share_machine(const MachineLoad& load) {
  const int most = thread_count();
  if (fixed) return;
  const std::optional<double> others = load.other_cores();
  use_threads(others ? threads_for_load(most, *others) : most);
}

}  // namespace drapelab::kernels
