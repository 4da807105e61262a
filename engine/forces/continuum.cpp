// Building the continuum elements, and the Eigen face of their kernels (drapelab/continuum.hpp).
#include "drapelab/continuum.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

#include "drapelab/cloth_model.hpp"
#include "forces/continuum_arrays.hpp"
#include "forces/continuum_families.hpp"

namespace drapelab {
namespace {

void check_params(const ContinuumParams& p) {
  if (!(p.stretch_modulus > 0.0 && std::isfinite(p.stretch_modulus)))
    throw std::invalid_argument("continuum stretch_modulus must be a positive number of N/m");
  if (!(p.poisson >= 0.0 && p.poisson < 0.5))
    throw std::invalid_argument("continuum poisson must be in [0, 0.5)");
  if (!(p.bending_rigidity >= 0.0 && std::isfinite(p.bending_rigidity)))
    throw std::invalid_argument("continuum bending_rigidity must be >= 0 N*m");
  if (!(p.damping >= 0.0 && std::isfinite(p.damping)))
    throw std::invalid_argument("continuum damping must be >= 0 s");
}

// The gradients g_0, g_1, g_2 of triangle (p0, p1, p2) in its own rest frame: with the rest edges
// written in an orthonormal basis of the triangle's plane as the 2 x 2 Dm, F = [x1 - x0, x2 - x0]
// Dm^-1, so g_1 and g_2 are Dm^-1's rows and g_0 = -(g_1 + g_2).
std::array<double, 6> rest_shape_gradient(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                          const Eigen::Vector3d& p2) {
  const Eigen::Vector3d e1 = p1 - p0, e2 = p2 - p0;
  const Eigen::Vector3d t1 = e1.normalized();
  const Eigen::Vector3d t2 = e1.cross(e2).normalized().cross(t1);
  Eigen::Matrix2d dm;
  dm << e1.dot(t1), e2.dot(t1), e1.dot(t2), e2.dot(t2);
  const Eigen::Matrix2d inverse = dm.inverse();
  return {-(inverse(0, 0) + inverse(1, 0)),
          -(inverse(0, 1) + inverse(1, 1)),
          inverse(0, 0),
          inverse(0, 1),
          inverse(1, 0),
          inverse(1, 1)};
}

// Compressed rows of (element, slot) per particle from each element's corners.
template <std::size_t Corners>
void incidence(const std::vector<std::array<std::int32_t, Corners>>& elements, int particles,
               std::vector<std::int32_t>& offsets, std::vector<std::int32_t>& of,
               std::vector<std::int32_t>& slot) {
  offsets.assign(static_cast<std::size_t>(particles) + 1, 0);
  for (const auto& corners : elements)
    for (std::int32_t p : corners) ++offsets[static_cast<std::size_t>(p) + 1];
  for (int i = 0; i < particles; ++i) offsets[i + 1] += offsets[i];
  of.resize(static_cast<std::size_t>(offsets.back()));
  slot.resize(of.size());
  std::vector<std::int32_t> next(offsets.begin(), offsets.end() - 1);
  for (std::size_t e = 0; e < elements.size(); ++e)
    for (std::size_t k = 0; k < Corners; ++k) {
      const std::int32_t at = next[static_cast<std::size_t>(elements[e][k])]++;
      of[static_cast<std::size_t>(at)] = static_cast<std::int32_t>(e);
      slot[static_cast<std::size_t>(at)] = static_cast<std::int32_t>(k);
    }
}

}  // namespace

MembraneLame membrane_lame(const ContinuumParams& params) {
  const double y = params.stretch_modulus, nu = params.poisson;
  return {y / (2.0 * (1.0 + nu)), y * nu / (1.0 - nu * nu)};
}

ContinuumElements build_continuum_elements(const Eigen::Matrix3Xd& rest,
                                           const Eigen::Matrix3Xi& triangles,
                                           const ContinuumParams& params,
                                           const std::vector<bool>& held) {
  check_params(params);
  ContinuumElements out;
  out.params = params;
  out.lame = membrane_lame(params);
  const int particles = static_cast<int>(rest.cols());
  if (!held.empty() && held.size() != static_cast<std::size_t>(particles))
    throw std::invalid_argument("continuum: the held mask must have one entry per particle");
  auto held_whole = [&](std::int32_t t) {
    if (held.empty()) return false;
    for (std::int32_t corner : out.triangle[static_cast<std::size_t>(t)])
      if (!held[static_cast<std::size_t>(corner)]) return false;
    return true;
  };
  // Membranes.
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    const Eigen::Vector3i v = triangles.col(t);
    const Eigen::Vector3d p0 = rest.col(v[0]), p1 = rest.col(v[1]), p2 = rest.col(v[2]);
    const double area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
    const double longest =
        std::max({(p1 - p0).squaredNorm(), (p2 - p1).squaredNorm(), (p0 - p2).squaredNorm()});
    if (!(area > 1e-12 * longest))
      throw std::invalid_argument("continuum: triangle " + std::to_string(t) +
                                  " has no area at rest (its corners are in a line)");
    out.triangle.push_back({v[0], v[1], v[2]});
    const auto g = rest_shape_gradient(p0, p1, p2);
    out.shape_gradient.insert(out.shape_gradient.end(), g.begin(), g.end());
    out.rest_area.push_back(area);
  }
  // Hinges: every edge with exactly two triangles (an edge of more is not a surface and bends
  // freely). Found by sorting each triangle's edges by their particle pair.
  std::vector<std::tuple<std::int32_t, std::int32_t, std::int32_t, std::int32_t, std::int32_t>>
      sides;  // (low, high, triangle, from, opposite) with the triangle's edge from -> other
  for (std::size_t t = 0; t < out.triangle.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t u = out.triangle[t][k], w = out.triangle[t][(k + 1) % 3];
      sides.emplace_back(std::min(u, w), std::max(u, w), static_cast<std::int32_t>(t), u,
                         out.triangle[t][(k + 2) % 3]);
    }
  std::sort(sides.begin(), sides.end());
  for (std::size_t s = 0; s < sides.size();) {
    std::size_t end = s;
    while (end < sides.size() && std::get<0>(sides[end]) == std::get<0>(sides[s]) &&
           std::get<1>(sides[end]) == std::get<1>(sides[s]))
      ++end;
    if (end - s == 2) {
      const auto& [low, high, t1, from, c] = sides[s];
      const auto& second = sides[s + 1];
      const std::int32_t a = from, b = from == low ? high : low, d = std::get<4>(second);
      const std::array<std::int32_t, 4> h{a, b, c, d};
      const double length2 = (rest.col(a) - rest.col(b)).squaredNorm();
      const std::int32_t t2 = std::get<2>(second);
      const double area1 = out.rest_area[static_cast<std::size_t>(t1)];
      const double area2 = out.rest_area[static_cast<std::size_t>(t2)];
      // The hinge stands for the strip of a third of its triangles about the edge. On a clamped
      // edge (one triangle held whole) the held half of that strip cannot bend: the turn happens
      // over the free half, twice the curvature over half the width, so twice the energy of an
      // interior hinge of the same turn. Second order at the clamp instead of first (a discrete
      // cantilever of 7 cells: bending length 0.992 of the continuum's instead of 0.905).
      const bool clamped = held_whole(t1) != held_whole(t2);
      const double areas = clamped ? (held_whole(t1) ? area2 : area1) : area1 + area2;
      out.hinge.push_back(h);
      out.hinge_triangle.push_back({t1, t2});
      // The second triangle runs b -> a when both windings agree (its own `from` is b).
      out.hinge_second_sign.push_back(std::get<3>(second) == b ? 1.0 : -1.0);
      out.hinge_stiffness.push_back(params.bending_rigidity * length2 / (2.0 * areas));
      out.rest_angle.push_back(hinge_angle(rest, h));
    }
    s = end;
  }
  for (std::size_t t = 0; t < out.triangle.size(); ++t) {
    for (int k = 0; k < 3; ++k) out.columns.triangle_corner[k].push_back(out.triangle[t][k]);
    for (int k = 0; k < 4; ++k)
      out.columns.gradient[k].push_back(out.shape_gradient[6 * t + 2 + k]);
  }
  for (std::size_t e = 0; e < out.hinge.size(); ++e) {
    for (int k = 0; k < 4; ++k) out.columns.hinge_corner[k].push_back(out.hinge[e][k]);
    for (int k = 0; k < 2; ++k) out.columns.hinge_triangle[k].push_back(out.hinge_triangle[e][k]);
  }
  kernels::ElementLists lists;
  lists.particles = particles;
  lists.triangle = out.triangle.empty() ? nullptr : out.triangle.front().data();
  for (int k = 0; k < 4; ++k) lists.gradient[k] = out.columns.gradient[k].data();
  lists.area = out.rest_area.data();
  lists.triangles = static_cast<std::int64_t>(out.triangle.size());
  lists.hinge = out.hinge.empty() ? nullptr : out.hinge.front().data();
  lists.hinge_triangle = out.hinge_triangle.empty() ? nullptr : out.hinge_triangle.front().data();
  lists.second_sign = out.hinge_second_sign.data();
  lists.stiffness = out.hinge_stiffness.data();
  lists.rest_angle = out.rest_angle.data();
  lists.hinges = static_cast<std::int64_t>(out.hinge.size());
  auto families = std::make_shared<kernels::ContinuumFamilies>();
  // A grid forms 2 to 4 triangle and 3 to 6 hinge families; more is not worth a pass each.
  if (build_continuum_families(lists, 8, *families)) out.families = std::move(families);
  incidence(out.triangle, particles, out.triangle_offsets, out.triangle_of, out.triangle_slot);
  incidence(out.hinge, particles, out.hinge_offsets, out.hinge_of, out.hinge_slot);
  return out;
}

std::size_t ContinuumElements::force_scratch_size() const {
  if (families) return static_cast<std::size_t>(families->scratch_size());
  const std::size_t particles = triangle_offsets.empty() ? 0 : triangle_offsets.size() - 1;
  return 6 * particles + 12 * triangle.size() + 12 * hinge.size();
}

std::vector<bool> held_particles(const ClothModel& model) {
  std::vector<bool> held(static_cast<std::size_t>(model.particle_count()));
  for (int i = 0; i < model.particle_count(); ++i)
    held[static_cast<std::size_t>(i)] = model.is_pinned(i);
  return held;
}

double continuum_energy(const ContinuumElements& elements, const Eigen::Matrix3Xd& x) {
  return kernels::continuum_energy_sum(continuum_arrays(elements), x.data(), nullptr, nullptr);
}

double membrane_energy(const ContinuumElements& elements, const Eigen::Matrix3Xd& x) {
  double membrane = 0.0;
  kernels::continuum_energy_sum(continuum_arrays(elements), x.data(), &membrane, nullptr);
  return membrane;
}

double bending_energy(const ContinuumElements& elements, const Eigen::Matrix3Xd& x) {
  double bending = 0.0;
  kernels::continuum_energy_sum(continuum_arrays(elements), x.data(), nullptr, &bending);
  return bending;
}

void add_continuum_forces(const ContinuumElements& elements, const Eigen::Matrix3Xd& x,
                          const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force) {
  std::vector<double> scratch(elements.force_scratch_size());
  kernels::add_continuum_forces(continuum_arrays(elements), x.data(), v.data(), scratch.data(),
                                force.data());
}

TriangleTerms triangle_terms(const ContinuumElements& elements, std::size_t t,
                             const Eigen::Matrix3Xd& x, bool exact_geometric) {
  TriangleTerms terms;
  Eigen::Matrix<double, 9, 9, Eigen::RowMajor> hessian, material;
  kernels::membrane_element(continuum_arrays(elements), static_cast<std::int64_t>(t), x.data(),
                            exact_geometric, terms.force.data(), hessian.data(), material.data());
  terms.hessian = hessian;
  terms.damping_hessian = material;
  return terms;
}

HingeTerms hinge_terms(const ContinuumElements& elements, std::size_t e,
                       const Eigen::Matrix3Xd& x) {
  HingeTerms terms;
  Eigen::Matrix<double, 12, 12, Eigen::RowMajor> hessian;
  kernels::hinge_element(continuum_arrays(elements), static_cast<std::int64_t>(e), x.data(),
                         &terms.angle, terms.force.data(), hessian.data());
  terms.hessian = hessian;
  return terms;
}

double hinge_angle(const Eigen::Matrix3Xd& x, const std::array<std::int32_t, 4>& hinge) {
  const Eigen::Vector3d a = x.col(hinge[0]), b = x.col(hinge[1]), c = x.col(hinge[2]),
                        d = x.col(hinge[3]);
  const Eigen::Vector3d edge = b - a;
  const Eigen::Vector3d n1 = edge.cross(c - a), n2 = (d - a).cross(edge);
  const double length = edge.norm();
  if (!(length > 0.0) || n1.squaredNorm() == 0.0 || n2.squaredNorm() == 0.0) return 0.0;
  return std::atan2(n1.cross(n2).dot(edge) / length, n1.dot(n2));
}

}  // namespace drapelab
