// Building a ClothModel from a regular grid of particles, and choosing which particles are pinned.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/continuum.hpp"

namespace drapelab {

enum class GridPlane {
  xz,
  xy
};  // xz: horizontal sheet (normal +y); xy: vertical sheet (normal +z)

struct SpringParams {
  double ks = 0.0;  // N/m
  double kd = 0.0;  // N*s/m
};

// Pin selectors of the scene format. Each resolves to a non-empty set of particles.
struct PinNamed {
  std::string name;
};  // corners, top_corners, edge_min_x, ..., center
struct PinGridCoord {
  int i = 0;
  int j = 0;
};  // grid coordinates
struct PinIndex {
  int index = 0;
};  // particle index k = j * nx + i
struct PinWithin {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0.0;
};  // m
using PinSelector = std::variant<PinNamed, PinGridCoord, PinIndex, PinWithin>;

// What every cloth shape has: its weight, contact thickness and spring constants per kind.
struct ClothPhysicsSpec {
  std::optional<double> mass;           // kg, total, split equally
  std::optional<double> areal_density;  // kg/m^2, times each vertex area
  double thickness = 0.005;             // m
  SpringParams stretch{2000.0, 1.0};
  SpringParams shear{200.0, 0.5};
  SpringParams bend{20.0, 0.1};
  // cloth.model: continuum when set: the builder adds the membrane and hinge elements
  // (continuum.hpp); the springs above stay for the Bullet cloths.
  std::optional<ContinuumParams> continuum;
};

struct GridClothSpec : ClothPhysicsSpec {
  Eigen::Vector2d size{1.0, 1.0};  // m: width along x, depth along the second axis
  int nx = 33;                     // particles along x
  int ny = 33;                     // particles along the second axis
  GridPlane plane = GridPlane::xz;
  Eigen::Vector3d center{0.0, 1.0, 0.0};               // m
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();  // deg, Euler (x, y, z) about the centre
  std::vector<PinSelector> pins;
};

// Names accepted by PinNamed on this plane (edge names follow the sheet's axes).
std::vector<std::string> pin_set_names(GridPlane plane);

// The particles a selector picks, in increasing order. Empty with `error` set when the selector is
// invalid for this grid (out of range, unknown name, or nothing inside a ball).
std::vector<int> select_pins(const GridClothSpec& spec, const PinSelector& selector,
                             std::string* error);

// Rest position of grid particle (i, j), exactly as the scene format defines it, then turned by the
// sheet's rotation about its centre.
Eigen::Vector3d grid_rest_position(const GridClothSpec& spec, int i, int j);

// Builds the immutable model: particles, triangles (two per cell: along one diagonal everywhere,
// or, with the continuum model, along diagonals that turn every row of cells), UVs,
// stretch/shear/bend springs with rest lengths, masses, vertex areas and pins. Preconditions
// (checked by the scene loader): nx, ny >= 1, nx * ny >= 2, a size within cloth_limits.hpp, exactly
// one of mass and areal_density, every pin selector valid. Throws std::invalid_argument otherwise.
ClothModel build_grid_cloth(const GridClothSpec& spec);

// The initial state: rest positions, each free particle offset along the (rotated) sheet normal by
// a uniform random amount in [-amplitude, amplitude] (m) drawn from `seed`; zero velocity.
ClothState initial_grid_state(const ClothModel& model, const GridClothSpec& spec, double amplitude,
                              std::uint64_t seed);

}  // namespace drapelab
