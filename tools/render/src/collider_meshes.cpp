// Collider meshes: tessellated spheres, capped cylinders, capsules, boxes and floor patches.
#include "drapelab/render/collider_meshes.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace drapelab::render {
namespace {

constexpr int kSlices = 48;  // segments around a round shape: smooth at a few hundred pixels
constexpr int kStacks = 24;  // latitude bands of a sphere (half for each capsule cap)
constexpr double kPi = std::numbers::pi;

// Grows a mesh vertex by vertex and triangle by triangle.
class MeshBuilder {
 public:
  explicit MeshBuilder(const Eigen::Vector3f& color) : color_(color) {}
  int vertex(const Eigen::Vector3d& p, const Eigen::Vector3d& n) { return vertex(p, n, color_); }
  int vertex(const Eigen::Vector3d& p, const Eigen::Vector3d& n, const Eigen::Vector3f& color) {
    positions_.push_back(p);
    normals_.push_back(n.normalized());
    colors_.push_back(color);
    return static_cast<int>(positions_.size()) - 1;
  }
  void triangle(int a, int b, int c) { triangles_.emplace_back(a, b, c); }
  void quad(int a, int b, int c, int d) {  // a b c d counter-clockwise
    triangle(a, b, c);
    triangle(a, c, d);
  }
  DrawMesh build() const {
    DrawMesh mesh;
    const auto v = static_cast<Eigen::Index>(positions_.size());
    mesh.positions.resize(3, v);
    mesh.normals.resize(3, v);
    mesh.colors.resize(3, v);
    for (Eigen::Index k = 0; k < v; ++k) {
      mesh.positions.col(k) = positions_[k];
      mesh.normals.col(k) = normals_[k];
      mesh.colors.col(k) = colors_[k];
    }
    mesh.triangles.resize(3, static_cast<Eigen::Index>(triangles_.size()));
    for (std::size_t t = 0; t < triangles_.size(); ++t)
      mesh.triangles.col(Eigen::Index(t)) = triangles_[t];
    return mesh;
  }

 private:
  Eigen::Vector3f color_;
  std::vector<Eigen::Vector3d> positions_, normals_;
  std::vector<Eigen::Vector3f> colors_;
  std::vector<Eigen::Vector3i> triangles_;
};

// A unit direction at longitude phi (about +y, from +x towards -z) and latitude theta (from -pi/2
// at the bottom to pi/2 at the top).
Eigen::Vector3d direction(double phi, double theta) {
  return {std::cos(theta) * std::cos(phi), std::sin(theta), -std::cos(theta) * std::sin(phi)};
}

// A band of a surface of revolution about +y: rings at the given latitudes on spheres of `radius`
// centred at (0, offset[k], 0); consecutive rings joined. Smooth normals from the sphere.
void add_revolution(MeshBuilder& builder, double radius, const std::vector<double>& latitudes,
                    const std::vector<double>& offsets) {
  std::vector<int> previous;
  for (std::size_t r = 0; r < latitudes.size(); ++r) {
    std::vector<int> ring;
    for (int s = 0; s <= kSlices;
         ++s) {  // the seam is duplicated so every quad has its own indices
      const Eigen::Vector3d n = direction(2.0 * kPi * s / kSlices, latitudes[r]);
      ring.push_back(builder.vertex(radius * n + Eigen::Vector3d(0, offsets[r], 0), n));
    }
    if (!previous.empty())
      for (int s = 0; s < kSlices; ++s)
        builder.quad(previous[s], previous[s + 1], ring[s + 1], ring[s]);
    previous = ring;
  }
}

// A flat disc cap at height y facing +y (up) or -y.
void add_cap(MeshBuilder& builder, double radius, double y, bool up) {
  const Eigen::Vector3d n(0, up ? 1.0 : -1.0, 0);
  const int center = builder.vertex(Eigen::Vector3d(0, y, 0), n);
  std::vector<int> ring;
  for (int s = 0; s <= kSlices; ++s) {
    const double phi = 2.0 * kPi * s / kSlices;
    ring.push_back(
        builder.vertex(Eigen::Vector3d(radius * std::cos(phi), y, -radius * std::sin(phi)), n));
  }
  for (int s = 0; s < kSlices; ++s) {
    if (up)
      builder.triangle(center, ring[s], ring[s + 1]);
    else
      builder.triangle(center, ring[s + 1], ring[s]);
  }
}

// Rotates a mesh built along +y onto `axis`.
void orient_along(DrawMesh& mesh, const Eigen::Vector3d& axis) {
  const Eigen::Matrix3d r =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitY(), axis.normalized())
          .toRotationMatrix();
  mesh.positions = r * mesh.positions;
  mesh.normals = r * mesh.normals;
}

DrawMesh sphere_mesh(double radius, const Eigen::Vector3f& color) {
  MeshBuilder builder(color);
  std::vector<double> latitudes, offsets;
  for (int k = 0; k <= kStacks; ++k) {
    latitudes.push_back(-kPi / 2 + kPi * k / kStacks);
    offsets.push_back(0.0);
  }
  add_revolution(builder, radius, latitudes, offsets);
  return builder.build();
}

DrawMesh cylinder_mesh(double radius, double height, const Eigen::Vector3d& axis,
                       const Eigen::Vector3f& color) {
  MeshBuilder builder(color);
  // The side: two rings on the equator of spheres centred at the bottom and top cap (normals
  // radial).
  add_revolution(builder, radius, {0.0, 0.0}, {-height / 2, height / 2});
  add_cap(builder, radius, -height / 2, false);
  add_cap(builder, radius, height / 2, true);
  DrawMesh mesh = builder.build();
  orient_along(mesh, axis);
  return mesh;
}

DrawMesh capsule_mesh(double radius, double height, const Eigen::Vector3d& axis,
                      const Eigen::Vector3f& color) {
  MeshBuilder builder(color);
  std::vector<double> latitudes, offsets;
  const int half = kStacks / 2;
  for (int k = 0; k <= half; ++k) {  // bottom hemisphere up to the equator, then the top one
    latitudes.push_back(-kPi / 2 + (kPi / 2) * k / half);
    offsets.push_back(-height / 2);
  }
  for (int k = 0; k <= half; ++k) {
    latitudes.push_back((kPi / 2) * k / half);
    offsets.push_back(height / 2);
  }
  add_revolution(builder, radius, latitudes, offsets);
  DrawMesh mesh = builder.build();
  orient_along(mesh, axis);
  return mesh;
}

DrawMesh box_mesh(const Eigen::Vector3d& half, const Eigen::Vector3f& color) {
  MeshBuilder builder(color);
  for (int axis = 0; axis < 3; ++axis)
    for (const double sign : {-1.0, 1.0}) {
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      n[axis] = sign;
      // Two in-face directions u, v with u x v = n, so the face is counter-clockwise from outside.
      const Eigen::Vector3d u = Eigen::Vector3d::Unit((axis + 1) % 3) * sign;
      const Eigen::Vector3d v = n.cross(u);
      const Eigen::Vector3d c = n.cwiseProduct(half);
      const Eigen::Vector3d du = u.cwiseAbs().cwiseProduct(half).norm() * u;
      const Eigen::Vector3d dv = v.cwiseAbs().cwiseProduct(half).norm() * v;
      builder.quad(builder.vertex(c - du - dv, n), builder.vertex(c + du - dv, n),
                   builder.vertex(c + du + dv, n), builder.vertex(c - du + dv, n));
    }
  return builder.build();
}

// A mesh collider's own triangles, each corner shaded by the mean normal of the triangles about
// its vertex that turn from this one by less than kSmoothTurn: curved surfaces look smooth and
// sharp edges (a table's rim, a box's edges) stay sharp.
DrawMesh surface_mesh(const TriangleMesh& mesh, const Eigen::Vector3f& color) {
  const double smooth_cosine = std::cos(30.0 * std::numbers::pi / 180.0);  // kSmoothTurn, 30 deg
  const Eigen::Index count = mesh.triangles.cols();
  Eigen::Matrix3Xd face(3, count);
  std::vector<std::vector<Eigen::Index>> faces_at(static_cast<std::size_t>(mesh.vertices.cols()));
  for (Eigen::Index t = 0; t < count; ++t) {
    const Eigen::Vector3d a = mesh.vertices.col(mesh.triangles(0, t));
    face.col(t) = (mesh.vertices.col(mesh.triangles(1, t)) - a)
                      .cross(mesh.vertices.col(mesh.triangles(2, t)) - a);  // area-weighted
    for (int k = 0; k < 3; ++k)
      faces_at[static_cast<std::size_t>(mesh.triangles(k, t))].push_back(t);
  }
  MeshBuilder builder(color);
  for (Eigen::Index t = 0; t < count; ++t) {
    const Eigen::Vector3d own = face.col(t).normalized();
    int corner[3];
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.triangles(k, t);
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      for (const Eigen::Index other : faces_at[static_cast<std::size_t>(v)])
        if (face.col(other).normalized().dot(own) >= smooth_cosine) normal += face.col(other);
      corner[k] = builder.vertex(mesh.vertices.col(v), normal);
    }
    builder.triangle(corner[0], corner[1], corner[2]);
  }
  return builder.build();
}

}  // namespace

DrawMesh solid_collider_mesh(const Collider& c, const Eigen::Vector3f& color) {
  switch (c.shape) {
    case ColliderShape::sphere:
      return sphere_mesh(c.radius, color);
    case ColliderShape::cylinder:
      return cylinder_mesh(c.radius, c.height, c.axis, color);
    case ColliderShape::capsule:
      return capsule_mesh(c.radius, c.height, c.axis, color);
    case ColliderShape::box:
      return box_mesh(c.half_extents, color);
    case ColliderShape::mesh:
      if (c.mesh) return surface_mesh(*c.mesh, color);
      break;
    case ColliderShape::plane:
      break;
  }
  throw std::invalid_argument(
      "solid_collider_mesh: a plane has no solid mesh (use plane_patch_mesh), and a mesh collider "
      "needs its mesh");
}

double round_tile_size(double span) {
  const double target = span / 10.0;
  const double decade = std::pow(10.0, std::floor(std::log10(target)));
  for (const double step : {1.0, 2.0, 5.0})
    if (step * decade * 1.5 >= target) return step * decade;
  return 10.0 * decade;
}

DrawMesh plane_patch_mesh(const Collider& plane, const Eigen::Vector3d& local_center,
                          double half_size, double tile, const Eigen::Vector3f& color_a,
                          const Eigen::Vector3f& color_b) {
  const Eigen::Vector3d n = plane.normal.normalized();
  // In-plane axes: u from the local axis least aligned with n, v = n x u, so u x v = n.
  Eigen::Index least = 0;
  n.cwiseAbs().minCoeff(&least);
  const Eigen::Vector3d u = (Eigen::Vector3d::Unit(least) - n * n[least]).normalized();
  const Eigen::Vector3d v = n.cross(u);
  const Eigen::Vector3d foot =
      local_center - n * n.dot(local_center);  // the plane passes the origin
  // Tiles aligned to whole multiples of `tile` along u and v, so the checker does not slide when
  // the patch centre moves between renders.
  const double u0 = std::floor((foot.dot(u) - half_size) / tile) * tile;
  const double v0 = std::floor((foot.dot(v) - half_size) / tile) * tile;
  const int count = static_cast<int>(std::ceil(2.0 * half_size / tile)) + 1;
  MeshBuilder builder(color_a);
  for (int i = 0; i < count; ++i)
    for (int j = 0; j < count; ++j) {
      const Eigen::Vector3f& color =
          ((i + j + static_cast<int>(std::lround(u0 / tile + v0 / tile))) % 2 == 0) ? color_a
                                                                                    : color_b;
      const double a = u0 + i * tile, b = v0 + j * tile;
      auto corner = [&](double du, double dv) {
        return builder.vertex((a + du) * u + (b + dv) * v, n, color);
      };
      builder.quad(corner(0, 0), corner(tile, 0), corner(tile, tile), corner(0, tile));
    }
  return builder.build();
}

void add_collider_bounds(const Collider& c, const Eigen::Isometry3d& pose, Bounds& bounds) {
  if (c.shape == ColliderShape::plane) return;
  if (c.shape == ColliderShape::mesh) {
    if (c.mesh)
      for (Eigen::Index v = 0; v < c.mesh->vertices.cols(); ++v)
        bounds.add(pose * Eigen::Vector3d(c.mesh->vertices.col(v)));
    return;
  }
  if (c.shape == ColliderShape::sphere) {
    bounds.add(pose.translation() - Eigen::Vector3d::Constant(c.radius));
    bounds.add(pose.translation() + Eigen::Vector3d::Constant(c.radius));
    return;
  }
  // The corners of a local box around the shape, posed: conservative for round shapes.
  Eigen::Vector3d half;
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  if (c.shape == ColliderShape::box) {
    half = c.half_extents;
  } else {
    const double extra = c.shape == ColliderShape::capsule ? c.radius : 0.0;
    half = {c.radius, c.height / 2 + extra, c.radius};
    frame = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitY(), c.axis.normalized())
                .toRotationMatrix();
  }
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner((k & 1) ? half.x() : -half.x(), (k & 2) ? half.y() : -half.y(),
                                 (k & 4) ? half.z() : -half.z());
    bounds.add(pose * (frame * corner));
  }
}

}  // namespace drapelab::render
