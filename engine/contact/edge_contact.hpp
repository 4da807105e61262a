// Contact on the cloth's triangles, not only at its particles: a collider's sharp edges and corners
// (box edges and corners, cylinder rims) against the cloth's edges and triangles.
//
// The particle contact (contact_model.hpp) keeps every particle a thickness h from every collider.
// A smooth collider (sphere, capsule, plane) then cannot reach far into a triangle between its
// particles (at most the sag s^2 / 8R of a triangle of side s over a radius R), but a sharp edge
// can cut through the triangles between two particles. So each collider edge (a box's twelve
// edges; a cylinder's two rims, as chords whose sag is at most h / 8) pushes every cloth edge whose
// closest point to it lies between the cloth edge's particles and nearer than h, and each box
// corner pushes every triangle whose closest point to it lies inside the triangle. One contact
// per cloth edge and collider: the nearest of the collider's edges. The push is the penalty
// spring-damper of the particle contact (same k and c), along the line from the collider's point to
// the cloth's, spread over the cloth edge's (or triangle's) particles by their barycentric
// weights, with Coulomb friction relative to the collider's surface. A cloth point that has passed
// behind a collider edge (the line points into the collider) is pushed along the edge's outward
// direction (the mean of its faces' normals) instead, with depth h plus its distance.
// docs/contact.md, "Contact on triangles", gives the cost.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "core/weighted_contact_pass.hpp"
#include "drapelab/cloth_model.hpp"
#include "drapelab/collider.hpp"
#include "drapelab/contact_fcl.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/weighted_contact.hpp"

namespace drapelab {

// A collider's sharp features in its own frame (m).
struct ColliderFeatures {
  // The outward normals of the faces that meet at a feature (unit; an edge's two with the first
  // repeated), for core/feature_push.hpp.
  using Faces = std::array<Eigen::Vector3d, 3>;
  struct Edge {
    Eigen::Vector3d from, to;  // m
    Eigen::Vector3d outward;   // unit: the mean of the normals of the faces that meet there
    Faces faces;
  };
  struct Corner {
    Eigen::Vector3d at;       // m
    Eigen::Vector3d outward;  // unit
    Faces faces;
  };
  std::vector<Edge> edges;
  std::vector<Corner> corners;
  bool empty() const { return edges.empty() && corners.empty(); }

  // What the shape is, so a cloth edge far from every feature is passed over in a few operations
  // (candidate_edges).
  ColliderShape shape = ColliderShape::sphere;
  Eigen::Vector3d half_extents = Eigen::Vector3d::Zero();   // m, box
  Eigen::Matrix3d rim_frame = Eigen::Matrix3d::Identity();  // cylinder: columns u, w, axis
  double radius = 0.0;                                      // m, cylinder
  double half_height = 0.0;                                 // m, cylinder
  int chords = 0;  // per rim: rim s, chord k is edge s chords + k

  // Calls visit(edge index) for every feature edge that may lie within `reach` (m) of the segment
  // a-b (given in the collider's frame), and for no edge farther than that from every point of it.
  template <typename Visit>
  void candidate_edges(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double reach,
                       Visit&& visit) const;
};

// Box: 12 edges, 8 corners. Cylinder: each rim as chords whose sag is at most `thickness` / 8
// (at least 16 chords). Mesh (from `shape`'s surface): every convex edge whose faces turn by more
// than kSharpMeshTurn, and every vertex where three or more of them meet. Sphere, capsule, plane:
// none (smooth).
ColliderFeatures collider_features(const Collider& collider, const FclCollider& shape,
                                   double thickness);

// A mesh's features: its convex edges sharper than kSharpMeshTurn, and the vertices where three
// or more of them meet, each corner with the three of its faces' normals that cover the largest
// angles there (engine/contact/mesh_features.cpp).
ColliderFeatures mesh_features(const MeshSurface& mesh);

// rad: a mesh edge whose two faces' normals differ by more than this is a sharp feature. Over a
// gentler edge of turn a, a cloth edge of length s bridging it sags onto it by about s a / 4: at
// most 2.2 mm for a 2 cm cloth edge, within the default 5 mm thickness.
inline constexpr double kSharpMeshTurn = 25.0 * 3.14159265358979323846 / 180.0;

// What the edge contacts did to one collider in one force evaluation.
struct EdgeContactTotals {
  int contact_count = 0;                             // cloth edges and triangles pushed
  double normal_force = 0.0;                         // N
  double friction_force = 0.0;                       // N
  double max_depth = 0.0;                            // m
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // N, on the collider (ColliderContactTotals)
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // N*m, about the world origin
  PowerSplit power;                                  // W (ColliderContactTotals)
};

// A collider feature near a cloth edge or triangle, and where it lies: for a solver that measures
// the contact afresh as the cloth moves (vbd).
struct FeatureContact {
  std::array<std::int32_t, 3> particle{-1, -1, -1};    // a cloth edge (a, b, -1) or triangle
  Eigen::Vector3d from = Eigen::Vector3d::Zero();      // m: the collider edge's ends, or its
  Eigen::Vector3d to = Eigen::Vector3d::Zero();        //    corner twice
  Eigen::Vector3d outward = Eigen::Vector3d::UnitY();  // unit
  ColliderFeatures::Faces faces{};                     // unit normals
  Eigen::Vector3d surface_velocity = Eigen::Vector3d::Zero();  // m/s, at the feature
  double static_friction = 0.0;                                // Coulomb coefficients
  double kinetic_friction = 0.0;
  int collider = 0;
};

class EdgeContact {
 public:
  EdgeContact(const ClothModel& model, const ContactModel& contacts);

  // Whether any collider has sharp features (otherwise add_forces does nothing).
  bool active() const { return active_; }
  // Adds the edge contacts' penalty and friction forces (N) at (x, v) and time t to `force`, which
  // holds every force but the particle contacts (friction is sized for a step of h s from it).
  // Overwrites totals(); pushing contacts are appended to `active` when given.
  void add_forces(const ContactModel& contacts, double t, double h, const Eigen::Matrix3Xd& x,
                  const Eigen::Matrix3Xd& v, const Eigen::VectorXd& inverse_mass,
                  Eigen::Matrix3Xd& force, std::vector<WeightedContact>* active);
  const std::vector<EdgeContactTotals>& totals() const { return totals_; }
  // The energy (J) the contacts at positions x and time t store in their penalty springs: 1/2 k d^2
  // over every contact, d its depth (m). Finds the contacts afresh; totals() is left as it was.
  double stored_energy(const ContactModel& contacts, double t, const Eigen::Matrix3Xd& x);
  // Every pair of a cloth edge and a collider edge, and of a cloth triangle and a collider corner,
  // within `reach` (m) of each other at x with the colliders posed at time t, into `near`
  // (cleared first); a cloth primitive's pairs with one collider come one after another.
  // totals() is left as it was.
  void find_near(const ContactModel& contacts, double t, const Eigen::Matrix3Xd& x, double reach,
                 std::vector<FeatureContact>& near);

 private:
  // The contacts at (x, t), into found_.
  void find_contacts(const ContactModel& contacts, double t, const Eigen::Matrix3Xd& x);
  // Collider c's features at `pose`, into posed_edges_ and posed_corners_; returns their bounding
  // box grown by `reach` (m).
  Eigen::AlignedBox3d pose_features(std::size_t c, const Eigen::Isometry3d& pose, double reach);
  // Their penalty and friction forces (add_forces after the search), through the pass the self
  // contacts take too (weighted_contact_pass.hpp), and what they did to each collider.
  void push_and_rub(const ContactModel& contacts, double h, const Eigen::Matrix3Xd& x,
                    const Eigen::Matrix3Xd& v, const Eigen::VectorXd& inverse_mass,
                    Eigen::Matrix3Xd& force, std::vector<WeightedContact>* active);
  // Adds the reaction of `on_cloth` (N, a force on the cloth at the contact's cloth point, the
  // weighted sum of its particles) to the collider's load.
  static void add_load(EdgeContactTotals& total, const WeightedContactPoint& f,
                       const Eigen::Matrix3Xd& x, const Eigen::Vector3d& on_cloth);

  const ClothModel& model_;
  double thickness_;  // m
  bool active_ = false;
  std::vector<ColliderFeatures> features_;  // per collider, in its frame
  std::vector<std::array<std::int32_t, 2>> edges_;
  std::vector<WeightedContactPoint> found_;              // group: the collider's index
  std::vector<ColliderFeatures::Edge> posed_edges_;      // one collider's, in the world
  std::vector<ColliderFeatures::Corner> posed_corners_;  // one collider's, in the world
  WeightedContactPass pass_;
  std::vector<WeightedContactTotals> pass_totals_;  // per collider
  std::vector<EdgeContactTotals> totals_;
};

template <typename Visit>
void ColliderFeatures::candidate_edges(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       double reach, Visit&& visit) const {
  const Eigen::Vector3d low = a.cwiseMin(b), high = a.cwiseMax(b);
  if (shape == ColliderShape::box) {
    // Near an edge of the box means near two of its face planes at once.
    int near_faces = 0;
    for (int axis = 0; axis < 3; ++axis)
      if (high[axis] >= half_extents[axis] - reach || low[axis] <= -half_extents[axis] + reach)
        ++near_faces;
    if (near_faces < 2) return;
  }
  if (shape == ColliderShape::box || shape == ColliderShape::mesh) {
    // Every edge whose box, grown by the reach, meets the segment's.
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const Eigen::Vector3d edge_low = edges[e].from.cwiseMin(edges[e].to).array() - reach;
      const Eigen::Vector3d edge_high = edges[e].from.cwiseMax(edges[e].to).array() + reach;
      if ((high.array() >= edge_low.array()).all() && (low.array() <= edge_high.array()).all())
        visit(e);
    }
    return;
  }
  if (shape != ColliderShape::cylinder || chords == 0) return;
  // In the rim frame: the axial span must reach a rim's plane, the farther end the rim's circle
  // (the distance from the axis is largest at an end of a segment), and only the chords that span
  // the segment's angles, one more on each side, can be near it.
  const Eigen::Vector3d pa = rim_frame.transpose() * a, pb = rim_frame.transpose() * b;
  const double z_low = std::min(pa.z(), pb.z()), z_high = std::max(pa.z(), pb.z());
  const double farthest = std::max(pa.head<2>().norm(), pb.head<2>().norm());
  if (farthest < radius - reach) return;
  const double step = 2.0 * 3.14159265358979323846 / chords;  // rad per chord
  auto chord_of = [&](const Eigen::Vector3d& p) {
    const double angle = std::atan2(p.y(), p.x());  // rad, (-pi, pi]
    return static_cast<int>(
        std::floor((angle < 0.0 ? angle + 2.0 * 3.14159265358979323846 : angle) / step));
  };
  int from = chord_of(pa), to = chord_of(pb);
  if (to < from) std::swap(from, to);
  int span = to - from;
  if (span > chords / 2) {  // the short way round passes through chord 0
    std::swap(from, to);
    span = chords - span;
  }
  for (int side = 0; side < 2; ++side) {
    const double rim = side == 0 ? -half_height : half_height;
    if (z_high < rim - reach || z_low > rim + reach) continue;
    for (int k = from - 1; k <= from + span + 1; ++k)
      visit(static_cast<std::size_t>(side * chords + ((k % chords) + chords) % chords));
  }
}

}  // namespace drapelab
