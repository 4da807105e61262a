// Vectorised, threaded loops of the spring fast path (spring_family_loops.hpp). Runs are independent
// (no two springs of a family share a first particle, nor a second one), so they are split among
// threads with a static schedule; no sum depends on the thread count.
#include "drapelab/spring_family_loops.hpp"

#include <cmath>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace drapelab::kernels {
namespace {

// Below this many springs in a family, starting threads costs more than it saves (a parallel
// region costs a few microseconds; a spring about a nanosecond).
constexpr std::int64_t kParallelSprings = 8192;

}  // namespace

void set_thread_count(int threads) {
#ifdef _OPENMP
  omp_set_num_threads(threads < 1 ? 1 : threads);
#else
  (void)threads;
#endif
}

int thread_count() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

void family_forces(const PackedState& s, const SpringFamily& family, double* const t[3]) {
  const std::int64_t runs = static_cast<std::int64_t>(family.run_start.size());
  const std::int64_t offset = 3 * static_cast<std::int64_t>(family.offset);  // doubles between the ends
  const double* rest = family.rest.data();
  const double* ks = family.ks.data();
  const double* kd = family.kd.data();
  double* tx = t[0];
  double* ty = t[1];
  double* tz = t[2];
#pragma omp parallel for schedule(static) if (family.size() >= kParallelSprings)
  for (std::int64_t r = 0; r < runs; ++r) {
    const std::int32_t length = family.run_length[r], slot = family.run_slot[r];
    const double* x = s.x + 3 * static_cast<std::int64_t>(family.run_start[r]);
    const double* v = s.v + 3 * static_cast<std::int64_t>(family.run_start[r]);
#pragma omp simd
    for (std::int32_t k = 0; k < length; ++k) {
      const std::int64_t a = 3 * static_cast<std::int64_t>(k), b = a + offset;
      const double dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
      const double dvx = v[a] - v[b], dvy = v[a + 1] - v[b + 1], dvz = v[a + 2] - v[b + 2];
      const double l = std::sqrt(dx * dx + dy * dy + dz * dz);
      const double inverse = l > 0.0 ? 1.0 / l : 0.0;  // a zero-length spring has no direction: no force
      const std::int32_t e = slot + k;
      const double magnitude = ks[e] * (l - rest[e]) + kd[e] * (dvx * dx + dvy * dy + dvz * dz) * inverse;  // N
      const double scale = -magnitude * inverse;
      tx[e] = scale * dx;
      ty[e] = scale * dy;
      tz[e] = scale * dz;
    }
  }
}

void family_scatter(const SpringFamily& family, double* const t[3], double* f) {
  const std::int64_t runs = static_cast<std::int64_t>(family.run_start.size());
  const std::int64_t offset = 3 * static_cast<std::int64_t>(family.offset);
  const bool parallel = family.size() >= kParallelSprings;
  const double* tx = t[0];
  const double* ty = t[1];
  const double* tz = t[2];
#pragma omp parallel for schedule(static) if (parallel)
  for (std::int64_t r = 0; r < runs; ++r) {
    double* out = f + 3 * static_cast<std::int64_t>(family.run_start[r]);
    const std::int32_t slot = family.run_slot[r];
#pragma omp simd
    for (std::int32_t k = 0; k < family.run_length[r]; ++k) {
      out[3 * k] += tx[slot + k];
      out[3 * k + 1] += ty[slot + k];
      out[3 * k + 2] += tz[slot + k];
    }
  }
  // The second particles, in a pass of their own: k + offset may be another run's first particle.
#pragma omp parallel for schedule(static) if (parallel)
  for (std::int64_t r = 0; r < runs; ++r) {
    double* out = f + 3 * static_cast<std::int64_t>(family.run_start[r]) + offset;
    const std::int32_t slot = family.run_slot[r];
#pragma omp simd
    for (std::int32_t k = 0; k < family.run_length[r]; ++k) {
      out[3 * k] -= tx[slot + k];
      out[3 * k + 1] -= ty[slot + k];
      out[3 * k + 2] -= tz[slot + k];
    }
  }
}

}  // namespace drapelab::kernels
