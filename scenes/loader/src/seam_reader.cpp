// cloth.seams (see seam_reader.hpp and docs/scene-reference.md).
#include "seam_reader.hpp"

#include <set>
#include <string>

#include "drapelab/scene/number_format.hpp"
#include "scene_keys.hpp"
#include "text_checks.hpp"
#include "value_ranges.hpp"

namespace drapelab::scene {
namespace {

// One side of a seam: particle indices, or a grid edge's name (its particles in increasing index).
std::optional<std::vector<int>> read_side(SceneReader& r, MapReader& seam, const std::string& side,
                                          const Scene& scene, const ClothModel* model) {
  const YAML::Node node = seam.get(side);
  const std::string path = seam.path_of(side);
  if (node.IsScalar() && !node.Scalar().empty()) {
    if (scene.cloth.shape != "grid") {
      r.error(node, path,
              "must be a list of particle indices (edge names are a grid's), got " +
                  quoted_value(node.Scalar()));
      return std::nullopt;
    }
    const auto name = r.choice(node, path, pin_set_names(scene.cloth.grid.plane));
    if (!name) return std::nullopt;
    std::string why;
    std::vector<int> particles = select_cloth_pins(scene.cloth, PinNamed{*name}, &why);
    if (particles.empty()) r.error(node, path, "selects no particle: " + why);
    return particles;
  }
  if (!node.IsSequence() || node.size() == 0) {
    r.error(node, path,
            "must be a non-empty list of particle indices, or a grid edge's name, got " +
                describe_scalar(node));
    return std::nullopt;
  }
  std::vector<int> particles;
  const long long count = model ? model->particle_count() : 0;
  for (std::size_t k = 0; k < node.size(); ++k) {
    const std::string item_path = path + "." + std::to_string(k);
    const auto index = r.integer(node[k], item_path, particle_index_range());
    if (!index) return std::nullopt;
    if (model && *index >= count) {
      r.error(node[k], item_path,
              "must be a particle of the cloth (0 to " + std::to_string(count - 1) + "), got " +
                  std::to_string(*index));
      return std::nullopt;
    }
    particles.push_back(static_cast<int>(*index));
  }
  return particles;
}

std::optional<SeamSpec> read_seam(SceneReader& r, const YAML::Node& node, const std::string& path,
                                  const Scene& scene, const ClothModel* model) {
  MapReader seam(r, node, path, key_names("cloth.seams[]"));
  if (!seam.valid()) return std::nullopt;
  if (!seam.has("a")) seam.missing("a", "one side's particle indices, or a grid edge's name");
  if (!seam.has("b")) seam.missing("b", "the other side's, as many as a's");
  SeamSpec out;
  out.close_time = seam.number(key("cloth.seams[].close_time")).value_or(out.close_time);
  const SpringParams& stretch = scene.cloth.grid.stretch;
  out.stiffness = seam.number(key("cloth.seams[].stiffness"), stretch.ks).value_or(stretch.ks);
  out.damping = seam.number(key("cloth.seams[].damping"), stretch.kd).value_or(stretch.kd);
  if (!seam.has("a") || !seam.has("b")) return std::nullopt;
  const auto a = read_side(r, seam, "a", scene, model);
  const auto b = read_side(r, seam, "b", scene, model);
  if (!a || !b || a->empty() || b->empty()) return std::nullopt;
  if (a->size() != b->size()) {
    r.error(seam.get("b"), seam.path_of("b"),
            "must be as long as a (" + std::to_string(a->size()) + " particles), got " +
                std::to_string(b->size()));
    return std::nullopt;
  }
  for (std::size_t k = 0; k < a->size(); ++k)
    if ((*a)[k] == (*b)[k]) {
      r.error(seam.get("b"), seam.path_of("b") + "." + std::to_string(k),
              "sews particle " + std::to_string((*a)[k]) +
                  " to itself; a[k] and b[k] must be two particles");
      return std::nullopt;
    }
  out.a = *a;
  out.b = *b;
  if (model)
    for (std::size_t k = 0; k < out.a.size(); ++k)
      out.rest.push_back(
          (model->rest_positions.col(out.a[k]) - model->rest_positions.col(out.b[k])).norm());
  return out;
}

}  // namespace

std::vector<SeamSpec> read_seams(SceneReader& reader, const YAML::Node& list, const Scene& scene,
                                 const ClothModel* model) {
  std::vector<SeamSpec> seams;
  if (list.IsNull()) return seams;
  if (!list.IsSequence()) {
    reader.error(list, "cloth.seams",
                 "must be a list of {a: [...], b: [...]} seams, got " + describe_scalar(list));
    return seams;
  }
  record_item_lines(reader, list, "cloth.seams");
  for (std::size_t k = 0; k < list.size(); ++k)
    if (auto seam = read_seam(reader, list[k], "cloth.seams." + std::to_string(k), scene, model))
      seams.push_back(std::move(*seam));
  return seams;
}

}  // namespace drapelab::scene
