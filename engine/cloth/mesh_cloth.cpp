// Cloth from a triangle mesh: edge springs, shear and bend springs across interior edges.
#include "drapelab/mesh_cloth.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>

#include "cloth/cloth_building.hpp"
#include "drapelab/cloth_limits.hpp"

namespace drapelab {
namespace {

using building::add_spring;
using building::vertex_areas;

using Edge = std::pair<int, int>;  // (smaller index, larger index)
Edge edge_of(int a, int b) { return a < b ? Edge{a, b} : Edge{b, a}; }

// For every edge, the vertices opposite it in its (one or two) triangles, in triangle order.
std::map<Edge, std::vector<int>> opposite_vertices(const Eigen::Matrix3Xi& triangles) {
  std::map<Edge, std::vector<int>> opposite;
  for (Eigen::Index t = 0; t < triangles.cols(); ++t)
    for (int e = 0; e < 3; ++e)
      opposite[edge_of(triangles(e, t), triangles((e + 1) % 3, t))].push_back(
          triangles((e + 2) % 3, t));
  return opposite;
}

// True when (a, b) is, within 1 %, the longest edge of the triangle (a, b, c).
bool is_longest_edge(const Eigen::Matrix3Xd& rest, int a, int b, int c) {
  const double edge = (rest.col(a) - rest.col(b)).norm();
  return edge >=
         1.01 * std::max((rest.col(a) - rest.col(c)).norm(), (rest.col(b) - rest.col(c)).norm());
}

SpringSet build_mesh_springs(const MeshClothSpec& spec, const Eigen::Matrix3Xd& rest) {
  SpringSet springs;
  const auto opposite = opposite_vertices(spec.mesh.triangles);
  for (const auto& [edge, across] : opposite)
    add_spring(springs, rest, edge.first, edge.second, SpringKind::stretch, spec.stretch);
  for (const auto& [edge, across] : opposite) {
    if (across.size() != 2 || across[0] == across[1]) continue;  // a border edge
    const auto [a, b] = edge;
    const bool diagonal =
        is_longest_edge(rest, a, b, across[0]) && is_longest_edge(rest, a, b, across[1]);
    if (diagonal)
      add_spring(springs, rest, across[0], across[1], SpringKind::shear, spec.shear);
    else
      add_spring(springs, rest, across[0], across[1], SpringKind::bend, spec.bend);
  }
  return springs;
}

// Planar UVs: the vertices projected on the two longest axes of their bounding box, scaled to [0,
// 1].
Eigen::Matrix2Xd planar_uvs(const Eigen::Matrix3Xd& vertices) {
  const Eigen::Vector3d low = vertices.rowwise().minCoeff(), high = vertices.rowwise().maxCoeff();
  const Eigen::Vector3d extent = high - low;
  int axes[3] = {0, 1, 2};
  std::sort(axes, axes + 3, [&](int p, int q) { return extent[p] > extent[q]; });
  const double scale = extent[axes[0]] > 0.0 ? extent[axes[0]] : 1.0;  // keep the aspect ratio
  Eigen::Matrix2Xd uvs(2, vertices.cols());
  for (Eigen::Index i = 0; i < vertices.cols(); ++i) {
    uvs(0, i) = (vertices(axes[0], i) - low[axes[0]]) / scale;
    uvs(1, i) = (vertices(axes[1], i) - low[axes[1]]) / scale;
  }
  return uvs;
}

}  // namespace

std::optional<std::string> mesh_problem(const TriangleMesh& mesh) {
  const Eigen::Index n = mesh.vertices.cols();
  if (n < 3) return "a mesh needs at least 3 vertices, got " + std::to_string(n);
  if (mesh.triangles.cols() == 0) return std::string("a mesh needs at least one triangle (face)");
  // Before the edge map below, whose memory grows with the triangles.
  if (const auto problem = cloth_size_problem(
          mesh_cloth_size(static_cast<double>(n), static_cast<double>(mesh.triangles.cols()))))
    return "the mesh " + *problem;
  for (Eigen::Index v = 0; v < n; ++v)
    if (!mesh.vertices.col(v).allFinite())
      return "vertex " + std::to_string(v) + " has a coordinate that is not a finite number";
  std::vector<char> used(static_cast<std::size_t>(n), 0);
  for (Eigen::Index t = 0; t < mesh.triangles.cols(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.triangles(c, t);
      if (v < 0 || v >= n)
        return "triangle " + std::to_string(t) + " uses vertex " + std::to_string(v) +
               ", outside 0.." + std::to_string(n - 1);
      used[static_cast<std::size_t>(v)] = 1;
    }
    const Eigen::Vector3d a = mesh.vertices.col(mesh.triangles(0, t)),
                          b = mesh.vertices.col(mesh.triangles(1, t)),
                          c = mesh.vertices.col(mesh.triangles(2, t));
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    if ((b - a).cross(c - a).norm() <= 1e-12 * longest * longest)
      return "triangle " + std::to_string(t) +
             " has no area (its vertices are repeated or collinear)";
  }
  for (Eigen::Index v = 0; v < n; ++v)
    if (!used[static_cast<std::size_t>(v)])
      return "vertex " + std::to_string(v) + " is used by no triangle";
  for (const auto& [edge, across] : opposite_vertices(mesh.triangles))
    if (across.size() > 2)
      return "the edge between vertices " + std::to_string(edge.first) + " and " +
             std::to_string(edge.second) + " is shared by " + std::to_string(across.size()) +
             " triangles (a cloth surface allows at most 2)";
  if (mesh.uvs.cols() != 0 && mesh.uvs.cols() != n)
    return "there are " + std::to_string(mesh.uvs.cols()) + " texture coordinates for " +
           std::to_string(n) + " vertices";
  return std::nullopt;
}

ClothModel build_mesh_cloth(const MeshClothSpec& spec) {
  if (const auto problem = mesh_problem(spec.mesh)) throw std::invalid_argument(*problem);
  if (spec.mass.has_value() == spec.areal_density.has_value())
    throw std::invalid_argument("mesh cloth needs exactly one of mass and areal_density");
  ClothModel model;
  const int count = static_cast<int>(spec.mesh.vertices.cols());
  model.thickness = spec.thickness;
  model.rest_positions = spec.mesh.vertices;
  model.triangles = spec.mesh.triangles;
  model.uvs = spec.mesh.uvs.cols() == count ? spec.mesh.uvs : planar_uvs(spec.mesh.vertices);
  model.vertex_area = vertex_areas(model.rest_positions, model.triangles);
  model.springs = build_mesh_springs(spec, model.rest_positions);
  model.mass = spec.mass ? Eigen::VectorXd::Constant(count, *spec.mass / count)
                         : Eigen::VectorXd(*spec.areal_density * model.vertex_area);
  model.inverse_mass = model.mass.cwiseInverse();
  for (int k : spec.pinned) {
    if (k < 0 || k >= count)
      throw std::invalid_argument("pin index " + std::to_string(k) + " is outside 0.." +
                                  std::to_string(count - 1));
    model.inverse_mass[k] = 0.0;
  }
  building::attach_continuum(spec, model);
  return model;
}

Eigen::Matrix3Xd vertex_normals(const Eigen::Matrix3Xd& positions,
                                const Eigen::Matrix3Xi& triangles) {
  Eigen::Matrix3Xd normals = Eigen::Matrix3Xd::Zero(3, positions.cols());
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    const int a = triangles(0, t), b = triangles(1, t), c = triangles(2, t);
    // The cross product's length is twice the area: an area-weighted sum.
    const Eigen::Vector3d n =
        (positions.col(b) - positions.col(a)).cross(positions.col(c) - positions.col(a));
    normals.col(a) += n;
    normals.col(b) += n;
    normals.col(c) += n;
  }
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    const double length = normals.col(i).norm();
    if (length > 0.0) normals.col(i) /= length;
  }
  return normals;
}

ClothState initial_mesh_state(const ClothModel& model, double amplitude, std::uint64_t seed) {
  ClothState state;
  state.x = model.rest_positions;
  state.v = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  if (amplitude > 0.0) {
    std::mt19937_64 random(seed);  // the same reproducible mapping as initial_grid_state
    const Eigen::Matrix3Xd normals = vertex_normals(model.rest_positions, model.triangles);
    for (int k = 0; k < model.particle_count(); ++k) {
      const double unit = static_cast<double>(random() >> 11) * 0x1.0p-53;  // [0, 1)
      if (!model.is_pinned(k)) state.x.col(k) += amplitude * (2.0 * unit - 1.0) * normals.col(k);
    }
  }
  return state;
}

}  // namespace drapelab
