// Scene loader: reads every key of docs/scene-reference.md, checks it, fills in defaults.
#include "drapelab/scene/scene_loader.hpp"

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <set>

#include "air_reader.hpp"
#include "cloth_reader.hpp"
#include "collider_reader.hpp"
#include "constraint_reader.hpp"
#include "drapelab/bounded_file.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/stability.hpp"
#include "interaction_reader.hpp"
#include "overrides.hpp"
#include "run_limits.hpp"
#include "run_memory.hpp"
#include "scene_keys.hpp"
#include "seam_reader.hpp"
#include "solver_reader.hpp"
#include "start_state.hpp"
#include "text_checks.hpp"
#include "tree_limits.hpp"
#include "value_ranges.hpp"
#include "yaml_reader.hpp"

namespace drapelab::scene {
namespace {

class SceneBuilder {
 public:
  SceneBuilder(SceneReader& reader, const std::filesystem::path& folder, StartInside start_inside)
      : r_(reader),
        folder_(folder),
        cloth_reader_(reader, scene_, folder),
        start_inside_(start_inside) {}

  Scene build(const YAML::Node& root) {
    MapReader top(r_, root, "", key_names(""));
    if (!top.valid()) return scene_;
    if (const auto name = top.text("name", std::nullopt)) {
      if (const auto problem = name_problem(*name))
        r_.error(top.get("name"), "name", *problem);
      else
        scene_.name = *name;
    } else if (!top.has("name")) {
      top.missing("name", "a short identifier such as sphere_drape ([a-z0-9_-]+, at most " +
                              std::to_string(kMaxNameLength) + " characters)");
    }
    scene_.description = top.text("description", "").value_or("");
    if (const auto duration = top.number(key("duration")))
      scene_.duration = *duration;
    else if (!top.has("duration"))
      top.missing("duration", "simulated seconds, a number > 0");
    const double frame_rate = default_number(key("frame_rate"));
    scene_.frame_rate = top.number(key("frame_rate")).value_or(frame_rate);
    if (const auto g = top.numbers(key("gravity"))) {
      if (g->norm() <= kMaxGravity)
        scene_.gravity = *g;
      else
        r_.error(top.get("gravity"), "gravity",
                 "must have a magnitude of at most " + format_number(kMaxGravity) + " m/s^2, got " +
                     format_number(g->norm()));
    }
    scene_.seed = static_cast<std::uint64_t>(top.integer(key("seed")).value_or(0));

    check_frame_count(top);
    if (top.has("cloth"))
      cloth_reader_.read(top.get("cloth"));
    else
      top.missing("cloth",
                  "a map describing the cloth (shape, size, resolution, mass, springs, pins)");
    if (top.has("contact")) read_contact(top.get("contact"));  // first: colliders take its friction
    if (top.has("colliders"))
      scene_.colliders =
          read_colliders(r_, top.get("colliders"), scene_.contact, folder_, warnings);
    if (top.has("metrics")) read_metrics(top.get("metrics"));
    if (top.has("air")) scene_.air = read_air(r_, top.get("air"), scene_.seed);
    cloth_reader_.finish();
    if (top.has("output")) read_output(top.get("output"));
    read_solvers(top);
    return scene_;
  }

  std::vector<std::string> notes;
  std::vector<std::string> warnings;
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
    MapReader contact(r_, node, "contact", key_names("contact"));
    if (!contact.valid()) return;
    ContactSpec& c = scene_.contact;
    c.stiffness = contact.number(key("contact.stiffness")).value_or(c.stiffness);
    c.damping = contact.number(key("contact.damping")).value_or(c.damping);
    c.friction = contact.number(key("contact.friction")).value_or(c.friction);
    c.static_friction =
        contact.number(key("contact.static_friction"), c.friction).value_or(c.friction);
    if (c.static_friction < c.friction)
      r_.error(contact.get("static_friction"), "contact.static_friction",
               "must be >= contact.friction (" + format_number(c.friction) + "), got " +
                   format_number(c.static_friction));
    c.triangles = contact.boolean(key("contact.triangles")).value_or(c.triangles);
  }

  // metrics.drape_support: a collider's name (a vertical cylinder or capsule, or a sphere: its
  // horizontal cross-section) or a radius in m (a disc centred under the cloth's centre).
  void read_metrics(const YAML::Node& node) {
    MapReader metrics(r_, node, "metrics", key_names("metrics"));
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
            "must name a collider or give a radius in m, got " + quoted_value(*name) +
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
      const auto radius =
          r_.number(support, "metrics.drape_support", key("metrics.drape_support").range);
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
    MapReader output(r_, node, "output", key_names("output"));
    if (!output.valid()) return;
    if (const auto meshes = output.choice(key("output.meshes"))) {
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
    const YAML::Node solvers = top.has("solvers") ? top.get("solvers") : default_solvers();
    if (cloth_reader_.geometry_ok() && r_.error_count() == 0 && run_fits_memory(solvers)) {
      try {
        model = std::make_shared<const ClothModel>(build_scene_cloth(scene_));
      } catch (const std::exception& e) {  // the builders' preconditions, and bad_alloc
        model = nullptr;
        r_.error(top.get("cloth"), "cloth", "cannot be built: " + std::string(e.what()));
      }
    }
    // Constraints resolve their ends on the built cloth (and are checked for form without one).
    if (top.has("constraints"))
      scene_.constraints = read_constraints(r_, top.get("constraints"), scene_, model.get());
    if (top.has("interactions"))
      scene_.interactions = read_interactions(r_, top.get("interactions"), scene_, model.get());
    if (top.has("cloth") && top.get("cloth").IsMap() && top.get("cloth")["seams"].IsDefined())
      scene_.cloth.seams = read_seams(r_, top.get("cloth")["seams"], scene_, model.get());
    scene_.solvers = scene::read_solvers(r_, solvers, scene_, model.get(), notes);
    check_continuum_is_used();
    check_dynamic_hosts(top);
    check_mujoco_limits(top);
    if (model && r_.error_count() == 0)
      check_start_state(r_, scene_, *model, top.node(), start_inside_, warnings);
  }

  // The contract's default solvers: our solver and Bullet's classic cloth, side by side.
  static YAML::Node default_solvers() {
    return YAML::Load("[{type: spring_damper}, {type: bullet_softbody}]");
  }

  // The run's memory from the cloth's particle count and the solvers, before anything is built
  // (run_memory.hpp); an error at the key that sizes the cloth when the process cannot hold it.
  bool run_fits_memory(const YAML::Node& solvers) {
    const auto bound = usable_memory();
    if (!bound) return true;  // no /proc: nothing to hold the estimate against
    const double particles = cloth_reader_.particle_count();
    const auto problem = run_memory_problem(
        particles, run_memory_parts(particles, solvers, scene_.cloth.self_collision.enabled),
        *bound);
    if (problem) cloth_reader_.size_error(*problem);
    return !problem;
  }

  // A dynamic collider is a rigid body of a Bullet world: our solver has one only when hosted. And
  // Bullet's classic cloth cannot hang a body from pins attached to it (docs/bullet.md,
  // "Constraints").
  void check_dynamic_hosts(MapReader& top) {
    std::string dynamic, carrying;
    for (const Collider& c : scene_.colliders)
      if (c.dynamic()) dynamic = c.name;
    for (const std::string& name : scene_.cloth.pin_attach)
      for (const Collider& c : scene_.colliders)
        if (c.dynamic() && c.name == name) carrying = name;
    if (dynamic.empty() || !top.has("solvers")) return;
    const YAML::Node list = top.get("solvers");
    for (std::size_t k = 0; k < scene_.solvers.size() && k < list.size(); ++k) {
      const SolverSpec& solver = scene_.solvers[k];
      if (solver.type == SolverType::bullet_softbody && !carrying.empty())
        r_.error(list[k]["type"], "solvers." + std::to_string(k) + ".type",
                 "is bullet_softbody, which cannot carry pins attached to the dynamic collider '" +
                     carrying +
                     "': its anchors hold a body only as hard as its links pull the anchored "
                     "node, and the body falls through (use bullet_deformable or spring_damper)",
                 list[k]);
      if (solver.type != SolverType::spring_damper || solver.bullet_host) continue;
      r_.error(list[k]["host"], "solvers." + std::to_string(k) + ".host",
               "is none, but collider '" + dynamic +
                   "' is dynamic: its rigid body lives in the Bullet world that hosts our solver "
                   "(use host: bullet)",
               list[k]);
    }
  }

  // What MuJoCo's mapping does not carry (docs/mujoco.md, "Where MuJoCo departs"): mesh
  // colliders (MuJoCo 2.2 meets only a mesh's convex hull) and dynamic colliders (a dynamic ball
  // bouncing on a soft sheet starts to roll and spin in it, measured).
  void check_mujoco_limits(MapReader& top) {
    std::string problem;
    for (const Collider& c : scene_.colliders) {
      if (!problem.empty()) break;
      if (c.shape == ColliderShape::mesh)
        problem = "collider '" + c.name +
                  "' is a mesh, and MuJoCo 2.2 meets a mesh only as its convex hull; the MuJoCo "
                  "solver carries spheres, cylinders, capsules, boxes and planes";
      else if (c.dynamic())
        problem = "collider '" + c.name +
                  "' is dynamic, and the MuJoCo solver carries static and kinematic colliders only";
    }
    if (problem.empty() || !top.has("solvers")) return;
    const YAML::Node list = top.get("solvers");
    for (std::size_t k = 0; k < scene_.solvers.size() && k < list.size(); ++k)
      if (scene_.solvers[k].type == SolverType::mujoco)
        r_.error(list[k]["type"], "solvers." + std::to_string(k) + ".type",
                 "is mujoco, but " + problem + " (use spring_damper or a Bullet cloth)", list[k]);
  }

  // cloth.continuum on a springs cloth serves the solvers with model: continuum. With none it acts
  // on nothing, which a note says (the scene may still be meant for them: --set solvers=...).
  void check_continuum_is_used() {
    if (!scene_.cloth.continuum_given || scene_.cloth.grid.continuum) return;
    for (const SolverSpec& solver : scene_.solvers)
      if (solver.type == SolverType::spring_damper && solver.continuum) return;
    notes.push_back(
        "cloth.continuum acts on no solver: the cloth is model: springs and no spring_damper "
        "solver "
        "has model: continuum (add model: continuum to the cloth or to a solver)");
  }

  SceneReader& r_;
  std::filesystem::path folder_;  // the scene file's, for the files it names
  Scene scene_;
  ClothReader cloth_reader_;
  StartInside start_inside_;
};

// The 1-based line where a second document of `text` starts: a "---" marker when content precedes
// it (or the second marker), or content after a "..." end marker; 0 when there is none. A textual
// scan, because yaml-cpp's LoadAll never returns on some malformed texts (a lone ",").
int second_document_line(const std::string& text) {
  const auto is_marker = [](std::string_view row, std::string_view marker) {
    return row.substr(0, 3) == marker &&
           (row.size() == 3 || row[3] == ' ' || row[3] == '\t' || row[3] == '\r');
  };
  bool content = false, ended = false;
  int markers = 0, line = 0;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view row(text.data() + start, end - start);
    ++line;
    const bool starts = is_marker(row, "---");
    if (starts && (content || ++markers == 2)) return line;
    const std::size_t first = row.find_first_not_of(" \t\r");
    const bool has_content =
        !starts && first != std::string_view::npos && row[first] != '#' && row[first] != '%';
    if (is_marker(row, "...")) {
      ended = true;
    } else if (has_content) {
      if (ended) return line;
      content = true;
    }
    start = end + 1;
  }
  return 0;
}

// The errors past kMaxListedErrors, counted in one line after those listed.
void add_unlisted_count(const SceneReader& reader, const std::string& display_name,
                        std::vector<std::string>& errors) {
  if (reader.unlisted_errors() == 0) return;
  errors.push_back(display_name + ": " + std::to_string(reader.unlisted_errors()) +
                   " more errors are not listed (only the first " +
                   std::to_string(kMaxListedErrors) + " are); correct these and check again");
}

// Where a text problem is: "scene.yaml:3" for the file, the override itself for a --set.
std::string text_error(const std::string& where, const TextProblem& problem) {
  return where + ": is not UTF-8 text: " + problem.what + " (byte " +
         std::to_string(problem.offset + 1) + "); save the scene as UTF-8";
}

LoadResult load_from_text(const std::string& text, const std::string& display_name,
                          const std::vector<std::string>& overrides,
                          const std::filesystem::path& source, StartInside start_inside) {
  LoadResult result;
  SceneReader reader(display_name, &result.errors);
  // Every string of a scene reaches summary.json, whose writer refuses anything but UTF-8.
  if (const auto problem = text_problem(text)) {
    result.errors.push_back(
        text_error(display_name + ":" + std::to_string(problem->line), *problem));
    return result;
  }
  // A second document would be silently ignored: point at where it starts.
  if (const int line = second_document_line(text)) {
    result.errors.push_back(display_name + ":" + std::to_string(line) +
                            ": starts a second YAML document; a scene file holds one (remove "
                            "this line and what follows, or merge it into the first)");
    return result;
  }
  // Sizes first: yaml-cpp's tree of a hostile file would take gigabytes (tree_limits.hpp).
  if (const auto problem = tree_size_problem(text, "")) {
    result.errors.push_back(display_name + ":" + std::to_string(problem->line + 1) + ": " +
                            (problem->path.empty() ? "the scene" : problem->path) + " " +
                            problem->message);
    return result;
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    const int line = e.mark.is_null() ? 1 : e.mark.line + 1;
    result.errors.push_back(display_name + ":" + std::to_string(line) +
                            ": not valid YAML: " + e.msg);
    return result;
  }
  if (!root.IsDefined() || root.IsNull()) {
    result.errors.push_back(
        display_name +
        ":1: the scene is empty; it needs at least name, duration, cloth and solvers");
    return result;
  }
  if (!apply_overrides(root, overrides, reader)) {
    add_unlisted_count(reader, display_name, result.errors);
    return result;
  }
  // The files a scene names are found from its folder, made absolute so that resolved.yaml, which
  // writes their full paths, loads from any folder (a run folder's, for drapelab render).
  std::error_code no_folder;
  const std::filesystem::path folder = std::filesystem::absolute(source, no_folder).parent_path();
  SceneBuilder builder(reader, no_folder ? source.parent_path() : folder, start_inside);
  Scene scene = builder.build(root);
  add_unlisted_count(reader, display_name, result.errors);
  if (!result.errors.empty()) return result;
  scene.source = source;
  result.notes = builder.notes;
  result.warnings = builder.warnings;
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
                           const std::vector<std::string>& overrides, StartInside start_inside) {
  BoundedFile read = read_bounded_file(file, kMaxInputFileBytes);
  if (!read.ok) {
    LoadResult result;
    result.errors.push_back(file.string() + ": " + read.error +
                            "; give the path of a scene file (.yaml)");
    return result;
  }
  return load_from_text(read.text, file.string(), overrides, file, start_inside);
}

LoadResult load_scene_text(const std::string& text, const std::string& display_name,
                           const std::vector<std::string>& overrides, StartInside start_inside) {
  return load_from_text(text, display_name, overrides, display_name, start_inside);
}

}  // namespace drapelab::scene
