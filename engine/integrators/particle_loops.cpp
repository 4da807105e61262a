// Per-particle passes of an explicit step (particle_loops.hpp). Each is one static-schedule loop:
// memory-bound work (a few flops per 24-byte column), so two cores mostly double the bandwidth from
// their own caches. Built without contraction into fused multiply-adds, so each pass gives the same
// bits on every CPU, and the update the bits of its plain expressions v + h (f m^-1) and x + h v.
#include "integrators/particle_loops.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/thread_blocks.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace drapelab::kernels {

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
