// The scene's cloth of any shape: grid, disc or mesh, with pins resolved by selector.
#include <algorithm>
#include <limits>
#include <stdexcept>

#include "drapelab/scene/scene.hpp"

namespace drapelab::scene {
namespace {

TriangleMesh shape_mesh(const ClothSpec& cloth) {
  if (cloth.shape == "disc") return make_disc_mesh(cloth.disc);
  if (!cloth.mesh) throw std::invalid_argument("mesh cloth without a mesh");
  return *cloth.mesh;
}

// Rim of a disc: its last ring.
std::vector<int> disc_rim(const DiscSpec& disc) {
  std::vector<int> rim;
  const int start = disc_ring_start(disc, disc.rings);
  for (int k = 0; k < disc_ring_count(disc, disc.rings); ++k) rim.push_back(start + k);
  return rim;
}

int nearest_to(const Eigen::Matrix3Xd& points, const Eigen::Vector3d& target) {
  int best = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const double d = (points.col(i) - target).squaredNorm();
    if (d < best_distance - 1e-15) {
      best_distance = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

std::vector<int> select_on_mesh(const ClothSpec& cloth, const TriangleMesh& mesh,
                                const PinSelector& selector, std::string* error) {
  const Eigen::Matrix3Xd& rest = mesh.vertices;
  const int count = static_cast<int>(rest.cols());
  if (const auto* named = std::get_if<PinNamed>(&selector)) {
    if (named->name == "center")
      return {cloth.shape == "disc" ? 0 : nearest_to(rest, rest.rowwise().mean())};
    if (named->name == "rim" && cloth.shape == "disc") return disc_rim(cloth.disc);
    if (error) {
      *error =
          "unknown pin set '" + named->name + "' for " + cloth.shape + " cloth; expected one of:";
      for (const auto& valid : pin_set_names(cloth)) *error += " " + valid;
    }
    return {};
  }
  if (std::holds_alternative<PinGridCoord>(selector)) {
    if (error) *error = "grid coordinates [i, j] need shape: grid; use {index: k} or {within: ...}";
    return {};
  }
  if (const auto* index = std::get_if<PinIndex>(&selector)) {
    if (index->index < 0 || index->index >= count) {
      if (error)
        *error = "particle index " + std::to_string(index->index) + " is outside 0.." +
                 std::to_string(count - 1);
      return {};
    }
    return {index->index};
  }
  const auto& ball = std::get<PinWithin>(selector);
  std::vector<int> picked;
  for (int i = 0; i < count; ++i)
    if ((rest.col(i) - ball.center).norm() <= ball.radius) picked.push_back(i);
  if (picked.empty() && error) *error = "no particle lies within the ball (rest positions)";
  return picked;
}

}  // namespace

std::vector<std::string> pin_set_names(const ClothSpec& cloth) {
  if (cloth.shape == "disc") return {"center", "rim"};
  if (cloth.shape == "mesh") return {"center"};
  return drapelab::pin_set_names(cloth.grid.plane);
}

std::vector<int> select_cloth_pins(const ClothSpec& cloth, const PinSelector& selector,
                                   std::string* error) {
  if (cloth.shape == "grid") return select_pins(cloth.grid, selector, error);
  return select_on_mesh(cloth, shape_mesh(cloth), selector, error);
}

ClothModel build_scene_cloth(const Scene& scene) {
  const ClothSpec& cloth = scene.cloth;
  if (cloth.shape == "grid") return build_grid_cloth(cloth.grid);
  MeshClothSpec spec;
  spec.mesh = shape_mesh(cloth);
  // Mass or density, thickness, springs and the continuum's parameters: every shape's physics.
  static_cast<ClothPhysicsSpec&>(spec) = static_cast<const ClothPhysicsSpec&>(cloth.grid);
  for (const auto& selector : cloth.grid.pins) {
    std::string error;
    const auto picked = select_on_mesh(cloth, spec.mesh, selector, &error);
    if (picked.empty()) throw std::invalid_argument("pin selector: " + error);
    spec.pinned.insert(spec.pinned.end(), picked.begin(), picked.end());
  }
  return build_mesh_cloth(spec);
}

ClothState initial_scene_state(const Scene& scene, const ClothModel& model) {
  if (scene.cloth.shape == "grid")
    return initial_grid_state(model, scene.cloth.grid, scene.cloth.perturbation, scene.seed);
  return initial_mesh_state(model, scene.cloth.perturbation, scene.seed);
}

std::shared_ptr<const ClothModel> cloth_for_solver(const Scene& scene, const SolverSpec& solver,
                                                   std::shared_ptr<const ClothModel> cloth) {
  const bool wants_continuum = solver.type == SolverType::spring_damper && solver.continuum;
  if (wants_continuum == cloth->uses_continuum()) return cloth;
  if (wants_continuum && scene.cloth.shape == "grid") {
    // A continuum grid splits its cells differently (build_grid_triangles): build it as one.
    GridClothSpec spec = scene.cloth.grid;
    spec.continuum = scene.cloth.continuum;
    return std::make_shared<const ClothModel>(build_grid_cloth(spec));
  }
  auto own = std::make_shared<ClothModel>(*cloth);
  if (wants_continuum) {
    if (own->triangles.cols() == 0)
      throw std::invalid_argument("model: continuum needs a two-dimensional cloth");
    own->continuum = std::make_shared<const ContinuumElements>(build_continuum_elements(
        own->rest_positions, own->triangles, scene.cloth.continuum, held_particles(*own)));
  } else {
    own->continuum.reset();
  }
  return own;
}

bool has_dynamic_colliders(const Scene& scene) {
  for (const Collider& c : scene.colliders)
    if (c.dynamic()) return true;
  return false;
}

std::shared_ptr<const DistanceConstraints> scene_constraints(const Scene& scene) {
  if (scene.constraints.empty() && scene.interactions.empty() && scene.cloth.seams.empty())
    return nullptr;
  auto constraints = std::make_shared<DistanceConstraints>();
  constraints->colliders = scene.colliders;
  constraints->list = scene.constraints;
  for (const DragSpec& drag : scene.interactions)
    constraints->list.push_back(drag_constraint(drag));
  for (const SeamSpec& seam : scene.cloth.seams)
    for (std::size_t k = 0; k < seam.a.size(); ++k)
      constraints->list.push_back(seam_stitch(seam, k));
  return constraints;
}

DistanceConstraint seam_stitch(const SeamSpec& seam, std::size_t k) {
  DistanceConstraint c;
  c.a = seam.a[k];
  c.b.kind = ConstraintEnd::Kind::particle;
  c.b.particle = seam.b[k];
  c.length = seam.rest[k];
  c.mode = ConstraintMode::soft;
  c.stiffness = seam.stiffness;
  c.damping = seam.damping;
  // Shut at once: a stitch of length 0 from the start.
  c.close_time = seam.close_time;
  if (seam.close_time <= 0.0) c.length = 0.0;
  return c;
}

DistanceConstraint drag_constraint(const DragSpec& drag) {
  auto track = std::make_shared<DragTrack>();
  track->particle = drag.particle;
  track->stiffness = drag.stiffness;
  track->damping = drag.damping;
  track->keyframes = drag.keyframes;
  DistanceConstraint c;
  c.a = drag.particle;
  c.b.kind = ConstraintEnd::Kind::drag;
  c.b.drag = std::move(track);
  c.length = 0.0;
  c.mode = ConstraintMode::soft;  // its spring is the track's
  return c;
}

std::shared_ptr<const Attachments> scene_attachments(const Scene& scene,
                                                     const ClothState& initial) {
  std::vector<std::pair<int, int>> attached;  // (particle, collider)
  const ClothSpec& cloth = scene.cloth;
  for (std::size_t k = 0; k < cloth.pin_attach.size() && k < cloth.grid.pins.size(); ++k) {
    if (cloth.pin_attach[k].empty()) continue;
    int collider = -1;
    for (std::size_t c = 0; c < scene.colliders.size(); ++c)
      if (scene.colliders[c].name == cloth.pin_attach[k]) collider = static_cast<int>(c);
    if (collider < 0)
      throw std::invalid_argument("cloth.pins." + std::to_string(k) + ".attach: no collider '" +
                                  cloth.pin_attach[k] + "'");
    std::string why;
    for (int particle : select_cloth_pins(cloth, cloth.grid.pins[k], &why))
      attached.emplace_back(particle, collider);
  }
  if (attached.empty()) return nullptr;
  return std::make_shared<const Attachments>(
      make_attachments(scene.colliders, attached, initial.x, 0.0));
}

}  // namespace drapelab::scene
