// Gravity and air drag (body_force_loops.hpp): sets f to weight minus drag; the springs then add
// theirs.
#include "forces/body_force_loops.hpp"

#include "core/thread_blocks.hpp"

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

}  // namespace drapelab::kernels
