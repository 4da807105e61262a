// The per-particle passes of an explicit step (body forces, the Euler updates, the health scan) and
// a block-parallel loop for the contact phase, on plain arrays. Like spring_family_loops.hpp, this
// header and its source include no Eigen: the source is built with OpenMP for the build machine's
// CPU. Every value is computed by the same expression whichever thread computes it, so results are
// bitwise identical for any thread count.
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

// x, v, f and every per-coordinate array below are 3 x n, packed as in ClothState: the passes run
// over the 3n coordinates as one unit-stride array, so a per-particle quantity comes repeated for
// each of its three coordinates.

// f = weight - air (v mass): gravity (weight = m g, N) and viscous air drag (air in 1/s, mass in
// kg), per coordinate. Overwrites f, so it also clears the force of the last evaluation.
void set_body_forces(std::int64_t n, const double* weight, const double* mass, double air,
                     const double* v, double* f);
// The same for particles begin <= i < end only, on the calling thread: for a pass that already runs
// in a parallel region (the spring fast path's first pass). The same expression, so the same bits.
void set_body_forces_range(std::int64_t begin, std::int64_t end, const double* weight,
                           const double* mass, double air, const double* v, double* f);

// The first particle (lowest index) whose position or velocity is not finite or whose speed squared
// exceeds max_speed_squared (m^2/s^2); -1 when every particle is healthy.
std::int64_t first_unhealthy_particle(std::int64_t n, const double* x, const double* v,
                                      double max_speed_squared);

// Symplectic Euler: v += h (f inverse_mass), then x += h v, with inverse_mass per coordinate (0
// holds a pinned particle). Returns first_unhealthy_particle of the new state, scanned in the same
// pass (the state is read only once).
std::int64_t symplectic_euler_pass(std::int64_t n, const double* inverse_mass, const double* f,
                                   double h, double* x, double* v, double max_speed_squared);
// Forward Euler: x += h v with the old v, then v += h (f m^-1); returns as symplectic_euler_pass.
std::int64_t explicit_euler_pass(std::int64_t n, const double* inverse_mass, const double* f,
                                 double h, double* x, double* v, double max_speed_squared);

// Either Euler update (symplectic when `symplectic`, else forward) of particles begin <= i < end
// only, on the calling thread, with the same expressions as the passes above (so the same bits):
// for a phase that already holds those particles in cache, such as the contact phase's blocks.
// Returns the first unhealthy particle of the range, or -1.
std::int64_t euler_range(bool symplectic, std::int64_t begin, std::int64_t end,
                         const double* inverse_mass, const double* f, double h, double* x,
                         double* v, double max_speed_squared);

// The contact broad phase for one posed collider, in plain numbers: a plane keeps the particles
// less than `radius` above it; any other shape those inside its bounding box and bounding sphere
// (both grown by the particle radius). Lengths in m.
struct NearCollider {
  bool plane = false;
  double normal[3] = {0.0, 0.0, 0.0};                          // plane: unit world normal
  double offset = 0.0;                                         // plane: n . p of a point on it
  double radius = 0.0;                                         // plane: the particle radius
  double low[3] = {0.0, 0.0, 0.0}, high[3] = {0.0, 0.0, 0.0};  // bounding box corners
  double center[3] = {0.0, 0.0, 0.0};                          // bounding sphere centre
  double reach_squared = 0.0;  // (bounding radius + particle radius)^2
};

// Writes to `near` (room for end - begin) the particles begin <= i < end that may touch the
// collider, in increasing order, and returns how many. A branch-free test per particle, so it
// vectorises.
int near_particles(const NearCollider& collider, const double* x, int begin, int end, int* near);

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

// The same for any callable body(block).
template <typename Body>
void for_each_block(std::int64_t blocks, bool parallel, const Body& body) {
  for_each_block(
      blocks, parallel,
      [](const void* context, std::int64_t block) { (*static_cast<const Body*>(context))(block); },
      &body);
}

}  // namespace drapelab::kernels
