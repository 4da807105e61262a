// How many threads our solver's parallel loops use (spring forces, particle passes, contact blocks,
// the matrix-free implicit solve). Results do not depend on it: every loop sums in a fixed order.
#pragma once

namespace drapelab::kernels {

// Threads the loops use (OpenMP); always 1 in a build without OpenMP.
void set_thread_count(int threads);
int thread_count();

}  // namespace drapelab::kernels
