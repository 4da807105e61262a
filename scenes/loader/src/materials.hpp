// Material presets (cloth.material): fabrics described by measured physical properties, turned into
// spring parameters for the cloth's own particle spacing, or into the continuum model's parameters
// (cloth.model: continuum). Numbers and their sources: docs/materials.md.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "drapelab/continuum.hpp"
#include "drapelab/grid_cloth.hpp"

namespace drapelab::scene {

struct Material {
  std::string name;
  double areal_density;  // kg/m^2, the fabric's weight
  double thickness;      // m
  double tensile;        // N/m, in-plane tensile stiffness E*t (softened, see docs/materials.md)
  double shear;          // N/m, in-plane shear stiffness G*t
  double poisson;        // in-plane Poisson ratio nu, for the continuum model, in [0, 0.5)
  double bending;        // N*m, bending rigidity B per unit width
  double damping_time;   // s, beta in kd = beta * ks (stiffness-proportional damping)
  double air_damping;    // 1/s
};

const std::vector<Material>& materials();
std::optional<Material> find_material(const std::string& name);
std::vector<std::string> material_names();

// Spring parameters of a material at particle spacing `spacing` (m):
//   stretch ks = tensile, shear ks = shear (a square cell of springs has the membrane's stiffness
//   whatever its size), bend ks = bend_spring_stiffness(B, spacing), and kd = beta ks for each.
struct MaterialSprings {
  SpringParams stretch, shear, bend;
};
MaterialSprings material_springs(const Material& material, double spacing);

// The bend spring's ks (N/m) for a bending rigidity B (N*m) at particle spacing `spacing` (m):
// 16 B / (spacing^2 theta^2) with theta = 0.3 rad (the bend spring's energy, which grows as
// theta^4, matches the continuum's 1/2 B kappa^2 per hinge at a typical drape angle).
double bend_spring_stiffness(double bending_rigidity, double spacing);

// The continuum model's parameters of a material (cloth.model: continuum): stretch_modulus =
// tensile, poisson, bending_rigidity = bending, damping = damping_time. The preset's shear is not
// used: the isotropic membrane's shear modulus is stretch_modulus / (2 (1 + poisson)).
ContinuumParams material_continuum(const Material& material);

// The springs a continuum cloth still carries (for the Bullet cloths and the stretch metrics), at
// particle spacing `spacing` (m), by material_springs' formula: stretch ks = stretch_modulus, shear
// ks = stretch_modulus / (2 (1 + poisson)), bend ks = bend_spring_stiffness(bending_rigidity,
// spacing), and kd = damping ks for each.
MaterialSprings continuum_springs(const ContinuumParams& params, double spacing);

}  // namespace drapelab::scene
