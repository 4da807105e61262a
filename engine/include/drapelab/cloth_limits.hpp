// How large a cloth may be. Every builder checks its size against these before it allocates, and
// the scene loader checks them before it builds anything, so that a slip (rings: 20000, a support
// ring a hair inside the rim, an OBJ file of fans) is an error that states the limit instead of an
// allocation of many gigabytes or an int overflow.
#pragma once

#include <optional>
#include <string>

namespace drapelab {

inline constexpr long long kMaxClothParticles = 4'000'000;  // a 2000 x 2000 grid
inline constexpr long long kMaxClothTriangles = 8'000'000;  // two per cell of that grid
inline constexpr double kMaxClothBytes = 2e9;               // bytes, estimated_cloth_bytes

// The counts that decide a cloth's memory. A disc or a mesh finds its springs through a map of its
// edges while it is built, so it costs more per triangle than a grid.
struct ClothSize {
  double particles = 0.0;
  double springs = 0.0;
  double triangles = 0.0;
  bool edge_map = false;  // built from triangles (disc, mesh): the edge map's transient memory
};

// Bytes per item of the model's arrays: a particle holds its rest position (24), mass (8), inverse
// mass (8), vertex area (8) and UV (16); a spring its two indices (8), rest length, ks and kd (24)
// and kind (1), rounded up; a triangle its three indices. Building from triangles adds about 120
// bytes per triangle for the map from each edge to its opposite vertices.
inline constexpr double kBytesPerParticle = 64.0;
inline constexpr double kBytesPerSpring = 40.0;
inline constexpr double kBytesPerTriangle = 12.0;
inline constexpr double kBytesPerTriangleEdgeMap = 120.0;

// Estimated bytes to build the cloth (doubles: the counts of a bad scene can exceed any integer).
inline double estimated_cloth_bytes(const ClothSize& size) {
  return kBytesPerParticle * size.particles + kBytesPerSpring * size.springs +
         (kBytesPerTriangle + (size.edge_map ? kBytesPerTriangleEdgeMap : 0.0)) * size.triangles;
}

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
  return {vertices, 3.0 * triangles, triangles, true};
}

inline std::string count_text(double count) {
  return count < 9.2e18 ? std::to_string(static_cast<long long>(count)) : std::to_string(count);
}

// The first limit the size breaks, as a message ("gives 12566371 particles; at most 4000000 are
// allowed"), or nothing.
inline std::optional<std::string> cloth_size_problem(const ClothSize& size) {
  if (!(size.particles <= static_cast<double>(kMaxClothParticles)))
    return "gives " + count_text(size.particles) + " particles; at most " +
           count_text(static_cast<double>(kMaxClothParticles)) + " are allowed";
  if (!(size.triangles <= static_cast<double>(kMaxClothTriangles)))
    return "gives " + count_text(size.triangles) + " triangles; at most " +
           count_text(static_cast<double>(kMaxClothTriangles)) + " are allowed";
  const double bytes = estimated_cloth_bytes(size);
  if (!(bytes <= kMaxClothBytes))
    return "needs about " + count_text(bytes / 1e6) + " MB to build (" +
           count_text(size.particles) + " particles, " + count_text(size.springs) + " springs, " +
           count_text(size.triangles) + " triangles); at most " + count_text(kMaxClothBytes / 1e6) +
           " MB are allowed";
  return std::nullopt;
}

}  // namespace drapelab
