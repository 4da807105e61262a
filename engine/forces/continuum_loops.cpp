// Membrane and hinge elements on plain arrays (continuum_loops.hpp). Notation of
// drapelab/continuum.hpp: F = sum_k x_k g_k^T (3 x 2), Green strain G = (F^T F - I) / 2, second
// Piola-Kirchhoff stress S = 2 mu G + lambda tr(G) I, first P = F S; the force on corner k is
// -A P g_k and the Hessian's block (k, l) is
//   A [ (g_l^T S g_k) I + mu (g_l . g_k) F F^T + mu u_l u_k^T + lambda u_k u_l^T ],  u_k = F g_k,
// whose last three terms form a positive semidefinite whole (they are dG : dS = 2 mu |dG|^2 +
// lambda tr(dG)^2 >= 0) and whose first is semidefinite when S is: the projection clamps S.
#include "forces/continuum_loops.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "forces/continuum_families.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace drapelab::kernels {
namespace {

constexpr double kPi = 3.14159265358979323846;

inline double dot3(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline void cross3(const double* a, const double* b, double* out) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

// The edges x1 - x0 and x2 - x0 of the triangle with corners `corner`.
inline void edges(const double* x, const std::int32_t* corner, double* e1, double* e2) {
  const double* x0 = x + 3 * static_cast<std::int64_t>(corner[0]);
  const double* x1 = x + 3 * static_cast<std::int64_t>(corner[1]);
  const double* x2 = x + 3 * static_cast<std::int64_t>(corner[2]);
  for (int a = 0; a < 3; ++a) {
    e1[a] = x1[a] - x0[a];
    e2[a] = x2[a] - x0[a];
  }
}

// F = e1 g_1^T + e2 g_2^T (column-major 3 x 2): sum_k x_k g_k^T with g_0 = -(g_1 + g_2), from the
// edges so that a translation changes no bit.
inline void deformation(const double* g, const double* e1, const double* e2, double* f) {
  for (int a = 0; a < 3; ++a) {
    f[a] = e1[a] * g[2] + e2[a] * g[4];
    f[3 + a] = e1[a] * g[3] + e2[a] * g[5];
  }
}

// atan2(y, x) in (-pi, pi] without a library call, so that the hinge loop vectorises, and with
// one division: the angle of (|x|, |y|) is that of (max, min) or pi/2 minus it, in [0, pi/4];
// subtracting the nearest of the angles j pi/16 (tan(a - b) = (tan a - tan b) / (1 + tan a tan b),
// one quotient of min and max) leaves an angle within pi/32, whose tangent u <= 0.0985 needs 8
// terms of the odd series atan(u) = u - u^3/3 + u^5/5 - ... for less than 1e-17 relative; then
// the octant and the quadrant. (0, 0) gives 0.
[[gnu::always_inline]] inline double angle_of(double y, double x) {
  const double ax = std::fabs(x), ay = std::fabs(y);
  const double low = std::min(ax, ay), high = std::max(ax, ay);
  // The nearest j pi/16 to atan(low / high): compare with the midpoints' tangents tan((2j+1)
  // pi/32).
  double tangent = 0.0, base = 0.0;  // tan(j pi/16) and j pi/16 (rad)
  tangent = low > 0.09849140335716425 * high ? 0.198912367379658 : tangent;
  base = low > 0.09849140335716425 * high ? 0.19634954084936207 : base;
  tangent = low > 0.3033466836073424 * high ? 0.41421356237309503 : tangent;
  base = low > 0.3033466836073424 * high ? 0.39269908169872414 : base;
  tangent = low > 0.5345111359507916 * high ? 0.6681786379192989 : tangent;
  base = low > 0.5345111359507916 * high ? 0.5890486225480862 : base;
  tangent = low > 0.8206787908286602 * high ? 1.0 : tangent;
  base = low > 0.8206787908286602 * high ? 0.25 * kPi : base;
  const double denominator = high + tangent * low;
  const double u = denominator > 0.0 ? (low - tangent * high) / denominator : 0.0;
  const double z = u * u, z2 = z * z, z4 = z2 * z2;
  // 1 - z/3 + z^2/5 - ... - z^7/15 in Estrin's pairs, so the terms do not wait on each other
  // (the coefficients as constants: a division by 3 is a division, a product by 1/3 is not)
  constexpr double c1 = 1.0 / 3, c2 = 1.0 / 5, c3 = 1.0 / 7, c4 = 1.0 / 9, c5 = 1.0 / 11,
                   c6 = 1.0 / 13, c7 = 1.0 / 15;
  const double series =
      (1.0 - c1 * z) + z2 * (c2 - c3 * z) + z4 * ((c4 - c5 * z) + z2 * (c6 - c7 * z));
  double phi = base + u * series;
  phi = ay > ax ? 0.5 * kPi - phi : phi;
  phi = x < 0.0 ? kPi - phi : phi;
  return y < 0.0 ? -phi : phi;
}

// What one membrane triangle needs at a shape: F (column-major 3 x 2), S and the clamped S.
struct MembraneState {
  double f[6];      // F: column 0 is f[0..2], column 1 is f[3..5]
  double s[3];      // S: 00, 01, 11 (N/m)
  double s_psd[3];  // S with its negative eigenvalues set to zero
  double energy;    // J
  const double* g;  // g_0, g_1, g_2
  double area;      // m^2
};

// The positive semidefinite part of the symmetric 2 x 2 matrix (s00, s01, s11).
void clamp_stress(const double* s, double* out) {
  const double mean = 0.5 * (s[0] + s[2]);
  const double half_gap = 0.5 * (s[0] - s[2]);
  const double radius = std::sqrt(half_gap * half_gap + s[1] * s[1]);
  const double high = mean + radius, low = mean - radius;
  if (low >= 0.0) {
    std::copy(s, s + 3, out);
  } else if (high <= 0.0) {
    out[0] = out[1] = out[2] = 0.0;
  } else {
    // high v v^T with v the unit eigenvector of `high`: (S - low I) / (high - low) = v v^T.
    const double scale = high / (high - low);
    out[0] = scale * (s[0] - low);
    out[1] = scale * s[1];
    out[2] = scale * (s[2] - low);
  }
}

MembraneState membrane_state(const ContinuumArrays& c, std::int64_t t, const double* x) {
  MembraneState m;
  m.g = c.shape_gradient + 6 * t;
  m.area = c.rest_area[t];
  const std::int32_t* corner = c.triangle + 3 * t;
  double e1[3], e2[3];
  edges(x, corner, e1, e2);
  deformation(m.g, e1, e2, m.f);
  const double g00 = 0.5 * (dot3(m.f, m.f) - 1.0);
  const double g01 = 0.5 * dot3(m.f, m.f + 3);
  const double g11 = 0.5 * (dot3(m.f + 3, m.f + 3) - 1.0);
  const double trace = g00 + g11;
  m.s[0] = 2.0 * c.mu * g00 + c.lambda * trace;
  m.s[1] = 2.0 * c.mu * g01;
  m.s[2] = 2.0 * c.mu * g11 + c.lambda * trace;
  m.energy =
      m.area * (c.mu * (g00 * g00 + 2.0 * g01 * g01 + g11 * g11) + 0.5 * c.lambda * trace * trace);
  clamp_stress(m.s, m.s_psd);
  return m;
}

// F y for a 2-vector y.
inline void apply_f(const double* f, const double* y, double* out) {
  for (int a = 0; a < 3; ++a) out[a] = f[a] * y[0] + f[3 + a] * y[1];
}

void membrane_force(const MembraneState& m, double* out) {
  for (int k = 0; k < 3; ++k) {
    const double* g = m.g + 2 * k;
    const double sg[2] = {m.s[0] * g[0] + m.s[1] * g[1], m.s[1] * g[0] + m.s[2] * g[1]};
    double p[3];
    apply_f(m.f, sg, p);  // P g_k = F S g_k
    for (int a = 0; a < 3; ++a) out[3 * k + a] = -m.area * p[a];
  }
}

// Block (k, l) of the membrane Hessian (9 entries, row-major) with stress `stress` in the geometric
// term.
void membrane_block(const ContinuumArrays& c, const MembraneState& m, const double* stress, int k,
                    int l, double* out) {
  const double* gk = m.g + 2 * k;
  const double* gl = m.g + 2 * l;
  const double geometric = gl[0] * (stress[0] * gk[0] + stress[1] * gk[1]) +
                           gl[1] * (stress[1] * gk[0] + stress[2] * gk[1]);
  const double gg = gk[0] * gl[0] + gk[1] * gl[1];
  double uk[3], ul[3];
  apply_f(m.f, gk, uk);
  apply_f(m.f, gl, ul);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const double fft = m.f[a] * m.f[b] + m.f[3 + a] * m.f[3 + b];
      out[3 * a + b] = m.area * ((a == b ? geometric : 0.0) + c.mu * gg * fft +
                                 c.mu * ul[a] * uk[b] + c.lambda * uk[a] * ul[b]);
    }
}

// The hinge at x: angle, and the gradient of the angle (12: a, b, c, d).
struct HingeState {
  double angle;
  double grad[12];
};

HingeState hinge_state(const ContinuumArrays& c, std::int64_t e, const double* x) {
  const std::int32_t* v = c.hinge + 4 * e;
  const double* xa = x + 3 * static_cast<std::int64_t>(v[0]);
  const double* xb = x + 3 * static_cast<std::int64_t>(v[1]);
  const double* xc = x + 3 * static_cast<std::int64_t>(v[2]);
  const double* xd = x + 3 * static_cast<std::int64_t>(v[3]);
  const double edge[3] = {xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]};
  const double to_c[3] = {xc[0] - xa[0], xc[1] - xa[1], xc[2] - xa[2]};
  const double to_d[3] = {xd[0] - xa[0], xd[1] - xa[1], xd[2] - xa[2]};
  // n1 = e x (c - a), the first triangle's normal; n2 = (d - a) x e, the second's (a, b, c) and
  // (b, a, d) both counter-clockwise.
  double n1[3], n2[3];
  cross3(edge, to_c, n1);
  cross3(to_d, edge, n2);
  const double length2 = dot3(edge, edge);
  const double length = std::sqrt(length2);
  const double n1_2 = dot3(n1, n1), n2_2 = dot3(n2, n2);
  HingeState s;
  if (!(length > 0.0 && n1_2 > 0.0 && n2_2 > 0.0)) {  // a collapsed triangle: no direction
    s.angle = 0.0;
    std::fill(s.grad, s.grad + 12, 0.0);
    return s;
  }
  double n1xn2[3];
  cross3(n1, n2, n1xn2);
  const double sine = dot3(n1xn2, edge) / length;  // |n1||n2| sin(theta)
  const double cosine = dot3(n1, n2);              // |n1||n2| cos(theta)
  s.angle = angle_of(sine, cosine);
  // d theta / d x_c = -|e| n1 / |n1|^2 and d theta / d x_d = -|e| n2 / |n2|^2 (each opposite
  // corner moves along its normal by its height times the angle); the edge's ends share the rest
  // by where the opposite corners project on the edge.
  const double tc = dot3(to_c, edge) / length2, td = dot3(to_d, edge) / length2;
  for (int a = 0; a < 3; ++a) {
    const double gc = -length * n1[a] / n1_2;
    const double gd = -length * n2[a] / n2_2;
    s.grad[6 + a] = gc;
    s.grad[9 + a] = gd;
    s.grad[a] = -(1.0 - tc) * gc - (1.0 - td) * gd;
    s.grad[3 + a] = -tc * gc - td * gd;
  }
  return s;
}

}  // namespace

double membrane_element(const ContinuumArrays& c, std::int64_t t, const double* x, bool exact,
                        double* force, double* hessian, double* material_hessian) {
  const MembraneState m = membrane_state(c, t, x);
  if (force) membrane_force(m, force);
  const double no_stress[3] = {0.0, 0.0, 0.0};
  for (double* out : {hessian, material_hessian}) {
    if (!out) continue;
    const double* stress = out == material_hessian ? no_stress : exact ? m.s : m.s_psd;
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) {
        double block[9];
        membrane_block(c, m, stress, k, l, block);
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) out[9 * (3 * k + a) + 3 * l + b] = block[3 * a + b];
      }
  }
  return m.energy;
}

double hinge_element(const ContinuumArrays& c, std::int64_t e, const double* x, double* angle,
                     double* force, double* hessian) {
  const HingeState s = hinge_state(c, e, x);
  const double k = c.hinge_stiffness[e];
  const double bend = s.angle - c.rest_angle[e];
  if (angle) *angle = s.angle;
  if (force)
    for (int r = 0; r < 12; ++r) force[r] = -2.0 * k * bend * s.grad[r];
  if (hessian)
    for (int r = 0; r < 12; ++r)
      for (int q = 0; q < 12; ++q) hessian[12 * r + q] = 2.0 * k * s.grad[r] * s.grad[q];
  return k * bend * bend;
}

double continuum_damping_power(const ContinuumArrays& c, const double* x, const double* v) {
  if (!(c.alpha > 0.0)) return 0.0;
  double power = 0.0;  // W
  for (std::int64_t t = 0; t < c.triangles; ++t) {
    const MembraneState m = membrane_state(c, t, x);
    double w1[3], w2[3], fdot[6];
    edges(v, c.triangle + 3 * t, w1, w2);
    deformation(m.g, w1, w2, fdot);
    // dG/dt = sym(F^T dF/dt); the damping stress alpha C : dG/dt takes A alpha dG/dt : C : dG/dt.
    const double d00 = dot3(m.f, fdot), d11 = dot3(m.f + 3, fdot + 3);
    const double d01 = 0.5 * (dot3(m.f, fdot + 3) + dot3(m.f + 3, fdot));
    const double trace = d00 + d11;
    power += m.area * c.alpha *
             (2.0 * c.mu * (d00 * d00 + 2.0 * d01 * d01 + d11 * d11) + c.lambda * trace * trace);
  }
  for (std::int64_t e = 0; e < c.hinges; ++e) {
    const HingeState s = hinge_state(c, e, x);
    double rate = 0.0;  // rad/s
    for (int k = 0; k < 4; ++k)
      for (int a = 0; a < 3; ++a)
        rate += s.grad[3 * k + a] * v[3 * static_cast<std::int64_t>(c.hinge[4 * e + k]) + a];
    power += 2.0 * c.hinge_stiffness[e] * c.alpha * rate * rate;
  }
  return power;
}

double continuum_energy_sum(const ContinuumArrays& c, const double* x, double* membrane,
                            double* bending) {
  double m = 0.0, b = 0.0;
  for (std::int64_t t = 0; t < c.triangles; ++t)
    m += membrane_element(c, t, x, false, nullptr, nullptr, nullptr);
  for (std::int64_t e = 0; e < c.hinges; ++e)
    b += hinge_element(c, e, x, nullptr, nullptr, nullptr);
  if (membrane) *membrane = m;
  if (bending) *bending = b;
  return m + b;
}

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

void continuum_particle_terms(const ContinuumArrays& c, std::int64_t i, const double* x,
                              const double* start, double h, double* f, double* block) {
  const double damping = c.alpha / h;           // the dissipation's weight on the Hessian (1)
  const double no_stress[3] = {0.0, 0.0, 0.0};  // the damping acts on the material term alone
  for (std::int32_t r = c.triangle_offsets[i]; r < c.triangle_offsets[i + 1]; ++r) {
    const std::int64_t t = c.triangle_of[r];
    const int k = c.triangle_slot[r];
    const MembraneState m = membrane_state(c, t, x);
    const double* g = m.g + 2 * k;
    // The elastic force on corner k, -A F S g_k, and the damping's -alpha/h A F dS g_k for the
    // step's move dF = sum_l w_l g_l^T (dS = C : sym(F^T dF))
    const double sg[2] = {m.s[0] * g[0] + m.s[1] * g[1], m.s[1] * g[0] + m.s[2] * g[1]};
    double pull[3];
    apply_f(m.f, sg, pull);
    for (int a = 0; a < 3; ++a) f[a] -= m.area * pull[a];
    if (damping > 0.0) {
      const std::int32_t* corner = c.triangle + 3 * t;
      double df[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
      for (int q = 0; q < 3; ++q)
        for (int a = 0; a < 3; ++a) {
          const std::int64_t at = 3 * static_cast<std::int64_t>(corner[q]) + a;
          const double w = x[at] - start[at];
          df[a] += w * m.g[2 * q];
          df[3 + a] += w * m.g[2 * q + 1];
        }
      const double dg00 = dot3(m.f, df), dg11 = dot3(m.f + 3, df + 3);
      const double dg01 = 0.5 * (dot3(m.f, df + 3) + dot3(m.f + 3, df));
      const double trace = dg00 + dg11;
      const double ds[3] = {2.0 * c.mu * dg00 + c.lambda * trace, 2.0 * c.mu * dg01,
                            2.0 * c.mu * dg11 + c.lambda * trace};
      const double dsg[2] = {ds[0] * g[0] + ds[1] * g[1], ds[1] * g[0] + ds[2] * g[1]};
      double resist[3];
      apply_f(m.f, dsg, resist);
      for (int a = 0; a < 3; ++a) f[a] -= damping * m.area * resist[a];
    }
    // The block's material part, and the clamped stress's geometric part on its diagonal
    double material[9];
    membrane_block(c, m, no_stress, k, k, material);
    const double geometric = m.area * (g[0] * (m.s_psd[0] * g[0] + m.s_psd[1] * g[1]) +
                                       g[1] * (m.s_psd[1] * g[0] + m.s_psd[2] * g[1]));
    const int entry[6] = {0, 4, 8, 1, 2, 5};  // xx, yy, zz, xy, xz, yz of a row-major 3 x 3
    for (int q = 0; q < 6; ++q)
      block[q] += (1.0 + damping) * material[entry[q]] + (q < 3 ? geometric : 0.0);
  }
  for (std::int32_t r = c.hinge_offsets[i]; r < c.hinge_offsets[i + 1]; ++r) {
    const std::int64_t e = c.hinge_of[r];
    const int k = c.hinge_slot[r];
    const HingeState s = hinge_state(c, e, x);
    const double stiffness = c.hinge_stiffness[e];
    double turn = 0.0;  // rad: grad(theta) . (x - start) over the hinge's corners
    if (damping > 0.0) {
      const std::int32_t* corner = c.hinge + 4 * e;
      for (int q = 0; q < 4; ++q) {
        const std::int64_t at = 3 * static_cast<std::int64_t>(corner[q]);
        const double dx[3] = {x[at] - start[at], x[at + 1] - start[at + 1],
                              x[at + 2] - start[at + 2]};
        turn += dot3(s.grad + 3 * q, dx);
      }
    }
    const double* g = s.grad + 3 * k;
    const double scale = -2.0 * stiffness * (s.angle - c.rest_angle[e] + damping * turn);
    for (int a = 0; a < 3; ++a) f[a] += scale * g[a];
    const double weight = 2.0 * stiffness * (1.0 + damping);
    block[0] += weight * g[0] * g[0];
    block[1] += weight * g[1] * g[1];
    block[2] += weight * g[2] * g[2];
    block[3] += weight * g[0] * g[1];
    block[4] += weight * g[0] * g[2];
    block[5] += weight * g[1] * g[2];
  }
}

}  // namespace drapelab::kernels
