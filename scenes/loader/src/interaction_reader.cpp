// Reading `interactions:` (see interaction_reader.hpp).
#include "interaction_reader.hpp"

#include "constraint_reader.hpp"
#include "drapelab/scene/number_format.hpp"
#include "scene_keys.hpp"

namespace drapelab::scene {
namespace {

// The keyframes of one drag: {t, target}, at least one, t increasing.
std::optional<std::vector<DragKeyframe>> read_keyframes(SceneReader& r, const YAML::Node& list,
                                                        const std::string& path) {
  if (!list.IsSequence() || list.size() == 0) {
    r.error(list, path,
            "must be a non-empty list of {t, target} (s, m), got " + describe_scalar(list));
    return std::nullopt;
  }
  record_item_lines(r, list, path);
  std::vector<DragKeyframe> keyframes;
  bool ok = true;
  double previous_t = -1.0;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string key_path = path + "." + std::to_string(k);
    MapReader frame(r, list[k], key_path, key_names("interactions[].keyframes[]"));
    if (!frame.valid()) {
      ok = false;
      continue;
    }
    if (!frame.has("t")) frame.missing("t", "the keyframe's time in s, >= 0");
    if (!frame.has("target"))
      frame.missing("target", "the point [x, y, z] in m the spring pulls to");
    const auto t = frame.number(key("interactions[].keyframes[].t"));
    const auto target = frame.numbers(key("interactions[].keyframes[].target"));
    if (!t || !target) {
      ok = false;
      continue;
    }
    if (*t <= previous_t) {
      r.error(frame.get("t"), frame.path_of("t"),
              "must be later than the previous keyframe's t = " + format_number(previous_t) +
                  ", got " + format_number(*t));
      ok = false;
      continue;
    }
    previous_t = *t;
    keyframes.push_back({*t, *target});
  }
  if (!ok) return std::nullopt;
  return keyframes;
}

std::optional<DragSpec> read_drag(SceneReader& r, const YAML::Node& item, const std::string& path,
                                  const Scene& scene, const ClothModel* model) {
  MapReader entry(r, item, path, key_names("interactions[]"));
  if (!entry.valid()) return std::nullopt;
  bool ok = true;
  if (!entry.has("type"))
    entry.missing("type", "the interaction's kind: drag");
  else
    ok = entry.choice(key("interactions[].type")).has_value() && ok;
  DragSpec drag;
  std::optional<int> particle;
  if (!entry.has("particle"))
    entry.missing("particle", "the particle pulled: {index: k} or [i, j]");
  else
    particle =
        read_cloth_particle(r, entry.get("particle"), entry.path_of("particle"), scene, model);
  if (!entry.has("stiffness")) entry.missing("stiffness", "the spring's stiffness in N/m, > 0");
  const auto stiffness = entry.number(key("interactions[].stiffness"));
  const auto damping = entry.number(key("interactions[].damping"));
  std::optional<std::vector<DragKeyframe>> keyframes;
  if (!entry.has("keyframes"))
    entry.missing("keyframes", "a list of {t, target}: where the spring pulls, and when");
  else
    keyframes = read_keyframes(r, entry.get("keyframes"), entry.path_of("keyframes"));
  if (!ok || !particle || !stiffness || !damping || !keyframes) return std::nullopt;
  if (model && model->is_pinned(*particle)) {
    r.error(entry.get("particle"), entry.path_of("particle"),
            "selects particle " + std::to_string(*particle) +
                ", which is pinned: a drag pulls a free particle");
    return std::nullopt;
  }
  drag.particle = *particle;
  drag.stiffness = *stiffness;
  drag.damping = *damping;
  drag.keyframes = std::move(*keyframes);
  return drag;
}

}  // namespace

std::vector<DragSpec> read_interactions(SceneReader& reader, const YAML::Node& list,
                                        const Scene& scene, const ClothModel* model) {
  std::vector<DragSpec> drags;
  if (!list.IsSequence()) {
    reader.error(list, "interactions",
                 "must be a list of drags ({type: drag, particle, stiffness, keyframes}), got " +
                     describe_scalar(list));
    return drags;
  }
  record_item_lines(reader, list, "interactions");
  for (std::size_t k = 0; k < list.size(); ++k)
    if (auto drag = read_drag(reader, list[k], "interactions." + std::to_string(k), scene, model))
      drags.push_back(std::move(*drag));
  return drags;
}

}  // namespace drapelab::scene
