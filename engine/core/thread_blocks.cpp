// How the threads share blocks of particles (thread_blocks.hpp).
#include "core/thread_blocks.hpp"

#include <algorithm>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace drapelab::kernels {

ThreadRun thread_run(std::int64_t blocks, std::int64_t block_size, std::int64_t n,
                     std::int64_t max_offset) {
  int thread = 0, threads = 1;
#ifdef _OPENMP
  thread = omp_get_thread_num();
  threads = omp_get_num_threads();
#endif
  ThreadRun run;
  run.first_block = blocks * thread / threads;
  run.end_block = blocks * (thread + 1) / threads;
  run.begin = std::min(n, run.first_block * block_size);
  run.end = std::min(n, run.end_block * block_size);
  run.deferred_end = thread == 0 ? run.begin : std::min(run.end, run.begin + max_offset);
  return run;
}

void for_each_block(std::int64_t blocks, bool parallel,
                    void (*body)(const void* context, std::int64_t block), const void* context) {
  // thread_run's split, so every block-parallel pass gives a block to the same core.
#pragma omp parallel if (parallel)
  {
    const ThreadRun run = thread_run(blocks, 1, blocks, 0);
    for (std::int64_t block = run.first_block; block < run.end_block; ++block) body(context, block);
  }
}

void for_each_block_balanced(std::int64_t blocks, bool parallel,
                             void (*body)(const void* context, std::int64_t block),
                             const void* context) {
#pragma omp parallel for schedule(dynamic, 1) if (parallel)
  for (std::int64_t block = 0; block < blocks; ++block) body(context, block);
}

}  // namespace drapelab::kernels
