// The terms of vbd's coarse step over plain arrays (vbd_loops.hpp): each aggregate moves as a
// rigid patch, particle i of aggregate a by P_i (t, w) = t + w x r_i with r_i = x_i - c_a, so the
// Newton step on G over (t, w) has the matrix sum P_i^T H P_j and the right-hand side sum P_i^T f_i
// (the aggregate's force, and its torque about c_a). No Eigen (see vbd_loops.hpp).
#include <algorithm>
#include <cmath>

#include "integrators/vbd/vbd_block.hpp"
#include "integrators/vbd/vbd_loops.hpp"

namespace drapelab::kernels {
namespace {

// A 3 x 3 matrix, row-major.
struct Mat3 {
  double m[9] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  double& operator()(int r, int c) { return m[3 * r + c]; }
  double operator()(int r, int c) const { return m[3 * r + c]; }
};

Mat3 symmetric(const double* h) {  // from the six entries xx, yy, zz, xy, xz, yz
  Mat3 s;
  s.m[0] = h[0];
  s.m[4] = h[1];
  s.m[8] = h[2];
  s.m[1] = s.m[3] = h[3];
  s.m[2] = s.m[6] = h[4];
  s.m[5] = s.m[7] = h[5];
  return s;
}

// [r]x, the matrix of v -> r x v.
Mat3 cross_matrix(const double* r) {
  Mat3 c;
  c(0, 1) = -r[2];
  c(0, 2) = r[1];
  c(1, 0) = r[2];
  c(1, 2) = -r[0];
  c(2, 0) = -r[1];
  c(2, 1) = r[0];
  return c;
}

Mat3 product(const Mat3& a, const Mat3& b) {
  Mat3 p;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) p(r, c) = a(r, 0) * b(0, c) + a(r, 1) * b(1, c) + a(r, 2) * b(2, c);
  return p;
}

// out (6 x 6, row-major) += sign B in its top left: the block of translations alone.
void add_translation(const Mat3& b, double sign, double* out) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out[6 * r + c] += sign * b(r, c);
}

// out (6 x 6, row-major) += sign P_a^T B P_b, with P = [I, -[r]x]: the blocks B, -B [rb]x,
// [ra]x B and -[ra]x B [rb]x.
void add_projected(const Mat3& b, const double* ra, const double* rb, double sign, double* out) {
  const Mat3 ca = cross_matrix(ra), cb = cross_matrix(rb);
  const Mat3 b_cb = product(b, cb);
  const Mat3 ca_b = product(ca, b);
  const Mat3 ca_b_cb = product(ca, b_cb);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      out[6 * r + c] += sign * b(r, c);
      out[6 * r + 3 + c] -= sign * b_cb(r, c);
      out[6 * (3 + r) + c] += sign * ca_b(r, c);
      out[6 * (3 + r) + 3 + c] -= sign * ca_b_cb(r, c);
    }
}

// A spring inside an aggregate does not stretch when the patch moves rigidly; against a rotation
// w it resists only through its tension, across (|d|^2 I - d d^T) on w with d = x_i - x_j and
// across = ks (1 - l0 / l) while it is stretched (N/m).
void add_tension(const double* xi, const double* xj, double rest_length, double ks, double* out) {
  const double d[3] = {xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]};
  const double length2 = dot(d, d);
  const double length = std::sqrt(length2);
  if (!(length > rest_length)) return;
  const double across = ks * (1.0 - rest_length / length);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out[6 * (3 + r) + 3 + c] += across * ((r == c ? length2 : 0.0) - d[r] * d[c]);
}

// Aggregate a's mass centre, radius, force and torque, and block (VbdCoarseTerms).
void aggregate_terms(const VbdProblem& p, const double* x, const VbdAggregates& g, std::int64_t a,
                     const VbdCoarseTerms& out) {
  double* centre = out.centre + 3 * a;
  double mass = 0.0;
  centre[0] = centre[1] = centre[2] = 0.0;
  for (std::int32_t k = g.offsets[a]; k < g.offsets[a + 1]; ++k) {
    const std::int64_t i = g.members[k];
    mass += p.mass[i];
    for (int d = 0; d < 3; ++d) centre[d] += p.mass[i] * x[3 * i + d];
  }
  for (int d = 0; d < 3; ++d) centre[d] /= mass;
  double* force = out.force + 6 * a;
  double* block = out.block + 36 * a;
  std::fill(force, force + 6, 0.0);
  std::fill(block, block + 36, 0.0);
  double radius = 0.0;
  const VbdSprings& s = g.springs;
  for (std::int32_t k = g.offsets[a]; k < g.offsets[a + 1]; ++k) {
    const std::int64_t i = g.members[k];
    const double* xi = x + 3 * i;
    const double r[3] = {xi[0] - centre[0], xi[1] - centre[1], xi[2] - centre[2]};
    radius = std::max(radius, std::sqrt(dot(r, r)));
    // Everything but the springs, then the springs: their forces (unless the elements give them),
    // the whole block of those that leave the aggregate, the tension of those inside it (each
    // once, from its lower end).
    Block b;
    particle_block(p, i, x, SpringTerms::none, b);
    for (std::int32_t e = s.offsets[i]; e < s.offsets[i + 1]; ++e) {
      const std::int64_t j = s.other[e];
      const bool inside = g.of[j] == a;
      Block spring;
      add_spring(xi, p.start + 3 * i, x + 3 * j, p.start + 3 * j, s.rest_length[e], s.ks[e],
                 s.kd[e], p.h, !inside, spring);
      if (g.spring_forces)
        for (int d = 0; d < 3; ++d) b.f[d] += spring.f[d];
      if (!inside)
        for (int d = 0; d < 6; ++d) b.h[d] += spring.h[d];
      else if (j > i && g.turns)
        add_tension(xi, x + 3 * j, s.rest_length[e], s.ks[e], block);
    }
    for (int d = 0; d < 3; ++d) force[d] += b.f[d];
    if (!g.turns) {
      add_translation(symmetric(b.h), 1.0, block);
      continue;
    }
    const double torque[3] = {r[1] * b.f[2] - r[2] * b.f[1], r[2] * b.f[0] - r[0] * b.f[2],
                              r[0] * b.f[1] - r[1] * b.f[0]};
    for (int d = 0; d < 3; ++d) force[3 + d] += torque[d];
    add_projected(symmetric(b.h), r, r, 1.0, block);
  }
  out.radius[a] = radius;
}

// Pair q's block -sum P_a^T B P_b over the springs joining its aggregates.
void pair_terms(const VbdProblem& p, const double* x, const VbdAggregates& g, std::int64_t q,
                const VbdCoarseTerms& out) {
  const double* ca = out.centre + 3 * g.pair_aggregates[2 * q];
  const double* cb = out.centre + 3 * g.pair_aggregates[2 * q + 1];
  double* block = out.pair_block + 36 * q;
  std::fill(block, block + 36, 0.0);
  const VbdSpringList& s = g.joining;
  for (std::int32_t e = g.pair_offsets[q]; e < g.pair_offsets[q + 1]; ++e) {
    const std::int64_t i = s.v0[e], j = s.v1[e];
    Block spring;
    if (!add_spring(x + 3 * i, p.start + 3 * i, x + 3 * j, p.start + 3 * j, s.rest_length[e],
                    s.ks[e], s.kd[e], p.h, true, spring))
      continue;
    if (!g.turns) {
      add_translation(symmetric(spring.h), -1.0, block);
      continue;
    }
    const double ri[3] = {x[3 * i] - ca[0], x[3 * i + 1] - ca[1], x[3 * i + 2] - ca[2]};
    const double rj[3] = {x[3 * j] - cb[0], x[3 * j + 1] - cb[1], x[3 * j + 2] - cb[2]};
    add_projected(symmetric(spring.h), ri, rj, -1.0, block);
  }
}

}  // namespace

void vbd_coarse_terms(const VbdProblem& p, const double* x, const VbdAggregates& g,
                      const VbdCoarseTerms& out) {
  // One thread sums each aggregate and each pair, in a fixed order: the bits do not depend on
  // the thread count.
#pragma omp parallel if (p.n >= 2048)
  {
#pragma omp for schedule(static)
    for (std::int64_t a = 0; a < g.count; ++a) aggregate_terms(p, x, g, a, out);
#pragma omp for schedule(static)
    for (std::int64_t q = 0; q < g.pair_count; ++q) pair_terms(p, x, g, q, out);
  }
}

}  // namespace drapelab::kernels
