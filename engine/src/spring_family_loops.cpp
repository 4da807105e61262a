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

void family_forces(const SoaState& s, const SpringFamily& family, double* const t[3]) {
  const std::int64_t runs = static_cast<std::int64_t>(family.run_start.size());
  const std::int32_t offset = family.offset;
  const double* rest = family.rest.data();
  const double* ks = family.ks.data();
  const double* kd = family.kd.data();
  double* tx = t[0];
  double* ty = t[1];
  double* tz = t[2];
#pragma omp parallel for schedule(static) if (family.size() >= kParallelSprings)
  for (std::int64_t r = 0; r < runs; ++r) {
    const std::int32_t first = family.run_start[r], length = family.run_length[r], slot = family.run_slot[r];
    const double* x0 = s.x[0] + first;
    const double* y0 = s.x[1] + first;
    const double* z0 = s.x[2] + first;
    const double* vx0 = s.v[0] + first;
    const double* vy0 = s.v[1] + first;
    const double* vz0 = s.v[2] + first;
#pragma omp simd
    for (std::int32_t k = 0; k < length; ++k) {
      const double dx = x0[k] - x0[k + offset], dy = y0[k] - y0[k + offset], dz = z0[k] - z0[k + offset];
      const double dvx = vx0[k] - vx0[k + offset], dvy = vy0[k] - vy0[k + offset], dvz = vz0[k] - vz0[k + offset];
      const double length_squared = dx * dx + dy * dy + dz * dz;
      const double l = std::sqrt(length_squared);
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

void family_scatter(const SpringFamily& family, double* const t[3], double* const f[3]) {
  const std::int64_t runs = static_cast<std::int64_t>(family.run_start.size());
  const std::int32_t offset = family.offset;
  const bool parallel = family.size() >= kParallelSprings;
#pragma omp parallel for schedule(static) if (parallel)
  for (std::int64_t r = 0; r < runs; ++r)
    for (int c = 0; c < 3; ++c) {
      double* out = f[c] + family.run_start[r];
      const double* in = t[c] + family.run_slot[r];
#pragma omp simd
      for (std::int32_t k = 0; k < family.run_length[r]; ++k) out[k] += in[k];
    }
  // The second particles, in a pass of their own: k + offset may be another run's first particle.
#pragma omp parallel for schedule(static) if (parallel)
  for (std::int64_t r = 0; r < runs; ++r)
    for (int c = 0; c < 3; ++c) {
      double* out = f[c] + family.run_start[r] + offset;
      const double* in = t[c] + family.run_slot[r];
#pragma omp simd
      for (std::int32_t k = 0; k < family.run_length[r]; ++k) out[k] -= in[k];
    }
}

}  // namespace drapelab::kernels
