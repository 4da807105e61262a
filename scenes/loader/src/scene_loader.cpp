// Scene loader: reads every key of docs/scene-reference.md, checks it, fills in defaults.
#include "drapelab/scene/scene_loader.hpp"

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <numbers>
#include <regex>
#include <set>
#include <sstream>

#include "cloth_reader.hpp"
#include "collider_reader.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/stability.hpp"
#include "overrides.hpp"
#include "run_limits.hpp"
#include "solver_reader.hpp"
#include "yaml_reader.hpp"

namespace drapelab::scene {
namespace {

bool valid_name(const std::string& name) {
  static const std::regex pattern("[a-z0-9_-]+");
  return std::regex_match(name, pattern);
}

class SceneBuilder {
 public:
  SceneBuilder(SceneReader& reader, const std::filesystem::path& folder)
      : r_(reader), cloth_reader_(reader, scene_, folder) {}

  Scene build(const YAML::Node& root) {
    MapReader top(r_, root, "",
                  {"name", "description", "duration", "frame_rate", "gravity", "seed", "cloth",
                   "colliders", "contact", "solvers", "metrics", "output"});
    if (!top.valid()) return scene_;
    if (const auto name = top.text("name", std::nullopt)) {
      if (valid_name(*name))
        scene_.name = *name;
      else
        r_.error(top.get("name"), "name", "must use only a-z, 0-9, _ and -, got '" + *name + "'");
    } else if (!top.has("name")) {
      top.missing("name", "a short identifier such as sphere_drape ([a-z0-9_-]+)");
    }
    scene_.description = top.text("description", "").value_or("");
    if (const auto duration = top.number("duration", Range::positive(), std::nullopt))
      scene_.duration = *duration;
    else if (!top.has("duration"))
      top.missing("duration", "simulated seconds, a number > 0");
    scene_.frame_rate = top.number("frame_rate", Range::positive(), 60.0).value_or(60.0);
    if (const auto g = top.numbers("gravity", 3, Range::any(), Eigen::Vector3d(0, -9.81, 0)))
      scene_.gravity = *g;
    scene_.seed =
        static_cast<std::uint64_t>(top.integer("seed", Range::non_negative(), 0).value_or(0));

    check_frame_count(top);
    if (top.has("cloth"))
      cloth_reader_.read(top.get("cloth"));
    else
      top.missing("cloth",
                  "a map describing the cloth (shape, size, resolution, mass, springs, pins)");
    if (top.has("contact")) read_contact(top.get("contact"));  // first: colliders take its friction
    if (top.has("colliders"))
      scene_.colliders = read_colliders(r_, top.get("colliders"), scene_.contact);
    if (top.has("metrics")) read_metrics(top.get("metrics"));
    cloth_reader_.finish();
    if (top.has("output")) read_output(top.get("output"));
    read_solvers(top);
    return scene_;
  }

  std::vector<std::string> notes;
  std::shared_ptr<const ClothModel> model;  // the scene's cloth, null when it cannot be built

 private:
  void check_frame_count(MapReader& top) {
    if (scene_.duration <= 0.0) return;
    const double frames = scene_.duration * scene_.frame_rate;
    const std::string product = format_number(scene_.duration) + " s x " +
                                format_number(scene_.frame_rate) + " /s = " + format_number(frames);
    if (std::abs(frames - std::round(frames)) > 1e-9 * std::max(1.0, frames))
      r_.error(top.get("duration"), "duration",
               "times frame_rate must be a whole number of frames, got " + product, top.node());
    else if (std::round(frames) < 1.0 && top.has("frame_rate"))  // a frame longer than the run
      r_.error(top.get("frame_rate"), "frame_rate",
               "(frames per second) times duration must give at least 1 frame, got " + product);
    else if (std::round(frames) < 1.0 || std::round(frames) > kMaxFrames)
      r_.error(top.get("duration"), "duration",
               "times frame_rate must give from 1 to " +
                   std::to_string(static_cast<long long>(kMaxFrames)) + " frames, got " + product,
               top.node());
  }

  void read_contact(const YAML::Node& node) {
    MapReader contact(r_, node, "contact", {"stiffness", "damping", "friction", "static_friction"});
    if (!contact.valid()) return;
    ContactSpec& c = scene_.contact;
    c.stiffness = contact.number("stiffness", Range::positive(), c.stiffness).value_or(c.stiffness);
    c.damping = contact.number("damping", Range::non_negative(), c.damping).value_or(c.damping);
    c.friction = contact.number("friction", Range::non_negative(), c.friction).value_or(c.friction);
    c.static_friction =
        contact.number("static_friction", Range::non_negative(), c.friction).value_or(c.friction);
    if (c.static_friction < c.friction)
      r_.error(contact.get("static_friction"), "contact.static_friction",
               "must be >= contact.friction (" + format_number(c.friction) + "), got " +
                   format_number(c.static_friction));
  }

  // metrics.drape_support: a collider's name (a vertical cylinder or capsule, or a sphere: its
  // horizontal cross-section) or a radius in m (a disc centred under the cloth's centre).
  void read_metrics(const YAML::Node& node) {
    MapReader metrics(r_, node, "metrics", {"drape_support"});
    if (!metrics.valid() || !metrics.has("drape_support")) return;
    const YAML::Node support = metrics.get("drape_support");
    DrapeSupportSpec spec;
    if (support.IsScalar() && !is_number(support)) {
      const auto name = r_.text(support, "metrics.drape_support");
      if (!name) return;
      std::vector<std::string> names;
      for (const auto& c : scene_.colliders) names.push_back(c.name);
      const Collider* found = nullptr;
      for (const auto& c : scene_.colliders)
        if (c.name == *name) found = &c;
      if (!found) {
        const std::string near = nearest_word(*name, names);
        r_.error(
            support, "metrics.drape_support",
            "must name a collider or give a radius in m, got '" + *name + "'" +
                (near.empty() ? std::string(names.empty() ? " (the scene has no colliders)" : "")
                              : "; did you mean " + near + "?"));
        return;
      }
      const auto disc = support_disc(*found, scene_.gravity);
      if (!disc) {
        r_.error(support, "metrics.drape_support",
                 "'" + *name + "' is a " + collider_shape_name(found->shape) +
                     " with no circular cross-section across gravity; name a sphere, or a cylinder "
                     "or capsule "
                     "whose axis is along gravity, or give a radius in m");
        return;
      }
      spec.collider = *name;
      spec.disc = *disc;
    } else {
      const auto radius = r_.number(support, "metrics.drape_support", Range::positive());
      if (!radius) return;
      spec.disc = {scene_.cloth.grid.center, *radius};
    }
    scene_.drape_support = spec;
  }

  static bool is_number(const YAML::Node& node) {
    try {
      (void)node.as<double>();
      return true;
    } catch (const YAML::Exception&) {
      return false;
    }
  }

  // The collider's disc seen along gravity, when it has one.
  static std::optional<DrapeSupport> support_disc(const Collider& c,
                                                  const Eigen::Vector3d& gravity) {
    const Eigen::Isometry3d pose = collider_pose(c, 0.0);
    if (c.shape == ColliderShape::sphere) return DrapeSupport{pose.translation(), c.radius};
    if (c.shape != ColliderShape::cylinder && c.shape != ColliderShape::capsule)
      return std::nullopt;
    const Eigen::Vector3d axis = (pose.linear() * c.axis).normalized();
    const Eigen::Vector3d down = gravity.squaredNorm() > 0.0 ? Eigen::Vector3d(gravity.normalized())
                                                             : Eigen::Vector3d(0, -1, 0);
    if (std::abs(axis.dot(down)) < std::cos(std::numbers::pi / 180.0))
      return std::nullopt;  // within 1 degree
    return DrapeSupport{pose.translation(), c.radius};
  }

  void read_output(const YAML::Node& node) {
    MapReader output(r_, node, "output", {"meshes"});
    if (!output.valid()) return;
    if (const auto meshes = output.choice("meshes", {"none", "obj", "pc2", "both"}, "none")) {
      if (*meshes == "obj")
        scene_.output.meshes = MeshOutput::obj;
      else if (*meshes == "pc2")
        scene_.output.meshes = MeshOutput::pc2;
      else if (*meshes == "both")
        scene_.output.meshes = MeshOutput::both;
      else
        scene_.output.meshes = MeshOutput::none;
    }
  }

  void read_solvers(MapReader& top) {
    // Colliders and contact are read by now: the automatic steps depend on them.
    // The cloth is built here, once: the automatic steps measure it, and the run uses it (model).
    if (cloth_reader_.geometry_ok() && r_.error_count() == 0) {
      try {
        model = std::make_shared<const ClothModel>(build_scene_cloth(scene_));
      } catch (const std::invalid_argument&) {
        model = nullptr;  // reported elsewhere (mass missing, bad pins)
      }
    }
    if (top.has("solvers")) {
      scene_.solvers = scene::read_solvers(r_, top.get("solvers"), scene_, model.get(), notes);
    } else {
      // The contract's default: our solver and Bullet's classic cloth, side by side.
      const YAML::Node defaults = YAML::Load("[{type: spring_damper}, {type: bullet_softbody}]");
      scene_.solvers = scene::read_solvers(r_, defaults, scene_, model.get(), notes);
    }
  }

  SceneReader& r_;
  Scene scene_;
  ClothReader cloth_reader_;
};

LoadResult load_from_text(const std::string& text, const std::string& display_name,
                          const std::vector<std::string>& overrides,
                          const std::filesystem::path& source) {
  LoadResult result;
  SceneReader reader(display_name, &result.errors);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    result.errors.push_back(display_name + ":" + std::to_string(e.mark.line + 1) +
                            ": not valid YAML: " + e.msg);
    return result;
  }
  if (!root.IsDefined() || root.IsNull()) {
    result.errors.push_back(
        display_name + ": the scene is empty; it needs at least name, duration, cloth and solvers");
    return result;
  }
  if (!apply_overrides(root, overrides, reader)) return result;
  SceneBuilder builder(reader, source.parent_path());
  Scene scene = builder.build(root);
  if (!result.errors.empty()) return result;
  scene.source = source;
  result.notes = builder.notes;
  result.model = builder.model;
  result.scene = std::move(scene);
  return result;
}

}  // namespace

const char* mesh_output_name(MeshOutput output) {
  switch (output) {
    case MeshOutput::none:
      return "none";
    case MeshOutput::obj:
      return "obj";
    case MeshOutput::pc2:
      return "pc2";
    case MeshOutput::both:
      return "both";
  }
  return "none";
}

int Scene::frame_count() const { return static_cast<int>(std::lround(duration * frame_rate)); }

LoadResult load_scene_file(const std::filesystem::path& file,
                           const std::vector<std::string>& overrides) {
  std::ifstream in(file, std::ios::binary);
  if (std::filesystem::is_directory(file)) {
    LoadResult result;
    result.errors.push_back(file.string() +
                            ": is a folder, not a file; give the path of a scene file (.yaml)");
    return result;
  }
  if (!in) {
    LoadResult result;
    result.errors.push_back(
        file.string() + ": cannot be read (" +
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
