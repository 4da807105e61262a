// Per-particle passes of an explicit step (particle_loops.hpp). Each is one static-schedule loop:
// memory-bound work (a few flops per 24-byte column), so two cores mostly double the bandwidth from
// their own caches. Built without contraction into fused multiply-adds, so each pass gives the same
// bits on every CPU, and the update the bits of its plain expressions v + h (f m^-1) and x + h v.
// The body-force pass sets f to weight minus drag; the springs then add theirs.
#include "integrators/particle_loops.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace drapelab::kernels {

void set_body_forces(std::int64_t n, const double* weight, const double* mass, double air,
                     const double* v, double* f) {
#pragma omp parallel for simd schedule(simd : static) if (n >= kParallelParticles)
  for (std::int64_t k = 0; k < 3 * n; ++k) f[k] = weight[k] - air * (v[k] * mass[k]);
}

void set_body_forces_range(std::int64_t begin, std::int64_t end, const double* weight,
                           const double* mass, double air, const double* v, double* f) {
#pragma omp simd
  for (std::int64_t k = 3 * begin; k < 3 * end; ++k) f[k] = weight[k] - air * (v[k] * mass[k]);
}

namespace {

// Particles per block of the update passes: a block is updated and tested branch-free on
// unit-stride arrays (so both vectorise), and searched particle by particle only when the test
// fails.
constexpr std::int64_t kBlock = 256;

// Finite position and velocity, speed squared within the limit (m, m/s, m^2/s^2).
inline bool healthy(const double* x, const double* v, double max_speed_squared) {
  return std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]) && std::isfinite(v[0]) &&
         std::isfinite(v[1]) && std::isfinite(v[2]) &&
         v[0] * v[0] + v[1] * v[1] + v[2] * v[2] <= max_speed_squared;
}

constexpr std::int64_t kNone = std::numeric_limits<std::int64_t>::max();

// The first unhealthy particle of [begin, end), or kNone, after a quick test of every coordinate:
// each |x| finite and each |v| within max_speed / sqrt(3) puts every speed within max_speed (a cube
// inside the ball), so a healthy block costs one vectorised pass over memory that is already in
// cache.
std::int64_t first_unhealthy_in(std::int64_t begin, std::int64_t end, const double* x,
                                const double* v, double max_speed_squared) {
  const double big = std::numeric_limits<double>::max();
  // Margin for rounding; never above the largest double, so an infinite velocity fails even when
  // the limit is so large that its square overflows.
  const double component_limit = std::min(big, std::sqrt(max_speed_squared / 3.0) * (1.0 - 1e-12));
  int outside = 0;
#pragma omp simd reduction(| : outside)
  for (std::int64_t k = 3 * begin; k < 3 * end; ++k)
    outside |= ((std::fabs(x[k]) <= big) & (std::fabs(v[k]) <= component_limit)) ? 0 : 1;
  if (!outside) return kNone;
  for (std::int64_t i = begin; i < end; ++i)
    if (!healthy(x + 3 * i, v + 3 * i, max_speed_squared)) return i;
  return kNone;
}

// Particles [begin, end) on the calling thread, block by block: update(first coordinate, end
// coordinate), then the health test. Every particle is updated; returns the first unhealthy one
// (blocks in increasing order) or kNone.
template <typename Update>
std::int64_t update_and_scan_range(std::int64_t begin, std::int64_t end, const double* x,
                                   const double* v, double max_speed_squared, Update update) {
  std::int64_t first = kNone;
  for (std::int64_t block = begin; block < end; block += kBlock) {
    const std::int64_t block_end = std::min(end, block + kBlock);
    update(3 * block, 3 * block_end);
    if (first == kNone) first = first_unhealthy_in(block, block_end, x, v, max_speed_squared);
  }
  return first;
}

// The same over the whole cloth, its blocks shared among the threads. Returns the first unhealthy
// particle (the minimum over blocks: the same for any thread count), or -1.
template <typename Update>
std::int64_t update_and_scan(std::int64_t n, const double* x, const double* v,
                             double max_speed_squared, Update update) {
  const std::int64_t blocks = (n + kBlock - 1) / kBlock;
  std::int64_t first = kNone;
#pragma omp parallel for schedule(static) reduction(min : first) if (n >= kParallelParticles)
  for (std::int64_t block = 0; block < blocks; ++block) {
    const std::int64_t begin = block * kBlock;
    first = std::min(first, update_and_scan_range(begin, std::min(n, begin + kBlock), x, v,
                                                  max_speed_squared, update));
  }
  return first == kNone ? -1 : first;
}

}  // namespace

std::int64_t first_unhealthy_particle(std::int64_t n, const double* x, const double* v,
                                      double max_speed_squared) {
  return update_and_scan(n, x, v, max_speed_squared, [](std::int64_t, std::int64_t) {});
}

namespace {

// The two Euler updates of coordinates [begin, end), each the one expression every pass and range
// below uses, so a fused update gives the bits of the whole-cloth pass.
void symplectic_euler_update(std::int64_t begin, std::int64_t end, const double* inverse_mass,
                             const double* f, double h, double* x, double* v) {
#pragma omp simd
  for (std::int64_t k = begin; k < end; ++k) {
    const double vk = v[k] + h * (f[k] * inverse_mass[k]);  // v(n+1) = v(n) + a(n) h
    v[k] = vk;
    x[k] += h * vk;  // x(n+1) = x(n) + v(n+1) h
  }
}

void explicit_euler_update(std::int64_t begin, std::int64_t end, const double* inverse_mass,
                           const double* f, double h, double* x, double* v) {
#pragma omp simd
  for (std::int64_t k = begin; k < end; ++k) {
    const double vk = v[k];
    x[k] += h * vk;                            // x(n+1) = x(n) + v(n) h
    v[k] = vk + h * (f[k] * inverse_mass[k]);  // v(n+1) = v(n) + a(n) h
  }
}

}  // namespace

std::int64_t symplectic_euler_pass(std::int64_t n, const double* inverse_mass, const double* f,
                                   double h, double* x, double* v, double max_speed_squared) {
  return update_and_scan(n, x, v, max_speed_squared, [=](std::int64_t begin, std::int64_t end) {
    symplectic_euler_update(begin, end, inverse_mass, f, h, x, v);
  });
}

std::int64_t explicit_euler_pass(std::int64_t n, const double* inverse_mass, const double* f,
                                 double h, double* x, double* v, double max_speed_squared) {
  return update_and_scan(n, x, v, max_speed_squared, [=](std::int64_t begin, std::int64_t end) {
    explicit_euler_update(begin, end, inverse_mass, f, h, x, v);
  });
}

namespace {

// Particles per chunk of the broad phase: the chunk's test results stay in L1 between its two
// passes.
constexpr int kNearChunk = 256;

// hit[i - begin] = 1 when particle i of [begin, end) passes the collider's broad-phase test, else
// 0, in one vectorised loop. Returns how many passed.
int near_test(const NearCollider& collider, const double* __restrict x, int begin, int end,
              std::int32_t* __restrict hit) {
  int passed = 0;
  if (collider.plane) {
    const double nx = collider.normal[0], ny = collider.normal[1], nz = collider.normal[2];
    const double offset = collider.offset, radius = collider.radius;
#pragma omp simd reduction(+ : passed)
    for (int i = begin; i < end; ++i) {
      hit[i - begin] =
          (nx * x[3 * i] + ny * x[3 * i + 1] + nz * x[3 * i + 2] - offset < radius) ? 1 : 0;
      passed += hit[i - begin];
    }
    return passed;
  }
  const double lx = collider.low[0], ly = collider.low[1], lz = collider.low[2];
  const double hx = collider.high[0], hy = collider.high[1], hz = collider.high[2];
  const double cx = collider.center[0], cy = collider.center[1], cz = collider.center[2];
  const double reach_squared = collider.reach_squared;
#pragma omp simd reduction(+ : passed)
  for (int i = begin; i < end; ++i) {
    const double px = x[3 * i], py = x[3 * i + 1], pz = x[3 * i + 2];
    const double dx = px - cx, dy = py - cy, dz = pz - cz;
    const bool inside = (px >= lx) & (px <= hx) & (py >= ly) & (py <= hy) & (pz >= lz) &
                        (pz <= hz) & (dx * dx + dy * dy + dz * dz < reach_squared);
    hit[i - begin] = inside ? 1 : 0;
    passed += hit[i - begin];
  }
  return passed;
}

}  // namespace

int near_particles(const NearCollider& collider, const double* x, int begin, int end, int* near) {
  // Two passes per chunk: the test of every particle (vectorised, counting those that pass), then
  // the list of those that passed (each index written always and kept only when its test held: no
  // branch), skipped for a chunk where none or all passed.
  std::int32_t hit[kNearChunk];
  int count = 0;
  for (int chunk = begin; chunk < end; chunk += kNearChunk) {
    const int chunk_end = std::min(end, chunk + kNearChunk);
    const int passed = near_test(collider, x, chunk, chunk_end, hit);
    if (passed == 0) continue;          // a chunk far from the collider: nothing to list
    if (passed == chunk_end - chunk) {  // a chunk wholly near it: every index
      for (int i = chunk; i < chunk_end; ++i) near[count++] = i;
      continue;
    }
    for (int i = chunk; i < chunk_end; ++i) {
      near[count] = i;
      count += hit[i - chunk];
    }
  }
  return count;
}

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

std::int64_t euler_range(bool symplectic, std::int64_t begin, std::int64_t end,
                         const double* inverse_mass, const double* f, double h, double* x,
                         double* v, double max_speed_squared) {
  const auto update = symplectic ? symplectic_euler_update : explicit_euler_update;
  const std::int64_t first = update_and_scan_range(
      begin, end, x, v, max_speed_squared,
      [=](std::int64_t b, std::int64_t e) { update(b, e, inverse_mass, f, h, x, v); });
  return first == kNone ? -1 : first;
}

}  // namespace drapelab::kernels
