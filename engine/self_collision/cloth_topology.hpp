// The cloth's mesh as self-collision sees it: its unique edges, each particle's neighbours and
// triangles, each edge's triangles, and the feasible-region tests that decide whether a particle
// near an edge or a corner is in contact with that edge or corner or with a face beside it. Built
// once from the model; shared by the penalty self-contacts and vbd's offset contacts.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "drapelab/cloth_model.hpp"

namespace drapelab {

class ClothTopology {
 public:
  explicit ClothTopology(const ClothModel& model);

  const Eigen::Matrix3Xi& triangles() const { return *triangles_; }
  // Unique mesh edges, lower index first, sorted.
  const std::vector<std::array<std::int32_t, 2>>& edges() const { return edges_; }
  // Whether a and b are joined by a mesh edge.
  bool adjacent(int a, int b) const;
  // Whether particle p is a corner of triangle t.
  bool is_corner(int p, int t) const {
    const auto& tri = *triangles_;
    return tri(0, t) == p || tri(1, t) == p || tri(2, t) == p;
  }
  // Feasible regions. Whether p at x.col(p) is nearest edge a-b (a < b) on every triangle that has
  // that edge, or nearest corner q on every triangle at q: otherwise a face (or edge) of one of
  // them is nearer and holds the contact, and this one would push along a slanted line beside it.
  bool nearest_edge_everywhere(const Eigen::Matrix3Xd& x, int p, int a, int b) const;
  bool nearest_corner_everywhere(const Eigen::Matrix3Xd& x, int p, int q) const;

 private:
  const Eigen::Matrix3Xi* triangles_;
  std::vector<std::array<std::int32_t, 2>> edges_;
  std::vector<std::int32_t> neighbour_start_;  // CSR: particle i's neighbours by an edge, sorted
  std::vector<std::int32_t> neighbours_;
  std::vector<std::array<std::int32_t, 2>> edge_triangles_;  // per edge, its triangles (-1: none)
  std::vector<std::int32_t> corner_start_;                   // CSR: particle i's triangles
  std::vector<std::int32_t> corner_triangles_;
};

}  // namespace drapelab
