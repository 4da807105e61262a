// A collider's triangle mesh prepared for contact: FCL's bounding-volume hierarchy over its
// triangles, and pseudo-normals at its faces, edges and vertices that sign the distance to it.
//
// The sign follows Baerentzen and Aanaes ("Signed distance computation using the angle weighted
// pseudonormal", 2005): a point is inside a closed, consistently wound mesh exactly when it lies
// behind the pseudo-normal of the surface feature nearest to it: the face's normal when the
// nearest point is inside a triangle, the sum of the two faces' normals on an edge, and at a
// vertex the sum of its triangles' normals weighted by their angles there. An open mesh is solid
// behind each face, as far as the point's nearest feature decides (docs/contact.md, "Mesh
// colliders").
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drapelab/triangle_mesh.hpp"

namespace fcl {
template <typename S>
class AABB;
template <typename BV>
class BVHModel;
}  // namespace fcl

namespace drapelab {

// The point of the surface nearest to a query point, all in the mesh's frame.
struct MeshSurfacePoint {
  double distance = 0.0;                              // m, signed: negative inside
  Eigen::Vector3d closest = Eigen::Vector3d::Zero();  // m
  // Unit, the way out of the solid from the query point: towards it from the surface when outside,
  // away from it when inside, the feature's pseudo-normal when it lies on the surface.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();
  int triangle = -1;
};

// An edge of the mesh and the triangles on each side (-1 on an open border; a third triangle on
// the same edge is counted in MeshQuality, not kept).
struct MeshEdge {
  int from = 0, to = 0;
  int left = -1, right = -1;
};

// What the loader warns about: a closed, manifold, consistently wound mesh has none of these.
struct MeshQuality {
  int border_edges = 0;        // edges with one triangle: the mesh is open there
  int non_manifold_edges = 0;  // edges with three or more triangles
  int misoriented_edges = 0;   // edges whose two triangles run along them the same way
  double volume = 0.0;         // m^3, enclosed (divergence theorem); negative when wound inwards
};

using MeshBvh = fcl::BVHModel<fcl::AABB<double>>;

class MeshSurface {
 public:
  // Throws std::invalid_argument for an empty mesh, a non-finite vertex, an index out of range or
  // a triangle of zero area (mesh_surface_problem says which).
  explicit MeshSurface(const TriangleMesh& mesh);

  const Eigen::Matrix3Xd& vertices() const { return vertices_; }
  const Eigen::Matrix3Xi& triangles() const { return triangles_; }
  const Eigen::Matrix3Xd& face_normals() const { return face_normals_; }
  const std::vector<MeshEdge>& edges() const { return edges_; }
  // Edge e's pseudo-normal (unit): the mean of its faces' normals.
  const Eigen::Vector3d& edge_normal(int e) const { return edge_normals_[e]; }
  // Vertex v's angle-weighted pseudo-normal (unit).
  Eigen::Vector3d vertex_normal(int v) const { return vertex_normals_.col(v); }
  // The edge of triangle t opposite its corner k.
  int triangle_edge(int t, int k) const { return triangle_edges_(k, t); }
  const MeshQuality& quality() const { return quality_; }
  // The box around every vertex (m).
  const Eigen::AlignedBox3d& bounds() const { return bounds_; }
  // FCL's hierarchy of the triangles, which is also the collider's FCL geometry.
  std::shared_ptr<MeshBvh> bvh() const { return bvh_; }

  // The nearest surface point to p no farther than `bound` (m, unsigned), or nothing.
  std::optional<MeshSurfacePoint> nearest(const Eigen::Vector3d& p, double bound) const;
  // The nearest surface point to p, searching without a bound where p may be inside (within the
  // mesh's box) and within `bound` (m) elsewhere: outside the box the point is outside the solid,
  // so a caller that wants only points nearer than `bound` loses nothing.
  std::optional<MeshSurfacePoint> signed_nearest(const Eigen::Vector3d& p, double bound) const;
  // Every triangle whose box meets `box`, into `out` (cleared first).
  void triangles_in_box(const Eigen::AlignedBox3d& box, std::vector<int>& out) const;

 private:
  Eigen::Matrix3Xd vertices_;
  Eigen::Matrix3Xi triangles_;
  Eigen::Matrix3Xd face_normals_;
  Eigen::Matrix3Xd vertex_normals_;
  Eigen::Matrix3Xi triangle_edges_;  // row k: the edge opposite corner k
  std::vector<MeshEdge> edges_;
  std::vector<Eigen::Vector3d> edge_normals_;
  MeshQuality quality_;
  Eigen::AlignedBox3d bounds_;
  std::shared_ptr<MeshBvh> bvh_;
};

// Why `mesh` cannot be a collider's surface (no vertex or triangle, a non-finite vertex, an index
// out of range, a triangle of zero area, with the triangle's number), or nothing.
std::optional<std::string> mesh_surface_problem(const TriangleMesh& mesh);

}  // namespace drapelab
