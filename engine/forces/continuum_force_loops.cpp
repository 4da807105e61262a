// The continuum's force loop (continuum_loops.hpp): every membrane triangle's and hinge's force at
// once, vectorised, either through the index lists or by dense families (continuum_families.hpp),
// and summed per particle in a fixed order so the result does not depend on the number of threads.
#include <algorithm>
#include <utility>
#include <vector>

#include "forces/continuum_element_math.hpp"
#include "forces/continuum_families.hpp"
#include "forces/continuum_loops.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace drapelab::kernels {
namespace {

// One membrane triangle from its edges e1 = x1 - x0, e2 = x2 - x0 (m) and their rates w1, w2
// (m/s): its normal e1 x e2 (m^2) and the forces on its corners (N). The second Piola-Kirchhoff
// stress of the strain plus alpha times its rate, S = C : (G + alpha dG/dt), gives the elastic
// force and the Kelvin-Voigt damping -alpha H_m v in one product P = F S; corner k's force is -A P
// g_k. Plain scalars, no calls, no branches, so that the loops calling it vectorise.
[[gnu::always_inline]] inline void membrane_slot(const double* e1, const double* e2,
                                                 const double* w1, const double* w2, double g1x,
                                                 double g1y, double g2x, double g2y, double area,
                                                 double mu, double lambda, double alpha,
                                                 double* normal, double* force0, double* force1,
                                                 double* force2) {
  cross3(e1, e2, normal);
  double f[6], fdot[6];  // F and dF/dt, column-major
  for (int a = 0; a < 3; ++a) {
    f[a] = e1[a] * g1x + e2[a] * g2x;
    f[3 + a] = e1[a] * g1y + e2[a] * g2y;
    fdot[a] = w1[a] * g1x + w2[a] * g2x;
    fdot[3 + a] = w1[a] * g1y + w2[a] * g2y;
  }
  // G + alpha dG/dt, with dG/dt = sym(F^T dF/dt)
  const double q00 = 0.5 * (dot3(f, f) - 1.0) + alpha * dot3(f, fdot);
  const double q11 = 0.5 * (dot3(f + 3, f + 3) - 1.0) + alpha * dot3(f + 3, fdot + 3);
  const double q01 = 0.5 * (dot3(f, f + 3) + alpha * (dot3(f, fdot + 3) + dot3(f + 3, fdot)));
  const double trace = q00 + q11;
  const double s00 = 2.0 * mu * q00 + lambda * trace, s01 = 2.0 * mu * q01;
  const double s11 = 2.0 * mu * q11 + lambda * trace;
  for (int a = 0; a < 3; ++a) {
    const double p0 = -area * (f[a] * s00 + f[3 + a] * s01);  // -A P, column 0 (N)
    const double p1 = -area * (f[a] * s01 + f[3 + a] * s11);
    force1[a] = p0 * g1x + p1 * g1y;
    force2[a] = p0 * g2x + p1 * g2y;
    force0[a] = -(force1[a] + force2[a]);
  }
}

// One hinge from its triangles' normals n1 = (b - a) x (c - a), n2 = (d - a) x (b - a), its
// corners' positions and velocities (3 each, in the order a, b, c, d): the forces on its corners
// (N, 3 each), elastic -2 k (theta - theta_0) grad(theta) plus the damping
// -2 k alpha grad(theta) (grad(theta) . v). grad(theta) is -|e| n1 / |n1|^2 at c and
// -|e| n2 / |n2|^2 at d (each opposite corner turns the hinge by its move along its normal over its
// height), and the edge's ends share minus their sum by where c and d project on the edge.
[[gnu::always_inline]] inline void hinge_slot(const double* n1, const double* n2, const double* x,
                                              const double* v, double stiffness, double rest,
                                              double alpha, double* force) {
  const double* xa = x;
  double edge[3], to_c[3], to_d[3];
  for (int a = 0; a < 3; ++a) {
    edge[a] = x[3 + a] - xa[a];
    to_c[a] = x[6 + a] - xa[a];
    to_d[a] = x[9 + a] - xa[a];
  }
  const double length2 = dot3(edge, edge);
  const double length = std::sqrt(length2);
  const double n1_2 = dot3(n1, n1), n2_2 = dot3(n2, n2);
  // A collapsed triangle or edge has no direction: no force.
  const bool sound = length > 0.0 && n1_2 > 0.0 && n2_2 > 0.0;
  // Two divisions for the hinge: 1 / |e|^2 and 1 / (|n1|^2 |n2|^2).
  const double inverse_length2 = sound ? 1.0 / length2 : 0.0;
  const double inverse_normals = sound ? 1.0 / (n1_2 * n2_2) : 0.0;
  double n1xn2[3];
  cross3(n1, n2, n1xn2);
  const double sine = dot3(n1xn2, edge) * length * inverse_length2;  // |n1||n2| sin(theta)
  const double angle = angle_of(sine, dot3(n1, n2));
  const double tc = dot3(to_c, edge) * inverse_length2, td = dot3(to_d, edge) * inverse_length2;
  const double scale_c = -length * n2_2 * inverse_normals;  // -|e| / |n1|^2
  const double scale_d = -length * n1_2 * inverse_normals;  // -|e| / |n2|^2
  double grad[12];
  for (int a = 0; a < 3; ++a) {
    const double gc = scale_c * n1[a], gd = scale_d * n2[a];
    grad[a] = (tc - 1.0) * gc + (td - 1.0) * gd;
    grad[3 + a] = -tc * gc - td * gd;
    grad[6 + a] = gc;
    grad[9 + a] = gd;
  }
  double rate = 0.0;  // d theta / dt (rad/s)
  for (int r = 0; r < 12; ++r) rate += grad[r] * v[r];
  const double moment = sound ? -2.0 * stiffness * (angle - rest + alpha * rate) : 0.0;
  for (int r = 0; r < 12; ++r) force[r] = moment * grad[r];
}

// The indexed loop's scratch: the state as unit-stride columns, then per triangle its normal and
// its corners' forces, then per hinge its corners' forces, column by column.
struct ForceColumns {
  ForceColumns(const ContinuumArrays& c, double* scratch) {
    const std::int64_t n = c.particles, t = c.triangles, h = c.hinges;
    for (int k = 0; k < 3; ++k) {
      x[k] = scratch + k * n;
      v[k] = scratch + (3 + k) * n;
    }
    double* triangles = scratch + 6 * n;
    for (int k = 0; k < 3; ++k) normal[k] = triangles + k * t;
    for (int k = 0; k < 9; ++k) triangle_force[k] = triangles + (3 + k) * t;
    double* hinges = triangles + 12 * t;
    for (int k = 0; k < 12; ++k) hinge_force[k] = hinges + k * h;
  }
  double* x[3];
  double* v[3];
  double* normal[3];          // (x1 - x0) x (x2 - x0), m^2
  double* triangle_force[9];  // N: corner k's component a in column 3 k + a
  double* hinge_force[12];    // N: likewise for a, b, c, d
};

// Triangle t through the index lists (the arrays come by value so that the compiler sees their
// pointers cannot change inside the loop, and vectorises it with gathers).
[[gnu::always_inline]] inline void triangle_columns(const ContinuumArrays c, const ForceColumns s,
                                                    std::int64_t t) {
  const std::int32_t i0 = c.triangle_corner[0][t], i1 = c.triangle_corner[1][t],
                     i2 = c.triangle_corner[2][t];
  double e1[3], e2[3], w1[3], w2[3], normal[3], f[9];
  for (int a = 0; a < 3; ++a) {
    e1[a] = s.x[a][i1] - s.x[a][i0];
    e2[a] = s.x[a][i2] - s.x[a][i0];
    w1[a] = s.v[a][i1] - s.v[a][i0];
    w2[a] = s.v[a][i2] - s.v[a][i0];
  }
  membrane_slot(e1, e2, w1, w2, c.gradient[0][t], c.gradient[1][t], c.gradient[2][t],
                c.gradient[3][t], c.rest_area[t], c.mu, c.lambda, c.alpha, normal, f, f + 3, f + 6);
  for (int a = 0; a < 3; ++a) s.normal[a][t] = normal[a];
  for (int r = 0; r < 9; ++r) s.triangle_force[r][t] = f[r];
}

// Hinge e through the index lists, from its triangles' normals (triangle_columns).
[[gnu::always_inline]] inline void hinge_columns(const ContinuumArrays c, const ForceColumns s,
                                                 std::int64_t e) {
  const std::int32_t t1 = c.hinge_wing[0][e], t2 = c.hinge_wing[1][e];
  const double sign = c.hinge_second_sign[e];
  double n1[3], n2[3], x[12], v[12], f[12];
  for (int a = 0; a < 3; ++a) {
    n1[a] = s.normal[a][t1];
    n2[a] = sign * s.normal[a][t2];
  }
  for (int k = 0; k < 4; ++k) {
    const std::int32_t i = c.hinge_corner[k][e];
    for (int a = 0; a < 3; ++a) {
      x[3 * k + a] = s.x[a][i];
      v[3 * k + a] = s.v[a][i];
    }
  }
  hinge_slot(n1, n2, x, v, c.hinge_stiffness[e], c.rest_angle[e], c.alpha, f);
  for (int r = 0; r < 12; ++r) s.hinge_force[r][e] = f[r];
}

void split_state(std::int64_t n, const double* x, const double* v, double* const* xs,
                 double* const* vs) {
#pragma omp for simd schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      xs[a][i] = x[3 * i + a];
      vs[a][i] = v[3 * i + a];
    }
}

// Every element through the index lists; called inside a parallel region.
void indexed_forces(const ContinuumArrays& c, const double* x, const double* v, double* scratch,
                    double* force) {
  const ForceColumns s(c, scratch);
  split_state(c.particles, x, v, s.x, s.v);
#pragma omp for simd schedule(static)
  for (std::int64_t t = 0; t < c.triangles; ++t) triangle_columns(c, s, t);
#pragma omp for simd schedule(static)
  for (std::int64_t e = 0; e < c.hinges; ++e) hinge_columns(c, s, e);
    // Each particle sums its elements' shares in the order of its rows.
#pragma omp for schedule(static)
  for (std::int64_t i = 0; i < c.particles; ++i) {
    double sum[3] = {0.0, 0.0, 0.0};
    for (std::int32_t r = c.triangle_offsets[i]; r < c.triangle_offsets[i + 1]; ++r) {
      const std::int32_t t = c.triangle_of[r], k = c.triangle_slot[r];
      for (int a = 0; a < 3; ++a) sum[a] += s.triangle_force[3 * k + a][t];
    }
    for (std::int32_t r = c.hinge_offsets[i]; r < c.hinge_offsets[i + 1]; ++r) {
      const std::int32_t e = c.hinge_of[r], k = c.hinge_slot[r];
      for (int a = 0; a < 3; ++a) sum[a] += s.hinge_force[3 * k + a][e];
    }
    for (int a = 0; a < 3; ++a) force[3 * i + a] += sum[a];
  }
}

// The family loop's scratch (continuum_families.hpp): columns of particles + 2 padding each; the
// state's values sit at [0, particles), the families' slot s at padding + s, and the padding on
// either side is never written, so it reads as zeros. The elements add their corners' forces
// straight into the particles' sums, one set of sums per corner number k (0..3): within a family
// two slots never share a particle at the same corner number, so the lanes of a vector never add
// to one sum, which they could do through different corners (a and b of a hinge are neighbours).
struct FamilyColumns {
  FamilyColumns(const ContinuumFamilies& f, double* scratch) : span(f.span()) {
    for (int k = 0; k < 3; ++k) {
      x[k] = scratch + k * span;
      v[k] = scratch + (3 + k) * span;
    }
    for (int q = 0; q < 12; ++q) sum[q] = scratch + (6 + q) * span + f.padding;
    normals = scratch + 18 * span;
  }
  // Component a of the normals of triangle family f (m^2), which the hinges read later.
  double* normal_column(std::int64_t family, int a) const {
    return normals + (3 * family + a) * span;
  }
  std::int64_t span;
  double* x[3];
  double* v[3];
  double* sum[12];  // N: corner number k's component a in sum[3 k + a], indexed by particle
  double* normals;
};

// The arrays a family's loop reads and writes, as plain pointers (passed by value so that the
// compiler sees nothing in the loop can move them; and the loops' bodies are functions, since GCC
// does not vectorise a simd loop that declares arrays in its own body).
struct FamilyPass {
  std::int64_t o[4];
  const double *px, *py, *pz, *vx, *vy, *vz;
  const double* in[5];  // triangles: g_1x, g_1y, g_2x, g_2y, area; hinges: stiffness, rest angle
  const double* n1[3];  // hinges: their triangles' normals, shifted to the hinge's slot
  const double* n2[3];
  double sign, mu, lambda, alpha;
  double* out[3];   // triangles: their normals
  double* sum[12];  // the sums of corner number k's forces, component a in 3 k + a (N)
};

[[gnu::always_inline]] inline void triangle_family_slot(const FamilyPass p, std::int64_t i) {
  const std::int64_t i0 = i + p.o[0], i1 = i + p.o[1], i2 = i + p.o[2];
  const double e1[3] = {p.px[i1] - p.px[i0], p.py[i1] - p.py[i0], p.pz[i1] - p.pz[i0]};
  const double e2[3] = {p.px[i2] - p.px[i0], p.py[i2] - p.py[i0], p.pz[i2] - p.pz[i0]};
  const double w1[3] = {p.vx[i1] - p.vx[i0], p.vy[i1] - p.vy[i0], p.vz[i1] - p.vz[i0]};
  const double w2[3] = {p.vx[i2] - p.vx[i0], p.vy[i2] - p.vy[i0], p.vz[i2] - p.vz[i0]};
  double normal[3], forces[9];
  membrane_slot(e1, e2, w1, w2, p.in[0][i], p.in[1][i], p.in[2][i], p.in[3][i], p.in[4][i], p.mu,
                p.lambda, p.alpha, normal, forces, forces + 3, forces + 6);
  for (int a = 0; a < 3; ++a) p.out[a][i] = normal[a];
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) p.sum[3 * k + a][i + p.o[k]] += forces[3 * k + a];
}

[[gnu::always_inline]] inline void hinge_family_slot(const FamilyPass p, std::int64_t i) {
  const double m1[3] = {p.n1[0][i], p.n1[1][i], p.n1[2][i]};
  const double m2[3] = {p.sign * p.n2[0][i], p.sign * p.n2[1][i], p.sign * p.n2[2][i]};
  double corners[12], rates[12], forces[12];
  for (int k = 0; k < 4; ++k) {
    const std::int64_t at = i + p.o[k];
    corners[3 * k] = p.px[at];
    corners[3 * k + 1] = p.py[at];
    corners[3 * k + 2] = p.pz[at];
    rates[3 * k] = p.vx[at];
    rates[3 * k + 1] = p.vy[at];
    rates[3 * k + 2] = p.vz[at];
  }
  hinge_slot(m1, m2, corners, rates, p.in[0][i], p.in[1][i], p.alpha, forces);
  for (int k = 0; k < 4; ++k)
    for (int a = 0; a < 3; ++a) p.sum[3 * k + a][i + p.o[k]] += forces[3 * k + a];
}

// This thread's block of [0, n) in a parallel region (all of it outside one): n split evenly in
// thread order.
std::pair<std::int64_t, std::int64_t> own_block(std::int64_t n) {
#ifdef _OPENMP
  const std::int64_t threads = omp_get_num_threads(), me = omp_get_thread_num();
#else
  const std::int64_t threads = 1, me = 0;
#endif
  return {n * me / threads, n * (me + 1) / threads};
}

// Calls slot(p, i) for every slot of a family's runs ([begin, end) pairs), the runs split among
// the threads, each run in vector lanes.
template <typename Slot>
[[gnu::always_inline]] inline void over_runs(const std::vector<std::int64_t>& runs,
                                             const FamilyPass p, Slot slot) {
#pragma omp for schedule(static) nowait
  for (std::size_t r = 0; r < runs.size(); r += 2) {
#pragma omp simd
    for (std::int64_t i = runs[r]; i < runs[r + 1]; ++i) slot(p, i);
  }
}

// Every element by families; called inside a parallel region. A family's loop splits its runs
// among the threads and adds into the sums of its corners' particles; a barrier after each family
// keeps each sum's additions in family order on any number of threads, and each thread then adds
// its own block of particles' sums, corner number by corner number: the same bits on any number of
// threads.
void family_forces(const ContinuumArrays& c, const ContinuumFamilies& fam, const double* x,
                   const double* v, double* scratch, double* force) {
  const FamilyColumns s(fam, scratch);
  const std::int64_t n = fam.particles, pad = fam.padding;
  split_state(n, x, v, s.x, s.v);
  const std::pair<std::int64_t, std::int64_t> mine = own_block(n);
  for (double* column : s.sum) std::fill(column + mine.first, column + mine.second, 0.0);
#pragma omp barrier
  FamilyPass p{};
  p.px = s.x[0], p.py = s.x[1], p.pz = s.x[2];
  p.vx = s.v[0], p.vy = s.v[1], p.vz = s.v[2];
  p.mu = c.mu, p.lambda = c.lambda, p.alpha = c.alpha;
  std::copy(s.sum, s.sum + 12, p.sum);
  for (std::size_t f = 0; f < fam.triangles.size(); ++f) {
    const TriangleFamily& tf = fam.triangles[f];
    for (int k = 0; k < 3; ++k) p.o[k] = tf.offset[static_cast<std::size_t>(k)];
    p.o[3] = 0;
    const double* in[5] = {tf.g1x.data(), tf.g1y.data(), tf.g2x.data(), tf.g2y.data(),
                           tf.area.data()};
    std::copy(in, in + 5, p.in);
    for (int a = 0; a < 3; ++a) p.out[a] = s.normal_column(static_cast<std::int64_t>(f), a) + pad;
    over_runs(tf.runs, p, [](const FamilyPass q, std::int64_t i) { triangle_family_slot(q, i); });
#pragma omp barrier
  }
  for (std::size_t f = 0; f < fam.hinges.size(); ++f) {
    const HingeFamily& hf = fam.hinges[f];
    for (int k = 0; k < 4; ++k) p.o[k] = hf.offset[static_cast<std::size_t>(k)];
    for (int a = 0; a < 3; ++a) {
      p.n1[a] = s.normal_column(hf.wing_family[0], a) + pad + hf.wing_shift[0];
      p.n2[a] = s.normal_column(hf.wing_family[1], a) + pad + hf.wing_shift[1];
    }
    p.sign = hf.second_sign;
    p.in[0] = hf.stiffness.data();
    p.in[1] = hf.rest_angle.data();
    over_runs(hf.runs, p, [](const FamilyPass q, std::int64_t i) { hinge_family_slot(q, i); });
#pragma omp barrier
  }
  const FamilyPass sums = p;  // by value, so that the compiler sees the pointers stay put
#pragma omp simd simdlen(4)   // twice as fast as AVX-512 lanes on the interleaved force
  for (std::int64_t i = mine.first; i < mine.second; ++i)
    for (int a = 0; a < 3; ++a)
      force[3 * i + a] +=
          ((sums.sum[a][i] + sums.sum[3 + a][i]) + sums.sum[6 + a][i]) + sums.sum[9 + a][i];
}

}  // namespace

void add_continuum_forces(const ContinuumArrays& c, const double* x, const double* v,
                          double* scratch, double* force) {
  // A second thread made the family loop slower up to 129 x 129 (33 against 41 ns per particle
  // at 65 x 65: it shares the caches, and each family ends at a barrier) and broke even at
  // 257 x 257 (44 against 44), docs/performance.md.
  const bool parallel = c.particles >= (c.families ? 32768 : 2048);
#pragma omp parallel if (parallel)
  {
    if (c.families)
      family_forces(c, *c.families, x, v, scratch, force);
    else
      indexed_forces(c, x, v, scratch, force);
  }
}

}  // namespace drapelab::kernels
