// Mesh colliders' surfaces (see drapelab/mesh_surface.hpp).
#include "drapelab/mesh_surface.hpp"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/AABB.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

#include "core/proximity.hpp"

namespace drapelab {
namespace {

// m^2: a triangle below this area has no direction of its own.
constexpr double kSmallestArea = 1e-14;
// m: a point this near the surface lies on it, for the direction of its way out.
constexpr double kOnSurface = 1e-12;

// Squared distance (m^2) from p to an FCL box.
double squared_distance_to_box(const fcl::AABB<double>& box, const Eigen::Vector3d& p) {
  const Eigen::Vector3d below = (box.min_ - p).cwiseMax(0.0);
  const Eigen::Vector3d above = (p - box.max_).cwiseMax(0.0);
  return (below + above).squaredNorm();
}

}  // namespace

std::optional<std::string> mesh_surface_problem(const TriangleMesh& mesh) {
  if (mesh.vertices.cols() == 0 || mesh.triangles.cols() == 0)
    return std::string("it has no triangles");
  for (Eigen::Index v = 0; v < mesh.vertices.cols(); ++v)
    if (!mesh.vertices.col(v).allFinite())
      return "vertex " + std::to_string(v + 1) + " is not finite";
  for (Eigen::Index t = 0; t < mesh.triangles.cols(); ++t) {
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles(k, t) < 0 || mesh.triangles(k, t) >= mesh.vertices.cols())
        return "triangle " + std::to_string(t + 1) + " names a vertex out of range";
    const Eigen::Vector3d a = mesh.vertices.col(mesh.triangles(0, t));
    const Eigen::Vector3d b = mesh.vertices.col(mesh.triangles(1, t));
    const Eigen::Vector3d c = mesh.vertices.col(mesh.triangles(2, t));
    if (0.5 * (b - a).cross(c - a).norm() < kSmallestArea)
      return "triangle " + std::to_string(t + 1) +
             " has no area (its corners are on one line); remove it or fix its vertices";
  }
  return std::nullopt;
}

MeshSurface::MeshSurface(const TriangleMesh& mesh)
    : vertices_(mesh.vertices), triangles_(mesh.triangles) {
  if (const auto problem = mesh_surface_problem(mesh)) throw std::invalid_argument(*problem);
  const Eigen::Index n = vertices_.cols(), m = triangles_.cols();
  for (Eigen::Index v = 0; v < n; ++v) bounds_.extend(Eigen::Vector3d(vertices_.col(v)));
  face_normals_.resize(3, m);
  vertex_normals_ = Eigen::Matrix3Xd::Zero(3, n);
  triangle_edges_.resize(3, m);
  // Each undirected edge once, keyed by its ordered ends; the first triangle along it is `left`.
  std::map<std::pair<int, int>, int> edge_of;
  for (Eigen::Index t = 0; t < m; ++t) {
    const Eigen::Vector3d a = vertices_.col(triangles_(0, t));
    const Eigen::Vector3d b = vertices_.col(triangles_(1, t));
    const Eigen::Vector3d c = vertices_.col(triangles_(2, t));
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    face_normals_.col(t) = cross.normalized();
    quality_.volume += a.dot(b.cross(c)) / 6.0;
    for (int k = 0; k < 3; ++k) {
      const int at = triangles_(k, t), next = triangles_((k + 1) % 3, t),
                previous = triangles_((k + 2) % 3, t);
      const Eigen::Vector3d corner = vertices_.col(at);
      vertex_normals_.col(at) +=
          angle_between(vertices_.col(next) - corner, vertices_.col(previous) - corner) *
          face_normals_.col(t);
      // The side from `next` to `previous` is opposite corner k.
      const std::pair<int, int> key(std::min(next, previous), std::max(next, previous));
      const auto [found, added] = edge_of.try_emplace(key, static_cast<int>(edges_.size()));
      if (added) {
        edges_.push_back({next, previous, static_cast<int>(t), -1});
      } else {
        MeshEdge& edge = edges_[static_cast<std::size_t>(found->second)];
        if (edge.right >= 0) {
          ++quality_.non_manifold_edges;
        } else {
          edge.right = static_cast<int>(t);
          if (edge.from == next) ++quality_.misoriented_edges;  // run the same way
        }
      }
      triangle_edges_(k, t) = found->second;
    }
  }
  for (Eigen::Index v = 0; v < n; ++v)
    if (vertex_normals_.col(v).squaredNorm() > 0.0) vertex_normals_.col(v).normalize();
  edge_normals_.reserve(edges_.size());
  for (const MeshEdge& edge : edges_) {
    if (edge.right < 0) ++quality_.border_edges;
    Eigen::Vector3d sum = face_normals_.col(edge.left);
    if (edge.right >= 0) sum += face_normals_.col(edge.right);
    // Two faces folded flat onto each other: either face's normal.
    edge_normals_.push_back(sum.squaredNorm() > 1e-24
                                ? Eigen::Vector3d(sum.normalized())
                                : Eigen::Vector3d(face_normals_.col(edge.left)));
  }
  std::vector<fcl::Vector3d> points(static_cast<std::size_t>(n));
  for (Eigen::Index v = 0; v < n; ++v) points[static_cast<std::size_t>(v)] = vertices_.col(v);
  std::vector<fcl::Triangle> faces(static_cast<std::size_t>(m));
  for (Eigen::Index t = 0; t < m; ++t)
    faces[static_cast<std::size_t>(t)] =
        fcl::Triangle(triangles_(0, t), triangles_(1, t), triangles_(2, t));
  bvh_ = std::make_shared<MeshBvh>();
  bvh_->beginModel(static_cast<int>(m), static_cast<int>(n));
  bvh_->addSubModel(points, faces);
  bvh_->endModel();
  bvh_->computeLocalAABB();
}

std::optional<MeshSurfacePoint> MeshSurface::nearest(const Eigen::Vector3d& p, double bound) const {
  double best2 = bound * bound;  // m^2: only nearer triangles are looked at
  if (!(best2 > 0.0)) best2 = 0.0;
  int best_triangle = -1;
  PointTriangleProximity best;
  // Depth-first, nearer child first, pruned by the nearest distance found so far.
  thread_local std::vector<int> stack;
  stack.clear();
  stack.push_back(0);
  while (!stack.empty()) {
    const int id = stack.back();
    stack.pop_back();
    const auto& node = bvh_->getBV(id);
    if (squared_distance_to_box(node.bv, p) > best2) continue;
    if (node.isLeaf()) {
      const int t = node.primitiveId();
      const PointTriangleProximity near = closest_point_on_triangle(
          p, vertices_.col(triangles_(0, t)), vertices_.col(triangles_(1, t)),
          vertices_.col(triangles_(2, t)));
      const double d2 = (near.closest - p).squaredNorm();
      if (d2 <= best2) {
        best2 = d2;
        best = near;
        best_triangle = t;
      }
      continue;
    }
    const int left = node.leftChild(), right = node.rightChild();
    const double to_left = squared_distance_to_box(bvh_->getBV(left).bv, p);
    const double to_right = squared_distance_to_box(bvh_->getBV(right).bv, p);
    // The nearer child is popped first.
    if (to_left <= to_right) {
      stack.push_back(right);
      stack.push_back(left);
    } else {
      stack.push_back(left);
      stack.push_back(right);
    }
  }
  if (best_triangle < 0) return std::nullopt;
  // The pseudo-normal of the feature the nearest point lies on.
  Eigen::Vector3d pseudo = face_normals_.col(best_triangle);
  switch (best.region) {
    case TriangleRegion::face:
      break;
    case TriangleRegion::edge:
      pseudo =
          edge_normals_[static_cast<std::size_t>(triangle_edges_(best.feature, best_triangle))];
      break;
    case TriangleRegion::corner:
      pseudo = vertex_normals_.col(triangles_(best.feature, best_triangle));
      break;
  }
  MeshSurfacePoint out;
  out.closest = best.closest;
  out.triangle = best_triangle;
  const Eigen::Vector3d away = p - best.closest;
  const double length = away.norm();
  const bool inside = away.dot(pseudo) < 0.0;
  out.distance = inside ? -length : length;
  // On the surface (within rounding of it) the direction to the point is noise: the feature's
  // pseudo-normal is the way out.
  out.normal = length > kOnSurface ? Eigen::Vector3d((inside ? -away : away) / length) : pseudo;
  return out;
}

std::optional<MeshSurfacePoint> MeshSurface::signed_nearest(const Eigen::Vector3d& p,
                                                            double bound) const {
  return nearest(p, bounds_.contains(p) ? std::numeric_limits<double>::infinity() : bound);
}

void MeshSurface::triangles_in_box(const Eigen::AlignedBox3d& box, std::vector<int>& out) const {
  out.clear();
  thread_local std::vector<int> stack;
  stack.clear();
  stack.push_back(0);
  while (!stack.empty()) {
    const auto& node = bvh_->getBV(stack.back());
    stack.pop_back();
    if ((node.bv.min_.array() > box.max().array()).any() ||
        (node.bv.max_.array() < box.min().array()).any())
      continue;
    if (node.isLeaf()) {
      out.push_back(node.primitiveId());
      continue;
    }
    stack.push_back(node.leftChild());
    stack.push_back(node.rightChild());
  }
}

}  // namespace drapelab
