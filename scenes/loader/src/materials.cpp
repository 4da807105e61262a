// Material presets (materials.hpp). Sources and reasoning: docs/materials.md.
#include "materials.hpp"

namespace drapelab::scene {

const std::vector<Material>& materials() {
  // name, areal density (kg/m^2), thickness (m), tensile (N/m), shear (N/m), bending (N*m),
  // beta (s), air damping (1/s)
  static const std::vector<Material> table = {
      {"silk", 0.080, 0.0002, 600.0, 15.0, 2.0e-6, 5e-5, 2.0},       // 19 momme charmeuse
      {"cotton", 0.130, 0.0003, 1000.0, 55.0, 1.0e-5, 5e-5, 1.0},    // poplin / broadcloth
      {"denim", 0.400, 0.0008, 2000.0, 170.0, 1.0e-4, 5e-5, 0.5},    // 12 oz/yd^2
      {"leather", 0.800, 0.0010, 3000.0, 150.0, 1.0e-4, 5e-5, 0.3},  // garment leather, 1 mm
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

MaterialSprings material_springs(const Material& material, double spacing) {
  constexpr double kDrapeAngle = 0.3;  // rad, the hinge angle at which bend energy is matched
  const double bend_ks = 16.0 * material.bending / (spacing * spacing * kDrapeAngle * kDrapeAngle);
  MaterialSprings s;
  s.stretch = {material.tensile, material.damping_time * material.tensile};
  s.shear = {material.shear, material.damping_time * material.shear};
  s.bend = {bend_ks, material.damping_time * bend_ks};
  return s;
}

}  // namespace drapelab::scene
