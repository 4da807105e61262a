// Material presets (materials.hpp). Sources and reasoning: docs/materials.md.
#include "materials.hpp"

namespace drapelab::scene {
namespace {

// Springs of the three kinds with stiffness-proportional damping: kd = beta ks.
MaterialSprings damped_springs(double stretch_ks, double shear_ks, double bend_ks, double beta) {
  MaterialSprings s;
  s.stretch = {stretch_ks, beta * stretch_ks};
  s.shear = {shear_ks, beta * shear_ks};
  s.bend = {bend_ks, beta * bend_ks};
  return s;
}

}  // namespace

const std::vector<Material>& materials() {
  // name, areal density (kg/m^2), thickness (m), tensile (N/m), shear (N/m), Poisson, bending
  // (N*m), beta (s), air damping (1/s)
  static const std::vector<Material> table = {
      {"silk", 0.080, 0.0002, 600.0, 15.0, 0.35, 2.0e-6, 5e-5, 2.0},      // 19 momme charmeuse
      {"cotton", 0.130, 0.0003, 1000.0, 55.0, 0.3, 1.0e-5, 5e-5, 1.0},    // poplin / broadcloth
      {"denim", 0.400, 0.0008, 2000.0, 170.0, 0.2, 1.0e-4, 5e-5, 0.5},    // 12 oz/yd^2
      {"leather", 0.800, 0.0010, 3000.0, 150.0, 0.4, 1.0e-4, 5e-5, 0.3},  // garment leather, 1 mm
  };
  return table;
}

std::optional<Material> find_material(const std::string& name) {
  for (const auto& m : materials())
    if (m.name == name) return m;
  return std::nullopt;
}

std::vector<std::string> material_names() {
  std::vector<std::string> names;
  for (const auto& m : materials()) names.push_back(m.name);
  return names;
}

double bend_spring_stiffness(double bending_rigidity, double spacing) {
  constexpr double kDrapeAngle = 0.3;  // rad, the hinge angle at which bend energy is matched
  return 16.0 * bending_rigidity / (spacing * spacing * kDrapeAngle * kDrapeAngle);
}

MaterialSprings material_springs(const Material& material, double spacing) {
  return damped_springs(material.tensile, material.shear,
                        bend_spring_stiffness(material.bending, spacing), material.damping_time);
}

ContinuumParams material_continuum(const Material& material) {
  ContinuumParams params;
  params.stretch_modulus = material.tensile;
  params.poisson = material.poisson;
  params.bending_rigidity = material.bending;
  params.damping = material.damping_time;
  return params;
}

MaterialSprings continuum_springs(const ContinuumParams& params, double spacing) {
  const double shear = params.stretch_modulus / (2.0 * (1.0 + params.poisson));
  return damped_springs(params.stretch_modulus, shear,
                        bend_spring_stiffness(params.bending_rigidity, spacing), params.damping);
}

}  // namespace drapelab::scene
