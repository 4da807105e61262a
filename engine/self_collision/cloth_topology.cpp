// The cloth's mesh for self-collision (cloth_topology.hpp).
#include "self_collision/cloth_topology.hpp"

#include <algorithm>

#include "cloth/mesh_edges.hpp"
#include "core/proximity.hpp"

namespace drapelab {

ClothTopology::ClothTopology(const ClothModel& model)
    : triangles_(&model.triangles), edges_(mesh_edges(model.triangles)) {
  const int n = model.particle_count();
  neighbour_start_.assign(static_cast<std::size_t>(n) + 1, 0);
  for (const auto& e : edges_) {
    ++neighbour_start_[static_cast<std::size_t>(e[0]) + 1];
    ++neighbour_start_[static_cast<std::size_t>(e[1]) + 1];
  }
  for (int i = 0; i < n; ++i) neighbour_start_[i + 1] += neighbour_start_[i];
  neighbours_.resize(static_cast<std::size_t>(neighbour_start_[n]));
  std::vector<std::int32_t> filled(neighbour_start_.begin(), neighbour_start_.end() - 1);
  for (const auto& e : edges_) {
    neighbours_[static_cast<std::size_t>(filled[e[0]]++)] = e[1];
    neighbours_[static_cast<std::size_t>(filled[e[1]]++)] = e[0];
  }
  for (int i = 0; i < n; ++i)
    std::sort(neighbours_.begin() + neighbour_start_[i],
              neighbours_.begin() + neighbour_start_[i + 1]);
  // Each edge's triangles and each particle's triangles.
  edge_triangles_.assign(edges_.size(), {-1, -1});
  corner_start_.assign(static_cast<std::size_t>(n) + 1, 0);
  const auto& tri = model.triangles;
  for (int t = 0; t < tri.cols(); ++t)
    for (int k = 0; k < 3; ++k) {
      ++corner_start_[static_cast<std::size_t>(tri(k, t)) + 1];
      const std::array<std::int32_t, 2> edge{std::min(tri(k, t), tri((k + 1) % 3, t)),
                                             std::max(tri(k, t), tri((k + 1) % 3, t))};
      auto& slots = edge_triangles_[static_cast<std::size_t>(
          std::lower_bound(edges_.begin(), edges_.end(), edge) - edges_.begin())];
      (slots[0] < 0 ? slots[0] : slots[1]) = t;
    }
  for (int i = 0; i < n; ++i) corner_start_[i + 1] += corner_start_[i];
  corner_triangles_.resize(static_cast<std::size_t>(corner_start_[n]));
  std::vector<std::int32_t> next(corner_start_.begin(), corner_start_.end() - 1);
  for (int t = 0; t < tri.cols(); ++t)
    for (int k = 0; k < 3; ++k) corner_triangles_[static_cast<std::size_t>(next[tri(k, t)]++)] = t;
}

bool ClothTopology::adjacent(int a, int b) const {
  return std::binary_search(neighbours_.begin() + neighbour_start_[a],
                            neighbours_.begin() + neighbour_start_[a + 1], b);
}

bool ClothTopology::nearest_edge_everywhere(const Eigen::Matrix3Xd& x, int p, int a, int b) const {
  const auto found =
      std::lower_bound(edges_.begin(), edges_.end(), std::array<std::int32_t, 2>{a, b});
  const auto& tri = *triangles_;
  for (const std::int32_t t : edge_triangles_[static_cast<std::size_t>(found - edges_.begin())]) {
    if (t < 0) continue;
    const PointTriangleProximity near =
        closest_point_on_triangle(x.col(p), x.col(tri(0, t)), x.col(tri(1, t)), x.col(tri(2, t)));
    if (near.region == TriangleRegion::face) return false;
  }
  return true;
}

bool ClothTopology::nearest_corner_everywhere(const Eigen::Matrix3Xd& x, int p, int q) const {
  const auto& tri = *triangles_;
  for (std::int32_t k = corner_start_[q]; k < corner_start_[q + 1]; ++k) {
    const std::int32_t t = corner_triangles_[static_cast<std::size_t>(k)];
    const PointTriangleProximity near =
        closest_point_on_triangle(x.col(p), x.col(tri(0, t)), x.col(tri(1, t)), x.col(tri(2, t)));
    if (near.region != TriangleRegion::corner) return false;
  }
  return true;
}

}  // namespace drapelab
