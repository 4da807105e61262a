// A triangle mesh as read from an OBJ file: a cloth's rest shape (mesh_cloth.hpp) or a collider's
// surface (mesh_surface.hpp).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace drapelab {

struct TriangleMesh {
  Eigen::Matrix3Xd vertices;   // m
  Eigen::Matrix3Xi triangles;  // vertex indices, consistently wound
  Eigen::Matrix2Xd uvs;        // one per vertex in [0, 1], or empty (then planar)
};

// The mesh's connected parts (triangles joined through shared vertices), each as the list of its
// vertices in increasing order; parts ordered by their lowest vertex. Vertices no triangle uses
// are left out.
std::vector<std::vector<int>> connected_parts(const TriangleMesh& mesh);

}  // namespace drapelab
