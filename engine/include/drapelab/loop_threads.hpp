// How many threads our solver's parallel loops use (spring forces, particle passes, contact blocks,
// the matrix-free implicit solve, vbd's sweeps and detections). Results do not depend on it: every
// loop sums in a fixed order, so the count may change from one step to the next.
#pragma once

#include "drapelab/machine_load.hpp"

namespace drapelab::kernels {

// The threads the loops use (OpenMP), fixed: share_machine then leaves them as they are. Without it
// the loops may use every core, as many as share_machine leaves them. Always 1 without OpenMP.
void set_thread_count(int threads);
// The most threads the loops use: set_thread_count's, or every core.
int thread_count();

// The threads to use of at most `most` while other processes keep `other_cores` cores busy: one
// thread fewer for each core they take (above 0.4 of one), at least one.
int threads_for_load(int most, double other_cores);

// Sets the loops' threads for the next step from what the other processes on the machine use
// (MachineLoad): with the second core busy, two threads meeting at a barrier wait for the one the
// scheduler has parked, about a hundred times a vbd step. Every thread_count() when the load is
// not known yet; nothing after set_thread_count.
void share_machine(const MachineLoad& load);

}  // namespace drapelab::kernels
