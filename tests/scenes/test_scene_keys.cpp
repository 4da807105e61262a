// The scene key table (scenes/loader/src/scene_keys_*.hpp) against what depends on it:
//   - docs/scene-reference.md's key tables are the ones it produces (drapelab-key-tables), and the
//     check names the key and the cell when they are not;
//   - each row is well formed: a known parent, a default that parses, lies in its range and among
//     its choices;
//   - its defaults and choices are those of the engine's settings and names;
//   - resolved.yaml writes every key of the table, and only those.
#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "drapelab/air.hpp"
#include "drapelab/implicit_euler.hpp"
#include "drapelab/integrators.hpp"
#include "drapelab/scene/key_tables.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "drapelab/scene/scene_writer.hpp"
#include "drapelab/self_collision.hpp"
#include "drapelab/vertex_block_descent.hpp"
#include "materials.hpp"
#include "scene_keys.hpp"

namespace drapelab::scene {
namespace {

namespace fs = std::filesystem;

std::string reference_page() {
  std::ifstream in(fs::path(DRAPELAB_SOURCE_DIR) / "docs" / "scene-reference.md", std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string listed(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += "\n  " + line;
  return text;
}

// The first problem that mentions every one of `words`, or empty.
std::string problem_with(const std::vector<std::string>& problems,
                         const std::vector<std::string>& words) {
  for (const std::string& problem : problems)
    if (std::all_of(words.begin(), words.end(), [&](const std::string& word) {
          return problem.find(word) != std::string::npos;
        }))
      return problem;
  return "";
}

// The page with its first line holding `from` changed to hold `to`.
std::string edited(std::string page, const std::string& from, const std::string& to) {
  const std::size_t at = page.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? page : page.replace(at, from.size(), to);
}

TEST(SceneKeys, ReferenceTablesMatchTheKeyTable) {
  const std::vector<std::string> problems = key_table_problems(reference_page());
  EXPECT_TRUE(problems.empty())
      << "docs/scene-reference.md disagrees with the scene key table; run "
         "build/scenes/loader/drapelab-key-tables docs/scene-reference.md:"
      << listed(problems);
}

TEST(SceneKeys, TheCheckNamesTheKeyAndTheDifference) {
  const std::string page = with_key_tables(reference_page());
  ASSERT_TRUE(key_table_problems(page).empty());
  const std::string thickness = "| `thickness` | number | `0.005` | [10⁻⁶, 1] | m |";
  // A wrong default, range and unit, each named with the key.
  EXPECT_NE(problem_with(key_table_problems(edited(page, thickness,
                                                   "| `thickness` | number | `0.004` | [10⁻⁶, "
                                                   "1] | m |")),
                         {"cloth.thickness", "default", "0.004", "0.005"}),
            "");
  EXPECT_NE(problem_with(key_table_problems(edited(page, thickness,
                                                   "| `thickness` | number | `0.005` | [0, 1] "
                                                   "| m |")),
                         {"cloth.thickness", "range"}),
            "");
  EXPECT_NE(problem_with(key_table_problems(edited(page, thickness,
                                                   "| `thickness` | number | `0.005` | [10⁻⁶, "
                                                   "1] | mm |")),
                         {"cloth.thickness", "unit"}),
            "");
  // A row left out, and a row of a key the table lacks.
  const std::size_t row = page.find(thickness);
  const std::string without = page.substr(0, row) + page.substr(page.find('\n', row) + 1);
  EXPECT_NE(problem_with(key_table_problems(without), {"cloth.thickness", "missing"}), "");
  EXPECT_NE(problem_with(key_table_problems(edited(page, "| `thickness` |", "| `thicknes` |")),
                         {"thicknes", "not a key"}),
            "");
  // A marker that is not closed, and a map in no table.
  const std::string contact = "<!-- scene-keys: contact -->";
  EXPECT_NE(problem_with(key_table_problems(edited(page, contact, "<!-- contact -->")),
                         {"contact.stiffness", "in no table"}),
            "");
}

TEST(SceneKeys, EveryRowIsWellFormed) {
  std::set<std::string> paths;
  const std::vector<const SceneKey*> rows = scene_keys();
  for (const SceneKey* row : rows) {
    const std::string path(row->path);
    SCOPED_TRACE(path);
    EXPECT_TRUE(paths.insert(path).second) << "declared twice";
    EXPECT_FALSE(row->doc.empty());
    if (!row->parent().empty()) {  // the parent is a map of the table, or a list's items
      std::string parent(row->parent());
      const bool items = parent.size() > 2 && parent.ends_with("[]");
      if (items) parent.resize(parent.size() - 2);
      const auto found = std::find_if(rows.begin(), rows.end(),
                                      [&](const SceneKey* k) { return k->path == parent; });
      ASSERT_TRUE(found != rows.end()) << "no row for its parent " << parent;
      EXPECT_EQ((*found)->type, items ? KeyType::list : KeyType::map);
    }
    EXPECT_EQ(row->type == KeyType::choice, !row->choices.empty());
    if (row->given != Given::value) continue;
    switch (row->type) {
      case KeyType::number:
        EXPECT_TRUE(row->range.contains(default_number(*row)));
        break;
      case KeyType::integer:
        EXPECT_TRUE(row->range.contains(static_cast<double>(default_integer(*row))));
        break;
      case KeyType::boolean:
        EXPECT_TRUE(row->fallback == "true" || row->fallback == "false");
        break;
      case KeyType::choice: {
        const auto choices = key_choices(*row);
        EXPECT_NE(std::find(choices.begin(), choices.end(), default_choice(*row)), choices.end());
        break;
      }
      case KeyType::numbers: {
        const Eigen::VectorXd values = default_numbers(*row);
        ASSERT_EQ(values.size(), row->size);
        for (Eigen::Index k = 0; k < values.size(); ++k)
          EXPECT_TRUE(row->range.contains(values[k]));
        break;
      }
      default:
        break;
    }
  }
}

TEST(SceneKeys, DefaultsAreTheEnginesSettings) {
  const auto number = [](std::string_view path) {
    for (const SceneKey* row : scene_keys())
      if (row->path == path) return default_number(*row);
    ADD_FAILURE() << "no row " << path;
    return 0.0;
  };
  const ContactSpec contact;
  EXPECT_EQ(number("contact.stiffness"), contact.stiffness);
  EXPECT_EQ(number("contact.damping"), contact.damping);
  EXPECT_EQ(number("contact.friction"), contact.friction);
  EXPECT_EQ(default_boolean(key("contact.triangles")), contact.triangles);
  const SelfCollisionSettings self;
  EXPECT_EQ(number("cloth.self_collision.stiffness"), self.stiffness);
  EXPECT_EQ(number("cloth.self_collision.damping"), self.damping);
  EXPECT_EQ(number("cloth.self_collision.friction"), self.friction);
  const AirSettings air;
  EXPECT_EQ(number("air.density"), air.density);
  EXPECT_EQ(number("air.drag"), air.drag);
  EXPECT_EQ(number("air.lift"), air.lift);
  const VbdSettings vbd;
  EXPECT_EQ(default_integer(key("solvers[].vbd.iterations")), vbd.iterations);
  EXPECT_EQ(default_integer(key("solvers[].vbd.order")), vbd.order);
  EXPECT_EQ(number("solvers[].vbd.chebyshev_rho"), vbd.chebyshev_rho);
  EXPECT_EQ(number("solvers[].vbd.friction_velocity"), vbd.friction_velocity);
  EXPECT_EQ(default_boolean(key("solvers[].vbd.coarse")), vbd.coarse_correction);
  const ImplicitSolveSettings implicit;
  EXPECT_EQ(number("solvers[].implicit.tolerance"), implicit.tolerance);
  EXPECT_EQ(default_integer(key("solvers[].implicit.max_iterations")), implicit.max_iterations);
  const ContinuumParams continuum;
  EXPECT_EQ(number("cloth.continuum.stretch_modulus"), continuum.stretch_modulus);
  EXPECT_EQ(number("cloth.continuum.poisson"), continuum.poisson);
  EXPECT_EQ(number("cloth.continuum.bending_rigidity"), continuum.bending_rigidity);
  EXPECT_EQ(number("cloth.continuum.damping"), continuum.damping);
  const GridClothSpec grid;
  EXPECT_EQ(number("cloth.thickness"), grid.thickness);
  EXPECT_EQ(number("cloth.springs.stretch.ks"), grid.stretch.ks);
  EXPECT_EQ(number("cloth.springs.stretch.kd"), grid.stretch.kd);
  EXPECT_EQ(number("cloth.springs.shear.ks"), grid.shear.ks);
  EXPECT_EQ(number("cloth.springs.shear.kd"), grid.shear.kd);
  EXPECT_EQ(number("cloth.springs.bend.ks"), grid.bend.ks);
  EXPECT_EQ(number("cloth.springs.bend.kd"), grid.bend.kd);
  EXPECT_EQ(default_numbers(key("cloth.size")), Eigen::VectorXd(grid.size));
  const DiscSpec disc;
  EXPECT_EQ(number("cloth.radius"), disc.radius);
  EXPECT_EQ(default_integer(key("cloth.rings")), disc.rings);
}

TEST(SceneKeys, ChoicesAreTheEnginesNames) {
  std::vector<std::string> types;
  for (const SolverType type : kSolverTypes) types.emplace_back(solver_type_name(type));
  EXPECT_EQ(key_choices(key("solvers[].type")), types);
  EXPECT_EQ(key_choices(key("solvers[].integrator")), integrator_names());
  EXPECT_EQ(key_choices(key("cloth.material")), material_names());
  std::vector<std::string> meshes;
  for (const MeshOutput output :
       {MeshOutput::none, MeshOutput::obj, MeshOutput::pc2, MeshOutput::both})
    meshes.emplace_back(mesh_output_name(output));
  EXPECT_EQ(key_choices(key("output.meshes")), meshes);
}

// The key paths of a YAML tree as the table writes them: list items as "[]".
void collect_paths(const YAML::Node& node, const std::string& path, std::set<std::string>& out) {
  if (node.IsMap()) {
    for (const auto& entry : node) {
      const std::string child = (path.empty() ? "" : path + ".") + entry.first.Scalar();
      out.insert(child);
      collect_paths(entry.second, child, out);
    }
  } else if (node.IsSequence()) {
    for (const auto& item : node) collect_paths(item, path + "[]", out);
  }
}

// A 0.2 m square mesh cloth pinned by index, with a rope to a point, a drag, turbulent air and a
// vbd solver: the keys no shipped scene writes. Its OBJ is written beside it in `folder`.
fs::path keys_scene_file(const fs::path& folder) {
  fs::create_directories(folder);
  std::ofstream obj(folder / "square.obj");
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) obj << "v " << 0.1 * (i - 1) << " 0 " << 0.1 * (j - 1) << "\n";
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = 1 + j * 3 + i;  // OBJ indices are 1-based
      obj << "f " << a << " " << a + 1 << " " << a + 4 << "\nf " << a << " " << a + 4 << " "
          << a + 3 << "\n";
    }
  std::ofstream scene(folder / "keys.yaml");
  scene << "name: keys_mesh\n"
           "duration: 0.1\n"
           "cloth:\n"
           "  shape: mesh\n"
           "  path: square.obj\n"
           "  scale: 1\n"
           "  center: [0, 1, 0]\n"
           "  mass: 0.01\n"
           "  pins: [{index: 0}]\n"
           "constraints:\n"
           "  - {type: distance, a: {index: 8}, b: {point: [0.2, 1.1, 0.2]}, mode: rope}\n"
           "interactions:\n"
           "  - {type: drag, particle: {index: 4}, stiffness: 1, keyframes: [{t: 0, target: [0, "
           "1.2, 0]}]}\n"
           "air:\n"
           "  wind: [1, 0, 0]\n"
           "  turbulence: {intensity: 0.1, length: 0.5}\n"
           "solvers:\n"
           "  - {type: spring_damper, integrator: vbd}\n";
  return folder / "keys.yaml";
}

// The shipped scenes, a change of one and the scene above: between them, every key of the table.
std::vector<std::pair<std::string, std::vector<std::string>>> resolved_cases(
    const fs::path& folder) {
  std::vector<std::pair<std::string, std::vector<std::string>>> cases;
  for (const auto& entry : fs::directory_iterator(fs::path(DRAPELAB_SOURCE_DIR) / "scenes"))
    if (entry.path().extension() == ".yaml") cases.push_back({entry.path().string(), {}});
  const std::string scenes = std::string(DRAPELAB_SOURCE_DIR) + "/scenes/";
  cases.push_back({scenes + "sphere_drape.yaml",
                   {"solvers=[{type: bullet_softbody, kLST: {stretch: 0.5, shear: 0.4, bend: "
                    "0.3}}]"}});
  cases.push_back({keys_scene_file(folder).string(), {}});
  return cases;
}

TEST(SceneKeys, ResolvedScenesWriteTheTablesKeysAndNoOther) {
  // {index: k} and [i, j] name a particle as the pins' selectors do; their forms are the doc
  // lines of constraints[].a, constraints[].b and interactions[].particle, not keys of their own.
  const std::set<std::string> particle_forms = {"constraints[].a.index", "constraints[].b.index",
                                                "interactions[].particle.index"};
  const std::vector<const SceneKey*> rows = scene_keys();
  const fs::path folder =
      fs::temp_directory_path() / ("drapelab_scene_keys_" + std::to_string(::getpid()));
  std::set<std::string> written;
  for (const auto& [file, overrides] : resolved_cases(folder)) {
    const LoadResult loaded = load_scene_file(file, overrides);
    ASSERT_TRUE(loaded.scene) << file << listed(loaded.errors);
    std::set<std::string> paths;
    collect_paths(YAML::Load(resolved_scene_yaml(*loaded.scene)), "", paths);
    for (const std::string& path : paths) {
      const bool known = std::any_of(rows.begin(), rows.end(),
                                     [&](const SceneKey* row) { return row->path == path; });
      EXPECT_TRUE(known || particle_forms.contains(path))
          << file << ": resolved.yaml writes " << path << ", which the key table lacks";
    }
    written.insert(paths.begin(), paths.end());
  }
  fs::remove_all(folder);
  for (const SceneKey* row : rows)
    EXPECT_TRUE(written.contains(std::string(row->path)))
        << row->path << " is in the key table but in no resolved scene (scene_writer.cpp)";
}

}  // namespace
}  // namespace drapelab::scene
