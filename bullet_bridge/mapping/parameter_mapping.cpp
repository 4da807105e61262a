// Our spring constants and colliders as Bullet's parameters (parameter_mapping.hpp).
#include "drapelab/bullet/parameter_mapping.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace drapelab::bullet {

double mapped_link_stiffness(double ks, double w, double h, int iterations) {
  // One Gauss-Seidel sweep moving a link by a fraction s is backward Euler on the spring when
  // s = ks w h^2 / (1 + ks w h^2); n sweeps move it by 1 - (1 - kLST)^n.
  if (ks <= 0.0 || w <= 0.0) return 0.0;
  return 1.0 - std::pow(1.0 + ks * w * h * h, -1.0 / iterations);
}

double largest_link_rate(const ClothModel& model) {
  double largest = 0.0;  // 1/s^2
  const SpringSet& s = model.springs;
  for (std::size_t e = 0; e < s.size(); ++e)
    largest =
        std::max(largest, s.ks[e] * (model.inverse_mass[s.v0[e]] + model.inverse_mass[s.v1[e]]));
  return largest;
}

double largest_mapped_step(const ClothModel& model) {
  const double rate = largest_link_rate(model);
  return rate > 0.0 ? std::sqrt(kMaxMappedLinkCompliance / rate)
                    : std::numeric_limits<double>::infinity();
}

double default_voxel_size(const std::vector<Collider>& colliders, double margin) {
  double feature = std::numeric_limits<double>::infinity();  // m, the smallest size of any collider
  for (const auto& c : colliders) {
    switch (c.shape) {
      case ColliderShape::sphere:
        feature = std::min(feature, c.radius);
        break;
      case ColliderShape::capsule:
        feature = std::min(feature, c.radius);
        break;
      case ColliderShape::cylinder:
        feature = std::min({feature, c.radius, c.height});
        break;
      case ColliderShape::box:
        feature = std::min(feature, 2.0 * c.half_extents.minCoeff());
        break;
      case ColliderShape::plane:
        break;
      case ColliderShape::mesh:
        // The signed-distance cache meets a mesh as its parts' convex hulls: a part's feature
        // is its box's shortest side.
        if (c.mesh)
          for (const std::vector<int>& part : connected_parts(*c.mesh)) {
            Eigen::AlignedBox3d box;
            for (const int v : part) box.extend(Eigen::Vector3d(c.mesh->vertices.col(v)));
            feature = std::min(feature, box.sizes().minCoeff());
          }
        break;
    }
  }
  return std::min(margin, feature / 10.0);
}

bool mesh_parts_are_convex(const TriangleMesh& mesh) {
  const Eigen::Index n = mesh.vertices.cols();
  if (n == 0) return true;
  const double size =
      (mesh.vertices.rowwise().maxCoeff() - mesh.vertices.rowwise().minCoeff()).norm();  // m
  const double tolerance = 1e-9 + 1e-7 * size;  // m: an OBJ file's printed digits
  const std::vector<std::vector<int>> parts = connected_parts(mesh);
  std::vector<std::size_t> part_of(static_cast<std::size_t>(n), 0);
  for (std::size_t p = 0; p < parts.size(); ++p)
    for (const int v : parts[p]) part_of[static_cast<std::size_t>(v)] = p;
  for (Eigen::Index t = 0; t < mesh.triangles.cols(); ++t) {
    const Eigen::Vector3d a = mesh.vertices.col(mesh.triangles(0, t));
    const Eigen::Vector3d b = mesh.vertices.col(mesh.triangles(1, t));
    const Eigen::Vector3d c = mesh.vertices.col(mesh.triangles(2, t));
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();  // outwards
    for (const int v : parts[part_of[static_cast<std::size_t>(mesh.triangles(0, t))]])
      if (normal.dot(Eigen::Vector3d(mesh.vertices.col(v)) - a) > tolerance) return false;
  }
  return true;
}

bool deformable_meets_mesh_triangles(const std::vector<Collider>& colliders) {
  return std::any_of(colliders.begin(), colliders.end(), [](const Collider& c) {
    return c.shape == ColliderShape::mesh && c.mesh && !mesh_parts_are_convex(*c.mesh);
  });
}

}  // namespace drapelab::bullet
