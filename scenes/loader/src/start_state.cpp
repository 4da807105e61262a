// The cloth against the colliders at t = 0 (start_state.hpp), with the engine's own FCL queries:
// a particle's signed distance from ParticleContactQuery, a triangle's from
// collider_triangle_signed_distance.
#include "start_state.hpp"

#include <cmath>
#include <limits>

#include "drapelab/contact_fcl.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/triangle_penetration.hpp"

namespace drapelab::scene {
namespace {

// Counts particle i, `depth` inside the solid (m), and keeps the deepest.
void note_particle(StartOverlap& overlap, int i, double depth) {
  ++overlap.inside;
  if (depth > overlap.deepest_depth) {
    overlap.deepest_depth = depth;
    overlap.deepest = i;
  }
}

// The free particles inside the solid. Returns every particle's signed distance to the solid (m,
// negative inside): exact within the solid's bounding box, a lower bound (the distance to the box)
// outside it, where no query is needed; NaN for a pinned particle.
std::vector<double> particles_inside(const ClothModel& model, const Eigen::Matrix3Xd& x,
                                     const FclCollider& shape, const Eigen::Isometry3d& pose,
                                     StartOverlap& overlap) {
  const double h = model.thickness;  // m: the query's particle radius
  const ParticleContactQuery query(h);
  const Eigen::AlignedBox3d bounds = collider_bounds(shape, pose, 0.0);  // a plane's: unbounded
  std::vector<double> distance(static_cast<std::size_t>(model.particle_count()), std::nan(""));
  for (int i = 0; i < model.particle_count(); ++i) {
    if (model.is_pinned(i)) continue;
    ++overlap.free_particles;
    double& d = distance[static_cast<std::size_t>(i)];
    d = std::sqrt(bounds.squaredExteriorDistance(x.col(i)));
    if (d > 0.0) continue;
    d = query.clearance(shape, pose, x.col(i)) + h;  // clearance = d - h
    if (d < -kStartInsideTolerance) note_particle(overlap, i, -d);
  }
  return distance;
}

// The triangles of free particles outside the solid that the solid crosses (a thin box or a pole
// between particles). A triangle's points lie within its longest edge of a corner and the distance
// to the solid changes no faster than the position, so a triangle whose corners all lie further
// than that from the solid is left out unqueried (a cloth resting on a table finer than its
// thickness). A plane's signed distance to a triangle is its nearest corner's, so a plane crosses
// no triangle whose corners are all outside.
void triangles_crossed(const ClothModel& model, const Eigen::Matrix3Xd& x, const FclCollider& shape,
                       const Eigen::Isometry3d& pose, const std::vector<double>& distance,
                       StartOverlap& overlap) {
  for (Eigen::Index t = 0; t < model.triangles.cols(); ++t) {
    bool skip = false;
    double nearest = std::numeric_limits<double>::infinity();  // m, of the corners
    double longest = 0.0;                                      // m, of the edges
    for (int k = 0; k < 3; ++k) {
      const int i = model.triangles(k, t);
      const double d = distance[static_cast<std::size_t>(i)];
      skip = skip || !(d >= -kStartInsideTolerance);  // pinned (NaN), or inside already
      nearest = std::min(nearest, d);
      longest = std::max(longest, (x.col(i) - x.col(model.triangles((k + 1) % 3, t))).norm());
    }
    if (skip || nearest > longest) continue;
    const double d = collider_triangle_signed_distance(shape, pose, x.col(model.triangles(0, t)),
                                                       x.col(model.triangles(1, t)),
                                                       x.col(model.triangles(2, t)));
    if (d >= -kStartInsideTolerance) continue;
    ++overlap.crossing;
    if (-d > overlap.deepest_crossing) {
      overlap.deepest_crossing = -d;
      overlap.deepest_triangle = static_cast<int>(t);
    }
  }
}

// A computed length for messages (m).
std::string metres(double value) { return format_figures(value) + " m"; }

// "plane 'floor'", "sphere 'ball' of radius 0.3 m at [0, 0.5, 0]", ... at t = 0.
std::string describe_collider(const Collider& c) {
  const std::string at = " at " + format_list(collider_pose(c, 0.0).translation());
  const std::string named = std::string(collider_shape_name(c.shape)) + " '" + c.name + "'";
  switch (c.shape) {
    case ColliderShape::plane:
      return named;
    case ColliderShape::sphere:
      return named + " of radius " + format_number(c.radius) + " m" + at;
    case ColliderShape::box:
      return named + " of half extents " + format_list(c.half_extents) + " m" + at;
    case ColliderShape::cylinder:
    case ColliderShape::capsule:
      return named + " of radius " + format_number(c.radius) + " m and height " +
             format_number(c.height) + " m" + at;
    case ColliderShape::mesh:
      return named + " from '" + c.mesh_file + "' (" +
             std::to_string(c.mesh ? c.mesh->triangles.cols() : 0) + " triangles)" + at;
  }
  return named;
}

// A unit vector for messages: each component to four significant figures, rounding noise (a
// normal turned by 90 degrees keeps a 2e-16) shown as 0.
std::string direction(const Eigen::Vector3d& unit) {
  std::string text = "[";
  for (int k = 0; k < 3; ++k)
    text += (k ? ", " : "") + format_figures(std::abs(unit[k]) < 1e-12 ? 0.0 : unit[k]);
  return text + "]";
}

// A plane's solid side at t = 0, in words: "solid where y < 1.5, the side its normal [0, 1, 0]
// points away from"; an inequality on the point and the normal when the normal is along no axis.
std::string solid_side(const Collider& plane) {
  const Eigen::Isometry3d pose = collider_pose(plane, 0.0);
  const Eigen::Vector3d normal = (pose.linear() * plane.normal).normalized();
  const Eigen::Vector3d point = pose.translation();
  std::string where = "(p - " + format_list(point) + ") . " + direction(normal) + " < 0";
  for (int axis = 0; axis < 3; ++axis)
    if (std::abs(std::abs(normal[axis]) - 1.0) <= 1e-12)
      where = std::string(1, "xyz"[axis]) + (normal[axis] > 0.0 ? " < " : " > ") +
              format_number(point[axis]);
  return "solid where " + where + ", the side its normal " + direction(normal) +
         " points away from";
}

// The self-collision thickness, at cloth.self_collision.thickness, or at cloth.self_collision when
// the thickness is the cloth's own.
void check_self_collision_thickness(SceneReader& reader, const Scene& scene,
                                    const ClothModel& model, const YAML::Node& root) {
  const SelfCollisionSettings& self = scene.cloth.self_collision;
  if (!self.enabled) return;
  double shortest = std::numeric_limits<double>::infinity();  // m
  for (std::size_t e = 0; e < model.springs.size(); ++e)
    if (model.springs.kind[e] == SpringKind::stretch)
      shortest = std::min(shortest, model.springs.rest_length[e]);
  const double largest = kMaxSelfThicknessPerEdge * shortest;  // m
  if (self.thickness < largest) return;
  const YAML::Node map = root["cloth"]["self_collision"];
  const bool given = map.IsDefined() && map.IsMap() && map["thickness"].IsDefined();
  const std::string bound = "below " + format_number(kMaxSelfThicknessPerEdge) +
                            " of the cloth's shortest rest edge (" +
                            format_number(kMaxSelfThicknessPerEdge) + " x " +
                            format_figures(shortest) + " m = " + format_figures(largest) + " m)";
  const std::string why =
      ": two layers keep this distance, and a particle lies about 0.7 of an edge from the far "
      "edge of a triangle beside it (d / sqrt(2) on a square grid), so a thicker layer pushes "
      "the flat cloth's neighbouring parts apart at rest and the run blows up; give a smaller "
      "thickness or a coarser cloth";
  if (given)
    reader.error(map["thickness"], "cloth.self_collision.thickness",
                 "must be " + bound + ", got " + format_number(self.thickness) + " m" + why);
  else
    reader.error(YAML::Node(), "cloth.self_collision",
                 "takes the cloth's thickness, " + format_number(self.thickness) +
                     " m, which must be " + bound + why + " (cloth.self_collision.thickness)");
}

}  // namespace

void check_start_state(SceneReader& reader, const Scene& scene, const ClothModel& model,
                       const YAML::Node& root, StartInside start_inside,
                       std::vector<std::string>& warnings) {
  check_self_collision_thickness(reader, scene, model, root);
  const YAML::Node list = root["colliders"];
  if (scene.colliders.empty() || !list.IsDefined() || !list.IsSequence()) return;
  const ClothState initial = initial_scene_state(scene, model);
  const std::string cloth_where = reader.where(YAML::Node(), "cloth", YAML::Node());
  const bool allowed = start_inside == StartInside::warning;
  for (std::size_t k = 0; k < scene.colliders.size() && k < list.size(); ++k) {
    const StartOverlap overlap = start_overlap(model, initial.x, scene.colliders[k]);
    if (!overlap.starts_inside()) continue;
    const std::string path = "colliders." + std::to_string(k);
    const std::string message =
        start_inside_message(scene.colliders[k], overlap, model, cloth_where, allowed);
    if (allowed)
      warnings.push_back(reader.where(list[k], path, list) + ": " + path + " " + message);
    else
      reader.error(list[k], path, message, list);
  }
}

StartOverlap start_overlap(const ClothModel& model, const Eigen::Matrix3Xd& x,
                           const Collider& collider) {
  StartOverlap overlap;
  const FclCollider shape = make_fcl_collider(collider);
  const Eigen::Isometry3d pose = collider_pose(collider, 0.0) * shape.shape_in_collider;
  const std::vector<double> distance = particles_inside(model, x, shape, pose, overlap);
  if (collider.shape != ColliderShape::plane)
    triangles_crossed(model, x, shape, pose, distance, overlap);
  return overlap;
}

std::string start_inside_message(const Collider& collider, const StartOverlap& overlap,
                                 const ClothModel& model, const std::string& cloth_where,
                                 bool allowed) {
  const bool plane = collider.shape == ColliderShape::plane;
  std::string text = "(" + describe_collider(collider) +
                     (plane ? ": a half-space, " + solid_side(collider) : "") + ")";
  if (overlap.inside > 0)
    text += " holds " + std::to_string(overlap.inside) + " of the cloth's " +
            std::to_string(overlap.free_particles) + " free particles at t = 0; the deepest is " +
            model.describe_particle(overlap.deepest) + ", " + metres(overlap.deepest_depth) +
            " inside";
  if (overlap.crossing > 0) {
    const auto corner = [&](int k) {
      return std::to_string(model.triangles(k, overlap.deepest_triangle));
    };
    text += std::string(overlap.inside > 0 ? "; it also" : " at t = 0") + " crosses " +
            std::to_string(overlap.crossing) +
            " triangles whose corners lie outside it, the deepest (of particles " + corner(0) +
            ", " + corner(1) + " and " + corner(2) + ") by " + metres(overlap.deepest_crossing);
  }
  text += ". The cloth (" + cloth_where + ") starts " +
          (overlap.inside > 0 ? "inside it" : "through it");
  if (allowed)
    return text +
           "; it runs anyway (--allow-start-inside): the contact pushes those particles "
           "out at once";
  text +=
      ", and the contact would push those particles out at once and blow the run up. Start "
      "the cloth outside every collider (within the thickness, " +
      metres(model.thickness) + ", is fine: it rests there): move the cloth or the collider";
  if (plane && overlap.inside == overlap.free_particles)
    text += ", or turn the plane's normal towards the cloth";
  return text + "; --allow-start-inside runs it anyway";
}

}  // namespace drapelab::scene
