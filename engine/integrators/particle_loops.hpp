// The per-particle passes of an explicit step (the Euler updates and the health scan), on plain
// arrays. Like spring_family_loops.hpp, this
// header and its source include no Eigen: the source is built with OpenMP for the build machine's
// CPU. Every value is computed by the same expression whichever thread computes it, so results are
// bitwise identical for any thread count.
#pragma once

#include <cstdint>

#include "core/thread_blocks.hpp"

namespace drapelab::kernels {

// x, v, f and every per-coordinate array below are 3 x n, packed as in ClothState: the passes run
// over the 3n coordinates as one unit-stride array, so a per-particle quantity comes repeated for
// each of its three coordinates.

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

}  // namespace drapelab::kernels
