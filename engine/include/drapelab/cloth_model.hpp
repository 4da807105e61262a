// ClothModel: the cloth as built. Immutable after build; every derived value is computed once by
// the builder (rest lengths, masses, vertex areas, spring lists), never lazily. Indices, not
// pointers.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace drapelab {

struct ContinuumElements;  // continuum.hpp

// The role a spring plays in the network; each kind has its own ks and kd in a scene.
enum class SpringKind : std::uint8_t {
  stretch = 0,  // structural: grid neighbours
  shear = 1,    // both diagonals of a grid cell
  bend = 2,     // skip-one neighbours along a grid line
};
inline constexpr int kSpringKindCount = 3;
const char* spring_kind_name(SpringKind kind);

// Springs as a structure of arrays, so the force loop streams through contiguous memory.
struct SpringSet {
  std::vector<std::int32_t> v0;     // first particle index
  std::vector<std::int32_t> v1;     // second particle index
  std::vector<double> rest_length;  // m, |X(v0) - X(v1)| in the rest pose
  std::vector<double> ks;           // N/m
  std::vector<double> kd;           // N*s/m
  std::vector<SpringKind> kind;

  std::size_t size() const { return v0.size(); }
  std::size_t count(SpringKind k) const;
};

// Where the particles came from, for messages ("particle 17 (i=2, j=0)") and grid-only selectors.
struct GridLayout {
  int nx = 0;  // particles along x
  int ny = 0;  // particles along the sheet's second axis (+z for xz, +y for xy)
};

struct ClothModel {
  Eigen::Matrix3Xd rest_positions;  // m, 3 x N
  Eigen::VectorXd mass;             // kg per particle (pinned particles keep their share)
  Eigen::VectorXd inverse_mass;     // 1/kg; 0 for a pinned particle, which never moves
  Eigen::VectorXd vertex_area;      // m^2: 1/3 of the incident rest triangle areas (0 for a chain)
  Eigen::Matrix3Xi triangles;       // particle indices, counter-clockwise seen from the normal side
  Eigen::Matrix2Xd uvs;             // texture coordinates in [0, 1], one per particle
  SpringSet springs;
  GridLayout grid;           // nx = ny = 0 for a non-grid cloth
  double thickness = 0.005;  // m, contact distance kept from colliders
  // cloth.model: continuum: the membrane and hinge elements our solver uses in place of `springs`.
  // The springs are still built (from the same fabric properties) for the Bullet cloths, the
  // stretch metrics and the explicit step bound's springs-equivalent estimate.
  std::shared_ptr<const ContinuumElements> continuum;

  int particle_count() const { return static_cast<int>(rest_positions.cols()); }
  bool is_pinned(int i) const { return inverse_mass[i] == 0.0; }
  double total_mass() const { return mass.sum(); }
  double rest_area() const { return vertex_area.sum(); }
  bool uses_continuum() const { return continuum != nullptr; }
  // "particle 17 (i=2, j=0)" on a grid, "particle 17" otherwise.
  std::string describe_particle(int i) const;
};

}  // namespace drapelab
