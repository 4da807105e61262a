// How deep colliders reach into the cloth's triangles, thickness included (docs/metrics.md,
// "Triangle penetration"): the particle clearance of collision_metrics.hpp misses a box edge or a
// cylinder rim that pokes between particles; this measures the whole surface of every triangle.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "drapelab/cloth_model.hpp"
#include "drapelab/contact_fcl.hpp"
#include "drapelab/contact_model.hpp"

namespace drapelab {

// Signed distance (m) from a posed collider's solid to triangle a-b-c: their distance when apart,
// minus the penetration depth (the shortest translation that separates them) when the solid
// crosses or holds the triangle. Closed forms for a half-space (the deepest vertex) and a sphere
// (centre to triangle, less the radius); FCL's GJK and EPA (libccd) for a box, a capsule or a
// cylinder, to within kTriangleDistanceTolerance. A mesh: the least of the mesh's signed distance
// (mesh_surface.hpp) over the triangle's corners and the points of the triangle over the mesh's
// vertices and edges (docs/metrics.md, "Triangle penetration").
double collider_triangle_signed_distance(const FclCollider& collider,
                                         const Eigen::Isometry3d& shape_pose,
                                         const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                         const Eigen::Vector3d& c);

// m: where FCL's GJK stops and how far EPA's depth may lie from the exact one.
inline constexpr double kTriangleDistanceTolerance = 1e-10;

// Over every triangle of the model at positions x and every collider posed at time t (s):
// max(0, h - d), h the cloth's thickness and d collider_triangle_signed_distance. 0 when the
// cloth keeps at least h from every collider; h when a collider touches a triangle; more when it
// crosses. Only triangles whose bounding box, grown by h, overlaps a collider's are measured;
// triangles with a non-finite vertex are left out.
double triangle_penetration(const ClothModel& model, const Eigen::Matrix3Xd& x,
                            const ContactModel& contacts, double t);

}  // namespace drapelab
