// How large a cloth may be. Every builder checks its size against these before it allocates, and
// the scene loader checks them before it builds anything, so that a slip (rings: 20000, a support
// ring a hair inside the rim, an OBJ file of fans) is an error that states the limit instead of an
// allocation of many gigabytes or an int overflow. Within them a cloth takes at most about 600 MB
// to build; the loader holds the whole run's memory against the machine's (run_memory.hpp).
#pragma once

#include <optional>
#include <string>

namespace drapelab {

// A 1000 x 1000 grid: its run with all three solvers needs about 8 GB (scenes/loader's
// run_memory.hpp), and a step of it takes seconds; a larger cloth is refused from its numbers.
inline constexpr long long kMaxClothParticles = 1'000'000;
inline constexpr long long kMaxClothTriangles = 2'000'000;  // two per cell of that grid

// The counts that decide a cloth's size (doubles: the counts of a bad scene can exceed any
// integer).
struct ClothSize {
  double particles = 0.0;
  double springs = 0.0;
  double triangles = 0.0;
};

// A grid of nx x ny particles: exact counts (grid_cloth.hpp).
inline ClothSize grid_cloth_size(double nx, double ny) {
  const auto positive = [](double v) { return v > 0.0 ? v : 0.0; };
  ClothSize size;
  size.particles = nx * ny;
  size.springs = nx * positive(ny - 1) + ny * positive(nx - 1) +
                 2.0 * positive(nx - 1) * positive(ny - 1) + nx * positive(ny - 2) +
                 ny * positive(nx - 2);
  size.triangles = 2.0 * positive(nx - 1) * positive(ny - 1);
  return size;
}

// A cloth built from a triangle mesh: at most three springs per triangle (its edges, shared or not,
// and one spring across each interior edge).
inline ClothSize mesh_cloth_size(double vertices, double triangles) {
  return {vertices, 3.0 * triangles, triangles};
}

inline std::string count_text(double count) {
  return count < 9.2e18 ? std::to_string(static_cast<long long>(count)) : std::to_string(count);
}

// The first limit the size breaks, as a message ("gives 12566371 particles; at most 1000000 are
// allowed"), or nothing.
inline std::optional<std::string> cloth_size_problem(const ClothSize& size) {
  if (!(size.particles <= static_cast<double>(kMaxClothParticles)))
    return "gives " + count_text(size.particles) + " particles; at most " +
           count_text(static_cast<double>(kMaxClothParticles)) + " are allowed";
  if (!(size.triangles <= static_cast<double>(kMaxClothTriangles)))
    return "gives " + count_text(size.triangles) + " triangles; at most " +
           count_text(static_cast<double>(kMaxClothTriangles)) + " are allowed";
  return std::nullopt;
}

}  // namespace drapelab
