// Cloth from any triangle mesh (an OBJ file, or the disc builder's rings): particles at the
// vertices, springs from the triangles.
//
// Springs (documented in the scene reference):
//   stretch  every edge of the mesh;
//   shear    across an interior edge that is the longest edge of both its triangles (to 1 %): the
//            other diagonal of the quad the two triangles make, so a quad mesh split into triangles
//            gets the grid's two diagonals per cell;
//   bend     across every other interior edge: the two vertices opposite it (a flexion spring),
//            which resists folding about that edge.
// Triangles already resist in-plane shear through their edges, so on a mesh of near-equilateral
// triangles (like the disc, where about a third of the interior edges happen to be long diagonals)
// shear and bend springs both mostly add bending stiffness.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/triangle_mesh.hpp"

namespace drapelab {

struct MeshClothSpec : ClothPhysicsSpec {
  TriangleMesh mesh;
  std::vector<int> pinned;  // particle indices held fixed
};

// Checks the mesh: its size within cloth_limits.hpp, finite vertices, indices in range, no
// degenerate (zero-area) triangle, no edge shared by more than two triangles, every vertex used.
// Returns the first problem, or nothing.
std::optional<std::string> mesh_problem(const TriangleMesh& mesh);

// Builds the model. Throws std::invalid_argument on a mesh_problem, on a missing or doubled mass,
// or on a pin out of range.
ClothModel build_mesh_cloth(const MeshClothSpec& spec);

// Unit normal per vertex: the area-weighted mean of its triangles' normals.
Eigen::Matrix3Xd vertex_normals(const Eigen::Matrix3Xd& positions,
                                const Eigen::Matrix3Xi& triangles);

// The initial state of any cloth: rest positions, each free particle offset along its vertex normal
// by a uniform random amount in [-amplitude, amplitude] (m) drawn from `seed`; zero velocity.
ClothState initial_mesh_state(const ClothModel& model, double amplitude, std::uint64_t seed);

}  // namespace drapelab
