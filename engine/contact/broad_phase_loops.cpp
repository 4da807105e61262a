// The contact broad phase (broad_phase_loops.hpp): a vectorised test of every particle of a
// chunk, then the list of those that passed.
#include "contact/broad_phase_loops.hpp"

#include <algorithm>

namespace drapelab::kernels {

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

}  // namespace drapelab::kernels
