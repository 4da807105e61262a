// Scene loader: reads every key of shared/scene-format.md, checks it, fills in defaults.
#include "drapelab/scene/scene_loader.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "drapelab/scene/number_format.hpp"
#include "drapelab/stability.hpp"
#include "collider_reader.hpp"
#include "solver_reader.hpp"
#include "overrides.hpp"
#include "run_limits.hpp"
#include "yaml_reader.hpp"

namespace drapelab::scene {
namespace {

// Keys of the contract that later versions bring: named so the message says so, never ignored.
const std::string kLaterCloth = "is not available yet in this version of drapelab";

bool valid_name(const std::string& name) {
  static const std::regex pattern("[a-z0-9_-]+");
  return std::regex_match(name, pattern);
}

class SceneBuilder {
 public:
  explicit SceneBuilder(SceneReader& reader) : r_(reader) {}

  Scene build(const YAML::Node& root) {
    MapReader top(r_, root, "",
                  {"name", "description", "duration", "frame_rate", "gravity", "seed", "cloth",
                   "colliders", "contact", "solvers", "metrics", "output"});
    if (!top.valid()) return scene_;
    if (const auto name = top.text("name", std::nullopt)) {
      if (valid_name(*name)) scene_.name = *name;
      else r_.error(top.get("name"), "name", "must use only a-z, 0-9, _ and -, got '" + *name + "'");
    } else if (!top.has("name")) {
      top.missing("name", "a short identifier such as sphere_drape ([a-z0-9_-]+)");
    }
    scene_.description = top.text("description", "").value_or("");
    if (const auto duration = top.number("duration", Range::positive(), std::nullopt)) scene_.duration = *duration;
    else if (!top.has("duration")) top.missing("duration", "simulated seconds, a number > 0");
    scene_.frame_rate = top.number("frame_rate", Range::positive(), 60.0).value_or(60.0);
    if (const auto g = top.numbers("gravity", 3, Range::any(), Eigen::Vector3d(0, -9.81, 0))) scene_.gravity = *g;
    scene_.seed = static_cast<std::uint64_t>(top.integer("seed", Range::non_negative(), 0).value_or(0));

    check_frame_count(top);
    if (top.has("cloth")) read_cloth(top.get("cloth"));
    else top.missing("cloth", "a map describing the cloth (shape, size, resolution, mass, springs, pins)");
    if (top.has("contact")) read_contact(top.get("contact"));  // first: colliders take its friction
    if (top.has("colliders")) scene_.colliders = read_colliders(r_, top.get("colliders"), scene_.contact);
    if (top.has("metrics")) read_metrics(top.get("metrics"));
    if (top.has("output")) read_output(top.get("output"));
    read_solvers(top);
    return scene_;
  }

  std::vector<std::string> notes;

 private:
  void check_frame_count(MapReader& top) {
    if (scene_.duration <= 0.0) return;
    const double frames = scene_.duration * scene_.frame_rate;
    const std::string product =
        format_number(scene_.duration) + " s x " + format_number(scene_.frame_rate) + " /s = " + format_number(frames);
    if (std::abs(frames - std::round(frames)) > 1e-9 * std::max(1.0, frames))
      r_.error(top.get("duration"), "duration", "times frame_rate must be a whole number of frames, got " + product,
               top.node());
    else if (std::round(frames) < 1.0 && top.has("frame_rate"))  // a frame longer than the run
      r_.error(top.get("frame_rate"), "frame_rate",
               "(frames per second) times duration must give at least 1 frame, got " + product);
    else if (std::round(frames) < 1.0 || std::round(frames) > kMaxFrames)
      r_.error(top.get("duration"), "duration",
               "times frame_rate must give from 1 to " + std::to_string(static_cast<long long>(kMaxFrames)) +
                   " frames, got " + product,
               top.node());
  }

  void read_cloth(const YAML::Node& node) {
    static const std::map<std::string, std::string> later = {
        {"radius", "(disc cloth) " + kLaterCloth + "; use shape: grid"},
        {"rings", "(disc cloth) " + kLaterCloth + "; use shape: grid"},
        {"path", "(mesh cloth) " + kLaterCloth + "; use shape: grid"},
        {"material", "(material presets) " + kLaterCloth + "; give springs and mass explicitly"}};
    MapReader cloth(r_, node, "cloth",
                    {"shape", "size", "resolution", "plane", "center", "rotation", "mass", "areal_density",
                     "thickness", "perturbation", "springs", "air_damping", "pins"},
                    later);
    if (!cloth.valid()) return;
    ClothSpec& spec = scene_.cloth;
    GridClothSpec& grid = spec.grid;
    if (cloth.has("shape")) {
      const auto shape = r_.choice(cloth.get("shape"), "cloth.shape", {"grid", "disc", "mesh"});
      if (shape && *shape != "grid")
        r_.error(cloth.get("shape"), "cloth.shape",
                 "'" + *shape + "' " + kLaterCloth + "; only grid cloth can be simulated now");
    }
    if (const auto size = cloth.numbers("size", 2, Range::positive(), Eigen::Vector2d(1.0, 1.0))) grid.size = *size;
    grid_ok_ = false;
    if (cloth.has("resolution")) {
      const auto resolution = r_.integers(cloth.get("resolution"), "cloth.resolution", 2, {1.0, true, 1e6, true});
      if (resolution) {
        grid.nx = static_cast<int>((*resolution)[0]);
        grid.ny = static_cast<int>((*resolution)[1]);
        if (grid.nx * static_cast<long long>(grid.ny) < 2)
          r_.error(cloth.get("resolution"), "cloth.resolution", "must give at least 2 particles in all, got [1, 1]");
        else if (grid.nx * static_cast<long long>(grid.ny) > 4'000'000)
          r_.error(cloth.get("resolution"), "cloth.resolution", "gives more than 4 million particles");
        else
          grid_ok_ = true;
      }
    } else {
      cloth.missing("resolution", "particles along each side, for example [33, 33] ([1, N] is a chain)");
    }
    if (const auto plane = cloth.choice("plane", {"xz", "xy"}, "xz"))
      grid.plane = *plane == "xz" ? GridPlane::xz : GridPlane::xy;
    if (const auto center = cloth.numbers("center", 3, Range::any(), Eigen::Vector3d(0, 1, 0))) grid.center = *center;
    if (const auto rotation = cloth.numbers("rotation", 3, Range::any(), Eigen::Vector3d::Zero()))
      grid.rotation = *rotation;

    const bool has_mass = cloth.has("mass"), has_density = cloth.has("areal_density");
    if (has_mass && has_density) {
      r_.error(cloth.get("areal_density"), "cloth.areal_density",
               "cannot be given together with cloth.mass; give one of them");
    } else if (has_mass) {
      if (const auto mass = cloth.number("mass", Range::positive(), std::nullopt)) grid.mass = *mass;
    } else if (has_density) {
      if (const auto density = cloth.number("areal_density", Range::positive(), std::nullopt)) {
        grid.areal_density = *density;
        if (grid_ok_ && (grid.nx == 1 || grid.ny == 1))
          r_.error(cloth.get("areal_density"), "cloth.areal_density",
                   "needs a two-dimensional cloth, but a chain has no area; give cloth.mass instead");
      }
    } else {
      cloth.missing("mass", "total kg (for example 0.25), or give cloth.areal_density in kg/m^2 instead");
    }
    grid.thickness = cloth.number("thickness", Range::positive(), 0.005).value_or(grid.thickness);
    spec.perturbation = cloth.number("perturbation", Range::non_negative(), 0.0).value_or(0.0);
    spec.air_damping = cloth.number("air_damping", Range::non_negative(), 0.0).value_or(0.0);
    if (cloth.has("springs")) read_springs(cloth.get("springs"));
    if (cloth.has("pins")) read_pins(cloth.get("pins"));
  }

  void read_springs(const YAML::Node& node) {
    MapReader springs(r_, node, "cloth.springs", {"stretch", "shear", "bend"});
    if (!springs.valid()) return;
    GridClothSpec& grid = scene_.cloth.grid;
    // Stretch springs hold the cloth together, so their ks must be > 0; shear and bend may be off.
    read_spring_kind(springs, "stretch", Range::positive(), grid.stretch);
    read_spring_kind(springs, "shear", Range::non_negative(), grid.shear);
    read_spring_kind(springs, "bend", Range::non_negative(), grid.bend);
  }

  void read_spring_kind(MapReader& springs, const std::string& kind, const Range& ks_range, SpringParams& out) {
    if (!springs.has(kind)) return;
    MapReader params(r_, springs.get(kind), springs.path_of(kind), {"ks", "kd"});
    if (!params.valid()) return;
    out.ks = params.number("ks", ks_range, out.ks).value_or(out.ks);
    out.kd = params.number("kd", Range::non_negative(), out.kd).value_or(out.kd);
  }

  void read_pins(const YAML::Node& node) {
    if (!node.IsSequence()) {
      r_.error(node, "cloth.pins", "must be a list of pin selectors (corners, [i, j], {index: k}, "
                                    "{within: {center: [x, y, z], radius: r}}), got " + describe_scalar(node));
      return;
    }
    GridClothSpec& grid = scene_.cloth.grid;
    record_item_lines(r_, node, "cloth.pins");
    for (std::size_t k = 0; k < node.size(); ++k) {
      const YAML::Node item = node[k];
      const std::string path = "cloth.pins." + std::to_string(k);
      std::optional<PinSelector> selector;
      if (item.IsScalar()) {
        auto names = pin_set_names(grid.plane);
        if (const auto name = r_.choice(item, path, names)) selector = PinNamed{*name};
      } else if (item.IsSequence()) {
        if (const auto ij = r_.integers(item, path, 2, Range::non_negative()))
          selector = PinGridCoord{static_cast<int>((*ij)[0]), static_cast<int>((*ij)[1])};
      } else if (item.IsMap()) {
        selector = read_pin_map(item, path);
      } else {
        r_.error(item, path, "must be a pin selector (a set name, [i, j], {index: k} or {within: ...}), got nothing");
      }
      if (!selector) continue;
      if (grid_ok_) {
        std::string why;
        if (select_pins(grid, *selector, &why).empty()) {
          r_.error(item, path, "selects no particle: " + why);
          continue;
        }
      }
      grid.pins.push_back(*selector);
    }
  }

  std::optional<PinSelector> read_pin_map(const YAML::Node& item, const std::string& path) {
    MapReader pin(r_, item, path, {"index", "within"});
    if (!pin.valid()) return std::nullopt;
    if (pin.has("index") == pin.has("within")) {
      r_.error(item, path, "must have exactly one of index or within");
      return std::nullopt;
    }
    if (pin.has("index")) {
      const auto index = pin.integer("index", Range::non_negative(), std::nullopt);
      if (!index) return std::nullopt;
      return PinIndex{static_cast<int>(*index)};
    }
    MapReader ball(r_, pin.get("within"), pin.path_of("within"), {"center", "radius"});
    if (!ball.valid()) return std::nullopt;
    const auto center = ball.numbers("center", 3, Range::any(), std::nullopt);
    const auto radius = ball.number("radius", Range::positive(), std::nullopt);
    if (!ball.has("center")) ball.missing("center", "the ball's centre [x, y, z] in m");
    if (!ball.has("radius")) ball.missing("radius", "the ball's radius in m, > 0");
    if (!center || !radius) return std::nullopt;
    return PinWithin{*center, *radius};
  }

  void read_contact(const YAML::Node& node) {
    MapReader contact(r_, node, "contact", {"stiffness", "damping", "friction", "static_friction"});
    if (!contact.valid()) return;
    ContactSpec& c = scene_.contact;
    c.stiffness = contact.number("stiffness", Range::positive(), c.stiffness).value_or(c.stiffness);
    c.damping = contact.number("damping", Range::non_negative(), c.damping).value_or(c.damping);
    c.friction = contact.number("friction", Range::non_negative(), c.friction).value_or(c.friction);
    c.static_friction = contact.number("static_friction", Range::non_negative(), c.friction).value_or(c.friction);
    if (c.static_friction < c.friction)
      r_.error(contact.get("static_friction"), "contact.static_friction",
               "must be >= contact.friction (" + format_number(c.friction) + "), got " + format_number(c.static_friction));
  }

  void read_metrics(const YAML::Node& node) {
    MapReader metrics(r_, node, "metrics", {},
                      {{"drape_support",
                        "is not available yet in this version of drapelab (the drape coefficient comes "
                        "with colliders and disc cloth); remove it"}});
  }

  void read_output(const YAML::Node& node) {
    MapReader output(r_, node, "output", {"meshes"});
    if (!output.valid()) return;
    if (const auto meshes = output.choice("meshes", {"none", "obj", "pc2", "both"}, "none")) {
      if (*meshes == "obj") scene_.output.meshes = MeshOutput::obj;
      else if (*meshes == "pc2") scene_.output.meshes = MeshOutput::pc2;
      else if (*meshes == "both") scene_.output.meshes = MeshOutput::both;
      else scene_.output.meshes = MeshOutput::none;
    }
  }

  void read_solvers(MapReader& top) {
    // Colliders and contact are read by now: the automatic steps depend on them.
    const bool cloth_ok = grid_ok_ && r_.error_count() == 0;
    if (top.has("solvers")) {
      scene_.solvers = scene::read_solvers(r_, top.get("solvers"), scene_, cloth_ok, notes);
    } else {
      // The contract's default: our solver and Bullet's classic cloth, side by side.
      const YAML::Node defaults = YAML::Load("[{type: spring_damper}, {type: bullet_softbody}]");
      scene_.solvers = scene::read_solvers(r_, defaults, scene_, cloth_ok, notes);
    }
  }

  SceneReader& r_;
  Scene scene_;
  bool grid_ok_ = false;  // resolution was read, so pins can be checked against the grid
};

LoadResult load_from_text(const std::string& text, const std::string& display_name,
                          const std::vector<std::string>& overrides, const std::filesystem::path& source) {
  LoadResult result;
  SceneReader reader(display_name, &result.errors);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    result.errors.push_back(display_name + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
    return result;
  }
  if (!root.IsDefined() || root.IsNull()) {
    result.errors.push_back(display_name + ": the scene is empty; it needs at least name, duration, cloth and solvers");
    return result;
  }
  if (!apply_overrides(root, overrides, reader)) return result;
  SceneBuilder builder(reader);
  Scene scene = builder.build(root);
  if (!result.errors.empty()) return result;
  scene.source = source;
  result.notes = builder.notes;
  result.scene = std::move(scene);
  return result;
}

}  // namespace

const char* mesh_output_name(MeshOutput output) {
  switch (output) {
    case MeshOutput::none: return "none";
    case MeshOutput::obj: return "obj";
    case MeshOutput::pc2: return "pc2";
    case MeshOutput::both: return "both";
  }
  return "none";
}

int Scene::frame_count() const { return static_cast<int>(std::lround(duration * frame_rate)); }

LoadResult load_scene_file(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  std::ifstream in(file, std::ios::binary);
  if (std::filesystem::is_directory(file)) {
    LoadResult result;
    result.errors.push_back(file.string() + ": is a folder, not a file; give the path of a scene file (.yaml)");
    return result;
  }
  if (!in) {
    LoadResult result;
    result.errors.push_back(file.string() + ": cannot be read (" +
                            (std::filesystem::exists(file) ? "permission denied or not a file" : "no such file") + ")");
    return result;
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  return load_from_text(buffer.str(), file.string(), overrides, file);
}

LoadResult load_scene_text(const std::string& text, const std::string& display_name,
                           const std::vector<std::string>& overrides) {
  return load_from_text(text, display_name, overrides, display_name);
}

}  // namespace drapelab::scene
