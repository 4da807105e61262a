// A mesh collider's sharp features (see edge_contact.hpp, collider_features).
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "contact/edge_contact.hpp"
#include "core/proximity.hpp"

namespace drapelab {

// The sharp convex edges of a mesh, and the vertices where three or more of them meet.
ColliderFeatures mesh_features(const MeshSurface& mesh) {
  ColliderFeatures features;
  features.shape = ColliderShape::mesh;
  const double sharp_cosine = std::cos(kSharpMeshTurn);
  std::vector<int> sharp_edges_at(static_cast<std::size_t>(mesh.vertices().cols()), 0);
  for (std::size_t e = 0; e < mesh.edges().size(); ++e) {
    const MeshEdge& edge = mesh.edges()[e];
    if (edge.right < 0) continue;  // an open border: no solid on its far side to push from
    const Eigen::Vector3d left = mesh.face_normals().col(edge.left);
    const Eigen::Vector3d right = mesh.face_normals().col(edge.right);
    if (left.dot(right) >= sharp_cosine) continue;
    // Convex when the right triangle's third corner lies behind the left face.
    int third = -1;
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.triangles()(k, edge.right);
      if (v != edge.from && v != edge.to) third = v;
    }
    const Eigen::Vector3d from = mesh.vertices().col(edge.from);
    if (third < 0 || left.dot(mesh.vertices().col(third) - from) >= 0.0) continue;
    features.edges.push_back({from,
                              mesh.vertices().col(edge.to),
                              mesh.edge_normal(static_cast<int>(e)),
                              {left, right, left}});
    ++sharp_edges_at[static_cast<std::size_t>(edge.from)];
    ++sharp_edges_at[static_cast<std::size_t>(edge.to)];
  }
  // A corner's faces: the normals of its triangles that differ by more than the sharp turn, the
  // three with the largest angles at the corner (feature_push takes three).
  std::vector<std::vector<std::pair<double, Eigen::Vector3d>>> faces_at(sharp_edges_at.size());
  for (Eigen::Index t = 0; t < mesh.triangles().cols(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.triangles()(k, t);
      if (sharp_edges_at[static_cast<std::size_t>(v)] < 3) continue;
      const Eigen::Vector3d at = mesh.vertices().col(v);
      const Eigen::Vector3d u = mesh.vertices().col(mesh.triangles()((k + 1) % 3, t)) - at;
      const Eigen::Vector3d w = mesh.vertices().col(mesh.triangles()((k + 2) % 3, t)) - at;
      const double angle = angle_between(u, w);  // rad, the triangle's angle at the corner
      const Eigen::Vector3d normal = mesh.face_normals().col(t);
      auto& list = faces_at[static_cast<std::size_t>(v)];
      const auto same = std::find_if(list.begin(), list.end(), [&](const auto& entry) {
        return entry.second.dot(normal) >= sharp_cosine;
      });
      if (same == list.end())
        list.emplace_back(angle, normal);
      else
        same->first += angle;
    }
  for (std::size_t v = 0; v < faces_at.size(); ++v) {
    auto& list = faces_at[v];
    if (list.size() < 2) continue;
    std::stable_sort(list.begin(), list.end(),
                     [](const auto& p, const auto& q) { return p.first > q.first; });
    const Eigen::Vector3d third = list.size() > 2 ? list[2].second : list[0].second;
    features.corners.push_back({mesh.vertices().col(static_cast<Eigen::Index>(v)),
                                mesh.vertex_normal(static_cast<int>(v)),
                                {list[0].second, list[1].second, third}});
  }
  return features;
}

}  // namespace drapelab
