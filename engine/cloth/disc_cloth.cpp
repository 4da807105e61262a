// Concentric-ring disc mesh (disc_cloth.hpp).
#include "drapelab/disc_cloth.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "drapelab/cloth_limits.hpp"
#include "drapelab/collider.hpp"

namespace drapelab {

std::vector<double> disc_ring_radii(const DiscSpec& spec) {
  if (spec.rings < 1) throw std::invalid_argument("a disc needs at least 1 ring");
  if (!(spec.radius > 0.0)) throw std::invalid_argument("a disc needs a positive radius");
  std::vector<double> radii;
  const int rings = spec.rings;
  if (!spec.ring_at) {
    for (int k = 1; k <= rings; ++k) radii.push_back(spec.radius * k / rings);
    return radii;
  }
  const double support = *spec.ring_at;
  if (!(support > 0.0 && support < spec.radius) || rings < 2)
    throw std::invalid_argument("a ring at " + std::to_string(support) +
                                " m needs 0 < it < the radius " + std::to_string(spec.radius) +
                                " m and at least 2 rings");
  // Rings inside the support in proportion to its radius, at least one on each side.
  const int inside =
      std::clamp(static_cast<int>(std::lround(rings * support / spec.radius)), 1, rings - 1);
  for (int k = 1; k <= inside; ++k) radii.push_back(support * k / inside);
  for (int k = 1; k <= rings - inside; ++k)
    radii.push_back(support + (spec.radius - support) * k / (rings - inside));
  radii.back() = spec.radius;
  radii[static_cast<std::size_t>(inside - 1)] = support;  // exactly, whatever the rounding
  return radii;
}

namespace {

// Particles on ring k from the radii, as a double: a ring a hair outside the one before it would
// hold more particles than an int counts.
double ring_count(const std::vector<double>& radii, int ring) {
  const double outer = radii[static_cast<std::size_t>(ring - 1)];
  const double inner = ring >= 2 ? radii[static_cast<std::size_t>(ring - 2)] : 0.0;
  return std::max(6.0, std::round(2.0 * std::numbers::pi * outer / (outer - inner)));
}

}  // namespace

ClothSize disc_cloth_size(const DiscSpec& spec) {
  const std::vector<double> radii = disc_ring_radii(spec);
  double particles = 1.0, triangles = 0.0, inner = 1.0;
  for (int k = 1; k <= spec.rings; ++k) {
    const double count = ring_count(radii, k);
    particles += count;
    triangles += (k == 1 ? 0.0 : inner) + count;  // the zip of ring k - 1 to ring k
    inner = count;
  }
  return mesh_cloth_size(particles, triangles);
}

int disc_ring_count(const DiscSpec& spec, int ring) {
  const double count = ring_count(disc_ring_radii(spec), ring);
  if (count > static_cast<double>(kMaxClothParticles))
    throw std::invalid_argument("disc ring " + std::to_string(ring) + " would hold " +
                                count_text(count) + " particles; at most " +
                                std::to_string(kMaxClothParticles) + " are allowed in a cloth");
  return static_cast<int>(count);
}

int disc_ring_start(const DiscSpec& spec, int ring) {
  int start = 1;
  for (int k = 1; k < ring; ++k) start += disc_ring_count(spec, k);
  return ring == 0 ? 0 : start;
}

TriangleMesh make_disc_mesh(const DiscSpec& spec) {
  if (const auto problem = cloth_size_problem(disc_cloth_size(spec)))
    throw std::invalid_argument("the disc " + *problem);
  const std::vector<double> radii = disc_ring_radii(spec);
  const int rings = spec.rings;
  std::vector<int> counts(static_cast<std::size_t>(rings + 1), 1),
      starts(static_cast<std::size_t>(rings + 1), 0);
  int total = 1;
  for (int k = 1; k <= rings; ++k) {
    counts[static_cast<std::size_t>(k)] = disc_ring_count(spec, k);
    starts[static_cast<std::size_t>(k)] = total;
    total += counts[static_cast<std::size_t>(k)];
  }
  const Eigen::Matrix3d turn = euler_rotation(spec.rotation);
  TriangleMesh mesh;
  mesh.vertices.resize(3, total);
  mesh.uvs.resize(2, total);
  mesh.vertices.col(0) = spec.center;
  mesh.uvs.col(0) << 0.5, 0.5;
  for (int k = 1; k <= rings; ++k)
    for (int p = 0; p < counts[static_cast<std::size_t>(k)]; ++p) {
      const double angle = 2.0 * std::numbers::pi * p / counts[static_cast<std::size_t>(k)];
      const Eigen::Vector3d local(radii[static_cast<std::size_t>(k - 1)] * std::cos(angle), 0.0,
                                  radii[static_cast<std::size_t>(k - 1)] * std::sin(angle));
      const int v = starts[static_cast<std::size_t>(k)] + p;
      mesh.vertices.col(v) = spec.center + turn * local;
      mesh.uvs.col(v) << 0.5 + 0.5 * local.x() / spec.radius, 0.5 + 0.5 * local.z() / spec.radius;
    }

  // Zip each ring to the next by angle: always advance the ring whose next point comes first.
  std::vector<Eigen::Vector3i> triangles;
  const Eigen::Vector3d normal = turn * Eigen::Vector3d::UnitY();
  auto emit = [&](int a, int b, int c) {
    const Eigen::Vector3d n = (mesh.vertices.col(b) - mesh.vertices.col(a))
                                  .cross(mesh.vertices.col(c) - mesh.vertices.col(a));
    if (n.dot(normal) < 0.0) std::swap(b, c);
    triangles.emplace_back(a, b, c);
  };
  for (int k = 0; k < rings; ++k) {
    const int n_in = counts[static_cast<std::size_t>(k)],
              n_out = counts[static_cast<std::size_t>(k + 1)];
    auto inner = [&](int i) { return starts[static_cast<std::size_t>(k)] + i % n_in; };
    auto outer = [&](int j) { return starts[static_cast<std::size_t>(k + 1)] + j % n_out; };
    int i = n_in == 1 ? 1 : 0;  // the centre has no next point: only the outer ring advances
    int j = 0;
    while (i < n_in || j < n_out) {
      const double next_in = static_cast<double>(i + 1) / n_in,
                   next_out = static_cast<double>(j + 1) / n_out;
      if (j < n_out && (i >= n_in || next_out <= next_in)) {
        emit(inner(i), outer(j), outer(j + 1));
        ++j;
      } else {
        emit(inner(i), outer(j), inner(i + 1));
        ++i;
      }
    }
  }
  mesh.triangles.resize(3, static_cast<Eigen::Index>(triangles.size()));
  for (std::size_t t = 0; t < triangles.size(); ++t)
    mesh.triangles.col(static_cast<Eigen::Index>(t)) = triangles[t];
  return mesh;
}

}  // namespace drapelab
