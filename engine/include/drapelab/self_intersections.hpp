// Self-intersection audit of a cloth's triangle mesh (docs/metrics.md, "Self-intersections"): how
// many of its edges cross a triangle they do not touch, from the positions alone, with exact
// predicates. Independent of any solver's own self-collision handling.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace drapelab {

// The unique edges of a triangle mesh, each as (lower index, higher index), sorted.
std::vector<Eigen::Vector2i> unique_edges(const Eigen::Matrix3Xi& triangles);

// Whether segment p-q crosses triangle a-b-c: p and q strictly on opposite sides of the
// triangle's plane, and the line p-q strictly inside the triangle (the three orient3d signs of
// the line against the triangle's sides agree and are non-zero). Touching does not count: an
// endpoint on the plane, the segment through a side or a corner, or a coplanar overlap. Exact
// for finite inputs.
bool segment_crosses_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                              const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c);

// Counts, for one mesh's connectivity, the edges that cross a non-adjacent triangle of the same
// mesh (one that contains neither endpoint of the edge). Each edge counts once, however many
// triangles it crosses. The broad phase is Eigen's KdBVH over edge and triangle bounding boxes,
// rebuilt for every call; an edge or triangle with a non-finite vertex is left out.
class SelfIntersectionCounter {
 public:
  explicit SelfIntersectionCounter(const Eigen::Matrix3Xi& triangles);
  int count(const Eigen::Matrix3Xd& x) const;
  std::size_t edge_count() const { return edges_.size(); }

 private:
  Eigen::Matrix3Xi triangles_;
  std::vector<Eigen::Vector2i> edges_;
};

// One-shot form of SelfIntersectionCounter(triangles).count(x).
int count_self_intersections(const Eigen::Matrix3Xi& triangles, const Eigen::Matrix3Xd& x);

}  // namespace drapelab
