// The unique edges of a triangle mesh (mesh_edges.hpp).
#include "cloth/mesh_edges.hpp"

#include <algorithm>

namespace drapelab {

std::vector<std::array<std::int32_t, 2>> mesh_edges(const Eigen::Matrix3Xi& triangles) {
  std::vector<std::array<std::int32_t, 2>> edges;
  edges.reserve(3 * static_cast<std::size_t>(triangles.cols()));
  for (Eigen::Index t = 0; t < triangles.cols(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = triangles(k, t), b = triangles((k + 1) % 3, t);
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

}  // namespace drapelab
