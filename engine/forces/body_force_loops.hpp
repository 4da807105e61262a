// Gravity and viscous air drag on every particle, the pass that starts each force evaluation, on
// plain arrays (no Eigen: built with OpenMP for the build machine's CPU, without fused
// multiply-adds, so that each pass gives the same bits on every CPU).
#pragma once

#include <cstdint>

namespace drapelab::kernels {

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

}  // namespace drapelab::kernels
