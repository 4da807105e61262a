// Self-intersections (see drapelab/self_intersections.hpp): a two-tree KdBVH query pairs every
// edge with the triangles whose boxes it overlaps, and exact orient3d signs decide each pair.
#include "drapelab/self_intersections.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <unsupported/Eigen/BVH>

#include "metrics/orient3d.hpp"

namespace drapelab {
namespace {

using AlignedBox = Eigen::AlignedBox3d;
using BoxList = std::vector<AlignedBox, Eigen::aligned_allocator<AlignedBox>>;
using Tree = Eigen::KdBVH<double, 3, int>;

bool finite_column(const Eigen::Matrix3Xd& x, int i) { return x.col(i).allFinite(); }

// The pairs whose boxes overlap, handed to the exact test; marks the edges found crossing.
class EdgeTriangleIntersector {
 public:
  EdgeTriangleIntersector(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xi& triangles,
                          const std::vector<Eigen::Vector2i>& edges, const BoxList& edge_boxes,
                          const BoxList& triangle_boxes, std::vector<char>& crossing)
      : x_(x),
        triangles_(triangles),
        edges_(edges),
        edge_boxes_(edge_boxes),
        triangle_boxes_(triangle_boxes),
        crossing_(crossing) {}

  bool intersectVolumeVolume(const AlignedBox& edges, const AlignedBox& triangles) const {
    return edges.intersects(triangles);
  }
  bool intersectVolumeObject(const AlignedBox& edges, int triangle) const {
    return edges.intersects(triangle_boxes_[static_cast<std::size_t>(triangle)]);
  }
  bool intersectObjectVolume(int edge, const AlignedBox& triangles) const {
    return edge_boxes_[static_cast<std::size_t>(edge)].intersects(triangles);
  }
  // Returns false: the query goes on over every pair.
  bool intersectObjectObject(int edge, int triangle) {
    const auto e = static_cast<std::size_t>(edge);
    if (crossing_[e]) return false;  // already counted
    if (!edge_boxes_[e].intersects(triangle_boxes_[static_cast<std::size_t>(triangle)]))
      return false;
    const int p = edges_[e][0], q = edges_[e][1];
    const Eigen::Vector3i t = triangles_.col(triangle);
    // Adjacent: the triangle holds an endpoint of the edge.
    if ((t.array() == p).any() || (t.array() == q).any()) return false;
    if (segment_crosses_triangle(x_.col(p), x_.col(q), x_.col(t[0]), x_.col(t[1]), x_.col(t[2])))
      crossing_[e] = 1;
    return false;
  }

 private:
  const Eigen::Matrix3Xd& x_;
  const Eigen::Matrix3Xi& triangles_;
  const std::vector<Eigen::Vector2i>& edges_;
  const BoxList& edge_boxes_;
  const BoxList& triangle_boxes_;
  std::vector<char>& crossing_;
};

}  // namespace

std::vector<Eigen::Vector2i> unique_edges(const Eigen::Matrix3Xi& triangles) {
  std::vector<Eigen::Vector2i> edges;
  edges.reserve(3 * static_cast<std::size_t>(triangles.cols()));
  for (Eigen::Index t = 0; t < triangles.cols(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles(k, t), b = triangles((k + 1) % 3, t);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  auto less = [](const Eigen::Vector2i& u, const Eigen::Vector2i& v) {
    return u[0] != v[0] ? u[0] < v[0] : u[1] < v[1];
  };
  std::sort(edges.begin(), edges.end(), less);
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

bool segment_crosses_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                              const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c) {
  const int side_p = orient3d(a, b, c, p);
  if (side_p == 0) return false;
  const int side_q = orient3d(a, b, c, q);
  if (side_q != -side_p) return false;  // same side, or q on the plane
  // The line p-q against each side of the triangle: one sign for all three means it passes
  // through the inside; a zero means it meets a side or a corner.
  const int ab = orient3d(p, q, a, b);
  if (ab == 0) return false;
  const int bc = orient3d(p, q, b, c);
  if (bc != ab) return false;
  return orient3d(p, q, c, a) == ab;
}

SelfIntersectionCounter::SelfIntersectionCounter(const Eigen::Matrix3Xi& triangles)
    : triangles_(triangles), edges_(unique_edges(triangles)) {}

int SelfIntersectionCounter::count(const Eigen::Matrix3Xd& x) const {
  if (edges_.empty()) return 0;
  std::vector<int> edge_ids, triangle_ids;
  BoxList edge_boxes(edges_.size()), triangle_boxes(static_cast<std::size_t>(triangles_.cols()));
  BoxList kept_edge_boxes, kept_triangle_boxes;
  for (std::size_t e = 0; e < edges_.size(); ++e) {
    const int p = edges_[e][0], q = edges_[e][1];
    if (!finite_column(x, p) || !finite_column(x, q)) continue;
    edge_boxes[e] = AlignedBox(x.col(p)).extend(x.col(q));
    edge_ids.push_back(static_cast<int>(e));
    kept_edge_boxes.push_back(edge_boxes[e]);
  }
  for (Eigen::Index t = 0; t < triangles_.cols(); ++t) {
    const Eigen::Vector3i v = triangles_.col(t);
    if (!finite_column(x, v[0]) || !finite_column(x, v[1]) || !finite_column(x, v[2])) continue;
    AlignedBox& box = triangle_boxes[static_cast<std::size_t>(t)];
    box = AlignedBox(x.col(v[0])).extend(x.col(v[1])).extend(x.col(v[2]));
    triangle_ids.push_back(static_cast<int>(t));
    kept_triangle_boxes.push_back(box);
  }
  if (edge_ids.empty() || triangle_ids.empty()) return 0;
  const Tree edge_tree(edge_ids.begin(), edge_ids.end(), kept_edge_boxes.begin(),
                       kept_edge_boxes.end());
  const Tree triangle_tree(triangle_ids.begin(), triangle_ids.end(), kept_triangle_boxes.begin(),
                           kept_triangle_boxes.end());
  std::vector<char> crossing(edges_.size(), 0);
  EdgeTriangleIntersector intersector(x, triangles_, edges_, edge_boxes, triangle_boxes, crossing);
  Eigen::BVIntersect(edge_tree, triangle_tree, intersector);
  return static_cast<int>(std::count(crossing.begin(), crossing.end(), 1));
}

int count_self_intersections(const Eigen::Matrix3Xi& triangles, const Eigen::Matrix3Xd& x) {
  return SelfIntersectionCounter(triangles).count(x);
}

}  // namespace drapelab
