// Triangle penetration (see drapelab/triangle_penetration.hpp).
#include "drapelab/triangle_penetration.hpp"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/detail/gjk_solver_indep.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/proximity.hpp"

namespace drapelab {
namespace {

// GJK and EPA iterations before giving up; a triangle against one of our shapes needs a few tens.
constexpr unsigned kGjkMaxIterations = 1000;

// The point of triangle a-b-c closest to p (Ericson, "Real-Time Collision Detection", 5.1.5): by
// the Voronoi region of p among the corners, sides and face.
Eigen::Vector3d nearest_point_of_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denominator = va + vb + vc;
  if (!(denominator > 0.0)) {
    // A degenerate (zero-area) triangle: the nearest of its three sides.
    Eigen::Vector3d best = a;
    for (const auto& [s, e] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
      const Eigen::Vector3d d = e - s;
      const double length_squared = d.squaredNorm();
      const double u =
          length_squared > 0.0 ? std::clamp((p - s).dot(d) / length_squared, 0.0, 1.0) : 0.0;
      const Eigen::Vector3d point = s + u * d;
      if ((point - p).squaredNorm() < (best - p).squaredNorm()) best = point;
    }
    return best;
  }
  return a + (vb / denominator) * ab + (vc / denominator) * ac;
}

// FCL's signed distance between a convex shape posed by shape_pose and a world-space triangle,
// from FCL's own GJK and EPA (GJKSolver_indep): libccd's EPA, the other solver FCL offers, aborts
// the program on an assertion when the triangle meets the shape at a degenerate polytope (seen on
// cloth pressed flat against a cylinder's rim); this one reports a failed expansion instead.
template <typename Shape>
double gjk_signed_distance(const Shape& shape, const Eigen::Isometry3d& shape_pose,
                           const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c) {
  fcl::detail::GJKSolver_indep<double> solver;
  solver.gjk_max_iterations = kGjkMaxIterations;
  solver.epa_max_iterations = kGjkMaxIterations;
  solver.gjk_tolerance = kTriangleDistanceTolerance;
  solver.epa_tolerance = kTriangleDistanceTolerance;
  const fcl::Transform3d pose(shape_pose.matrix());
  double distance = 0.0;  // m
  if (solver.shapeTriangleDistance(shape, pose, a, b, c, &distance)) return distance;
  double depth = 0.0;  // m
  fcl::Vector3d point, normal;
  solver.shapeTriangleIntersect(shape, pose, a, b, c, &point, &depth, &normal);
  return -std::abs(depth);
}

// The points of triangle a-b-c (given in the mesh's frame) where a mesh may come nearest to it:
// its corners, the feet on it of the mesh's vertices that lie over it, and the feet of the ends of
// the mesh's edges cut to the triangle's prism. A mesh's signed distance is linear over any part
// of the triangle that faces one flat piece of the mesh, so its least value lies at one of these.
// Features farther from the triangle's box than its longest edge are left out: reaching deeper,
// the solid would hold a corner first.
double mesh_triangle_signed_distance(const MeshSurface& mesh, const Eigen::Vector3d& a,
                                     const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double infinity = std::numeric_limits<double>::infinity();
  double least = infinity;  // m
  const auto sample = [&](const Eigen::Vector3d& q) {
    if (const auto near = mesh.signed_nearest(q, infinity)) least = std::min(least, near->distance);
  };
  sample(a);
  sample(b);
  sample(c);
  const Eigen::Vector3d cross = (b - a).cross(c - a);
  if (!(cross.squaredNorm() > 0.0)) return least;  // no plane to stand features over
  const Eigen::Vector3d n = cross.normalized();
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  Eigen::AlignedBox3d box(a);
  box.extend(b).extend(c);
  box.min().array() -= longest;
  box.max().array() += longest;
  thread_local std::vector<int> near_triangles;
  mesh.triangles_in_box(box, near_triangles);
  const Eigen::Vector3d corner[3] = {a, b, c};
  const auto foot = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d {
    return p - (p - a).dot(n) * n;
  };
  for (const int t : near_triangles) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d v = mesh.vertices().col(mesh.triangles()(k, t));
      const Eigen::Vector3d q = foot(v);
      if (closest_point_on_triangle(q, a, b, c).region == TriangleRegion::face) sample(q);
      // The edge opposite corner k, cut to the prism over the triangle: (p - from) . m >= 0 on
      // each side's inward normal m.
      const MeshEdge& edge = mesh.edges()[static_cast<std::size_t>(mesh.triangle_edge(t, k))];
      const Eigen::Vector3d e0 = mesh.vertices().col(edge.from), e1 = mesh.vertices().col(edge.to);
      double low = 0.0, high = 1.0;
      for (int side = 0; side < 3 && low <= high; ++side) {
        const Eigen::Vector3d& from = corner[side];
        const Eigen::Vector3d& to = corner[(side + 1) % 3];
        const Eigen::Vector3d inward = n.cross(to - from);  // the triangle is wound about n
        const double start = (e0 - from).dot(inward), slope = (e1 - e0).dot(inward);
        if (slope == 0.0) {
          if (start < 0.0) high = -1.0;
        } else if (slope > 0.0) {
          low = std::max(low, -start / slope);
        } else {
          high = std::min(high, -start / slope);
        }
      }
      if (low > high) continue;
      sample(foot(e0 + low * (e1 - e0)));
      sample(foot(e0 + high * (e1 - e0)));
    }
  }
  return least;
}

}  // namespace

double collider_triangle_signed_distance(const FclCollider& collider,
                                         const Eigen::Isometry3d& shape_pose,
                                         const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                         const Eigen::Vector3d& c) {
  if (collider.mesh) {
    const Eigen::Isometry3d to_mesh = shape_pose.inverse();
    return mesh_triangle_signed_distance(*collider.mesh, to_mesh * a, to_mesh * b, to_mesh * c);
  }
  const fcl::CollisionGeometry<double>& shape = *collider.geometry;
  switch (shape.getNodeType()) {
    case fcl::GEOM_HALFSPACE: {
      // The half-space's signed distance is linear: the triangle's deepest point is a vertex.
      const auto& halfspace = static_cast<const fcl::Halfspace<double>&>(shape);
      const Eigen::Isometry3d to_shape = shape_pose.inverse();
      return std::min({halfspace.signedDistance(to_shape * a),
                       halfspace.signedDistance(to_shape * b),
                       halfspace.signedDistance(to_shape * c)});
    }
    case fcl::GEOM_SPHERE: {
      // A ball of radius r about o and a convex set meet iff their distance is below r, and the
      // shortest separating move is r less that distance.
      const double radius = static_cast<const fcl::Sphere<double>&>(shape).radius;
      const Eigen::Vector3d centre = shape_pose.translation();
      return (nearest_point_of_triangle(centre, a, b, c) - centre).norm() - radius;
    }
    case fcl::GEOM_BOX:
      return gjk_signed_distance(static_cast<const fcl::Box<double>&>(shape), shape_pose, a, b, c);
    case fcl::GEOM_CAPSULE:
      return gjk_signed_distance(static_cast<const fcl::Capsule<double>&>(shape), shape_pose, a, b,
                                 c);
    case fcl::GEOM_CYLINDER:
      return gjk_signed_distance(static_cast<const fcl::Cylinder<double>&>(shape), shape_pose, a, b,
                                 c);
    default:
      throw std::logic_error(
          "collider_triangle_signed_distance: a shape make_fcl_collider never "
          "makes");
  }
}

double triangle_penetration(const ClothModel& model, const Eigen::Matrix3Xd& x,
                            const ContactModel& contacts, double t) {
  const double h = model.thickness;  // m
  double deepest = 0.0;              // m, max(0, h - d) so far
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const FclCollider& collider = contacts.fcl_collider(k);
    const Eigen::Isometry3d pose = contacts.shape_pose(k, t);
    const Eigen::AlignedBox3d reach = collider_bounds(collider, pose, h);
    for (Eigen::Index f = 0; f < model.triangles.cols(); ++f) {
      const Eigen::Vector3d a = x.col(model.triangles(0, f));
      const Eigen::Vector3d b = x.col(model.triangles(1, f));
      const Eigen::Vector3d c = x.col(model.triangles(2, f));
      if (!a.allFinite() || !b.allFinite() || !c.allFinite()) continue;
      // Broad phase: a triangle whose box stays h away from the collider's box cannot be nearer
      // than h to the collider.
      if (!reach.intersects(Eigen::AlignedBox3d(a).extend(b).extend(c))) continue;
      deepest = std::max(deepest, h - collider_triangle_signed_distance(collider, pose, a, b, c));
    }
  }
  return deepest;
}

}  // namespace drapelab
