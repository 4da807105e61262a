// The ground floor's threading: fixed blocks of particles and how the threads share them. Every
// threaded pass of the engine splits its work this way, never by the thread count alone, so that
// every sum runs in the same order and results are bitwise identical for any thread count. No
// Eigen: the loops that include this are built with OpenMP for the build machine's CPU.
#pragma once

#include <cstdint>

namespace drapelab::kernels {

// Below this many particles a per-particle pass costs less than starting the threads (a parallel
// region costs a few microseconds): every threaded particle phase runs on one thread below it.
inline constexpr std::int64_t kParallelParticles = 4096;
// Particles per block of the spring kernel's gather (spring_family_loops.hpp) and of the contact
// phase (contact_model.hpp). One size for both: a thread's run of blocks (thread_run) is then the
// same particles in both, so the contact phase can run inside the spring kernel's parallel region
// on the particles each thread has just gathered. Fixed, never derived from the thread count, so
// every sum runs in the same order on any machine.
inline constexpr std::int64_t kPhaseBlock = 512;

// Runs body(context, block) for block = 0 .. blocks - 1, each thread taking one contiguous run of
// blocks, as the other passes split the particles: each core then works on the particles already in
// its own cache (handing blocks out round robin instead would make the next pass wait on lines the
// other core has read, and cost more than it balances). Threads start only when `parallel` is true;
// body must write only what its block owns. A function pointer and a context, so nothing is
// allocated.
void for_each_block(std::int64_t blocks, bool parallel,
                    void (*body)(const void* context, std::int64_t block), const void* context);

// Inside an OpenMP parallel region (or outside one, as the only thread): the calling thread's share
// of `blocks` blocks of `block_size` particles out of n, one contiguous run per thread, and how far
// its first particles must wait for a barrier when particle i reads slots i and i - offset (offset
// up to max_offset) computed block by block: the first max_offset particles of every run but the
// first read slots of the previous thread's run.
struct ThreadRun {
  std::int64_t first_block = 0, end_block = 0;  // blocks [first_block, end_block)
  std::int64_t begin = 0, end = 0;              // particles [begin, end)
  std::int64_t deferred_end = 0;  // particles [begin, deferred_end) wait for the barrier
};
ThreadRun thread_run(std::int64_t blocks, std::int64_t block_size, std::int64_t n,
                     std::int64_t max_offset);

// Runs body(context, block) for every block, each thread taking the next block not yet taken: for
// passes whose blocks differ widely in cost (a search where part of the cloth is crowded) and that
// write only per-block results, so which thread ran a block does not change the result.
void for_each_block_balanced(std::int64_t blocks, bool parallel,
                             void (*body)(const void* context, std::int64_t block),
                             const void* context);
template <typename Body>
void for_each_block_balanced(std::int64_t blocks, bool parallel, const Body& body) {
  for_each_block_balanced(
      blocks, parallel,
      [](const void* context, std::int64_t block) { (*static_cast<const Body*>(context))(block); },
      &body);
}

// The same for any callable body(block).
template <typename Body>
void for_each_block(std::int64_t blocks, bool parallel, const Body& body) {
  for_each_block(
      blocks, parallel,
      [](const void* context, std::int64_t block) { (*static_cast<const Body*>(context))(block); },
      &body);
}

}  // namespace drapelab::kernels
