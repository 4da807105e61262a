// One membrane triangle or hinge at a time on plain arrays (continuum_loops.hpp): each element's
// energy, force and Hessian, the damping's power, the elastic energy, and vertex block descent's
// per-particle terms. Notation of drapelab/continuum.hpp: F = sum_k x_k g_k^T (3 x 2), Green
// strain G = (F^T F - I) / 2, second Piola-Kirchhoff stress S = 2 mu G + lambda tr(G) I, first
// P = F S; the force on corner k is -A P g_k and the Hessian's block (k, l) is
//   A [ (g_l^T S g_k) I + mu (g_l . g_k) F F^T + mu u_l u_k^T + lambda u_k u_l^T ],  u_k = F g_k,
// whose last three terms form a positive semidefinite whole (they are dG : dS = 2 mu |dG|^2 +
// lambda tr(dG)^2 >= 0) and whose first is semidefinite when S is: the projection clamps S.
#include <algorithm>
#include <cmath>

#include "forces/continuum_element_math.hpp"
#include "forces/continuum_loops.hpp"

namespace drapelab::kernels {
namespace {

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
