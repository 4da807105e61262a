// cloth: the shape (grid, disc or mesh), its geometry, mass, springs (a material preset first, then
// the explicit keys), and the pin selectors. Pins are checked in finish(), once the drape support
// (which places a disc's rings) is known.
#pragma once

#include <filesystem>

#include "drapelab/scene/scene.hpp"
#include "scene_key.hpp"
#include "yaml_reader.hpp"

namespace drapelab::scene {

class ClothReader {
 public:
  // `folder`: where relative paths (the mesh file) are found, the scene file's folder.
  ClothReader(SceneReader& reader, Scene& scene, std::filesystem::path folder);
  void read(const YAML::Node& node);
  // Gives a disc a ring at the drape support's radius, then checks every pin selector on the shape.
  void finish();
  // The geometry was read without error, so the cloth can be built.
  bool geometry_ok() const { return geometry_ok_; }
  // With the geometry read: the cloth's particle count from its numbers (before it is built), and
  // an error at the key that sets it (cloth.resolution, cloth.rings or cloth.path).
  double particle_count() const;
  void size_error(const std::string& message);

 private:
  void read_shape(MapReader& cloth);
  void read_grid(MapReader& cloth);
  void read_disc(MapReader& cloth);
  void read_mesh(MapReader& cloth);
  void apply_material(MapReader& cloth);
  void read_mass(MapReader& cloth);
  // cloth.model and, by it, cloth.springs (springs) or cloth.continuum (continuum: the params, a
  // preset's first, and the springs derived from them).
  void read_model(MapReader& cloth);
  void read_springs(const YAML::Node& node);
  // One kind of spring: `ks` and `kd` are its rows in the key table (cloth.springs.KIND.ks).
  void read_spring_kind(MapReader& springs, const SceneKey& ks, const SceneKey& kd,
                        SpringParams& out);
  void read_pins(const YAML::Node& node);
  // cloth.self_collision, resolved: thickness defaults to the cloth's, static_friction to friction.
  void read_self_collision(MapReader& cloth);
  // A pin given as a map; its `attach` (a collider's name) goes to `attach`.
  std::optional<PinSelector> read_pin_map(const YAML::Node& item, const std::string& path,
                                          std::string& attach);
  void check_pin_attach();
  double particle_spacing() const;  // m, for material presets and the continuum's springs
  // An undefined node: an error about a whole map-valued key of the cloth is placed at the key's
  // own line (SceneReader::where), not at the map's first entry.
  static YAML::Node at_key() { return YAML::Node(YAML::NodeType::Undefined); }
  void check_disc_size();

  SceneReader& r_;
  Scene& scene_;
  std::filesystem::path folder_;
  bool geometry_ok_ = false;
  YAML::Node cloth_node_;               // the cloth map, for errors about the whole cloth
  YAML::Node rings_node_;               // a disc's rings (undefined when left out)
  std::vector<YAML::Node> pin_nodes_;   // one per selector in scene_.cloth.grid.pins, for messages
  std::vector<std::string> pin_paths_;  // ... and its key path (cloth.pins.K)
  // The material's continuum parameters (cloth.material), the defaults of cloth.continuum.
  std::optional<ContinuumParams> preset_continuum_;
};

}  // namespace drapelab::scene
