// Connected parts of a triangle mesh (see drapelab/triangle_mesh.hpp).
#include <numeric>

#include "drapelab/triangle_mesh.hpp"

namespace drapelab {

std::vector<std::vector<int>> connected_parts(const TriangleMesh& mesh) {
  const auto n = static_cast<std::size_t>(mesh.vertices.cols());
  // Union-find over the vertices, each triangle joining its three corners.
  std::vector<std::size_t> root(n);
  std::iota(root.begin(), root.end(), std::size_t{0});
  const auto find = [&](std::size_t v) {
    while (root[v] != v) v = root[v] = root[root[v]];
    return v;
  };
  std::vector<bool> used(n, false);
  for (Eigen::Index t = 0; t < mesh.triangles.cols(); ++t)
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::size_t>(mesh.triangles(k, t));
      const auto b = static_cast<std::size_t>(mesh.triangles((k + 1) % 3, t));
      used[a] = true;
      const std::size_t ra = find(a), rb = find(b);
      if (ra != rb) root[std::max(ra, rb)] = std::min(ra, rb);
    }
  // Each root is its part's lowest vertex, so parts come in order of their lowest vertex.
  std::vector<std::vector<int>> parts;
  std::vector<int> part_of(n, -1);
  for (std::size_t v = 0; v < n; ++v) {
    if (!used[v]) continue;
    const std::size_t r = find(v);
    if (part_of[r] < 0) {
      part_of[r] = static_cast<int>(parts.size());
      parts.emplace_back();
    }
    parts[static_cast<std::size_t>(part_of[r])].push_back(static_cast<int>(v));
  }
  return parts;
}

}  // namespace drapelab
