// The cloth's start against the colliders at t = 0 (docs/scene-reference.md, "Where the cloth
// starts"). A free particle whose centre lies inside a collider's solid, or a triangle of free
// particles outside it that the solid crosses, makes a cloth that starts inside or through the
// collider: the penalty contact pushes such particles by their whole depth in one step and the run
// blows up, naming only a particle's speed. A particle within the thickness of a collider but
// outside its solid starts in contact, as a cloth laid on a table does, and is fine. Pinned
// particles never move and take no contact, so they are left out (a pin carried inside a body,
// with its triangles).
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/collider.hpp"
#include "drapelab/scene/scene.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "yaml_reader.hpp"

namespace drapelab::scene {

// m: a particle or triangle counts as inside only when deeper than this, the rounding of the
// placement (coordinates up to 10^4 m) and of FCL's distance queries (10^-10 m).
inline constexpr double kStartInsideTolerance = 1e-9;

// What one collider holds of the cloth at positions x at t = 0.
struct StartOverlap {
  int free_particles = 0;      // particles that are not pinned
  int inside = 0;              // free particles whose centre lies inside the collider's solid
  int deepest = -1;            // the deepest of them
  double deepest_depth = 0.0;  // m, its distance inside the surface
  int crossing = 0;            // triangles of free particles outside the solid that it crosses
  int deepest_triangle = -1;
  double deepest_crossing = 0.0;  // m, the solid's penetration of that triangle

  bool starts_inside() const { return inside > 0 || crossing > 0; }
};

StartOverlap start_overlap(const ClothModel& model, const Eigen::Matrix3Xd& x,
                           const Collider& collider);

// The checks of the start of a scene that loaded without error, reported through `reader` at the
// key that causes each: the self-collision thickness against the cloth's shortest rest edge
// (kMaxSelfThicknessPerEdge), and the cloth against every collider, an error at the collider or,
// with StartInside::warning, a located line in `warnings`. `root` is the scene's YAML tree.
void check_start_state(SceneReader& reader, const Scene& scene, const ClothModel& model,
                       const YAML::Node& root, StartInside start_inside,
                       std::vector<std::string>& warnings);

// The message for a collider that the cloth starts inside or through, without its location and
// key: what the collider is (a plane's solid side), how many particles lie inside and the deepest,
// the triangles it crosses, where the cloth is (`cloth_where`: "scene.yaml:7") and what to do.
// `allowed`: the run goes on anyway (--allow-start-inside), so the message says what follows.
std::string start_inside_message(const Collider& collider, const StartOverlap& overlap,
                                 const ClothModel& model, const std::string& cloth_where,
                                 bool allowed);

}  // namespace drapelab::scene
