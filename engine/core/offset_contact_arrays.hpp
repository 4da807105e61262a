// Offset self-contacts (self_collision/offset_contacts.hpp) as plain arrays, for the loops built
// without Eigen (vbd's sweeps), and the closest points each contact needs at any state, on plain
// values. Positions are 3 x n packed as in ClothState.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace drapelab {

// What a contact joins: particle 0 and a triangle (1, 2, 3), an edge (1, 2) or a particle (1); or
// edge (0, 1) and edge (2, 3).
enum class SelfContactKind : std::uint8_t { point_face, point_edge, point_point, edge_edge };

struct OffsetContactArrays {
  std::int64_t count = 0;
  // Particle i's contacts: rows offsets[i] to offsets[i + 1] - 1 of (contact, slot) pairs. Null:
  // no self-contact.
  const std::int32_t* offsets = nullptr;
  const std::int32_t* contact = nullptr;
  const std::int32_t* slot = nullptr;
  const SelfContactKind* kind = nullptr;   // per contact
  const std::int32_t* particle = nullptr;  // 4 per contact, -1 unused
  const double* normal_force = nullptr;    // N per contact: friction's lagged load
  double offset = 0.0;                     // m: the gap the energy keeps (r)
  double stiffness = 0.0;                  // N/m (k)
  double damping = 0.0;                    // N*s/m on the rate the gap closes or opens
  double kinetic_friction = 0.0;           // Coulomb coefficients
  double static_friction = 0.0;
  // Per particle: the centre of its conservative bound (m, 3 each) and the bound (m).
  const double* anchor = nullptr;
  const double* bound = nullptr;
};

namespace offset_contact {

inline double dot(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// The barycentric weights (u, v, w) of the point of triangle (a, b, c) closest to p, by the
// Voronoi regions of its corners and edges (Ericson, Real-Time Collision Detection, 5.1.5).
inline void triangle_weights(const double* p, const double* a, const double* b, const double* c,
                             double* out) {
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  const double bp[3] = {p[0] - b[0], p[1] - b[1], p[2] - b[2]};
  const double cp[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
  const double d1 = dot(ab, ap), d2 = dot(ac, ap), d3 = dot(ab, bp), d4 = dot(ac, bp);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  const auto set = [out](double u, double v, double w) {
    out[0] = u;
    out[1] = v;
    out[2] = w;
  };
  if (d1 <= 0.0 && d2 <= 0.0) return set(1.0, 0.0, 0.0);
  if (d3 >= 0.0 && d4 <= d3) return set(0.0, 1.0, 0.0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0) {
    const double t = d1 / (d1 - d3);
    return set(1.0 - t, t, 0.0);
  }
  if (d6 >= 0.0 && d5 <= d6) return set(0.0, 0.0, 1.0);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0) {
    const double t = d2 / (d2 - d6);
    return set(1.0 - t, 0.0, t);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return set(0.0, 1.0 - t, t);
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) return set(1.0, 0.0, 0.0);  // a degenerate triangle: its first corner
  return set(1.0 - (vb + vc) / sum, vb / sum, vc / sum);
}

// The parameter in [0, 1] of the point of segment a-b closest to p.
inline double segment_parameter(const double* p, const double* a, const double* b) {
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  const double length2 = dot(ab, ab);
  return length2 > 0.0 ? std::clamp(dot(ap, ab) / length2, 0.0, 1.0) : 0.0;
}

// The parameters s, t in [0, 1] of the closest points of segments p0-p1 and q0-q1 (Ericson 5.1.9).
inline void segment_pair_parameters(const double* p0, const double* p1, const double* q0,
                                    const double* q1, double& s, double& t) {
  const double d1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double d2[3] = {q1[0] - q0[0], q1[1] - q0[1], q1[2] - q0[2]};
  const double r[3] = {p0[0] - q0[0], p0[1] - q0[1], p0[2] - q0[2]};
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r), c = dot(d1, r);
  s = t = 0.0;
  if (!(a > 0.0) || !(e > 0.0)) {
    if (a > 0.0) s = std::clamp(-c / a, 0.0, 1.0);
    if (e > 0.0) t = std::clamp(f / e, 0.0, 1.0);
    return;
  }
  const double b = dot(d1, d2);
  const double denominator = a * e - b * b;
  s = denominator > 1e-12 * a * e ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
  t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
}

// A contact's weights w (4) at positions p[0..3] of its particles (unused slots may be null): the
// gap vector is sum_s w_s p_s, from the second side's closest point to the first's.
inline void weights(SelfContactKind kind, const double* const* p, double* w) {
  w[0] = 1.0;
  w[1] = w[2] = w[3] = 0.0;
  switch (kind) {
    case SelfContactKind::point_face: {
      double b[3];
      triangle_weights(p[0], p[1], p[2], p[3], b);
      w[1] = -b[0];
      w[2] = -b[1];
      w[3] = -b[2];
      return;
    }
    case SelfContactKind::point_edge: {
      const double t = segment_parameter(p[0], p[1], p[2]);
      w[1] = -(1.0 - t);
      w[2] = -t;
      return;
    }
    case SelfContactKind::point_point:
      w[1] = -1.0;
      return;
    case SelfContactKind::edge_edge: {
      double s = 0.0, t = 0.0;
      segment_pair_parameters(p[0], p[1], p[2], p[3], s, t);
      w[0] = 1.0 - s;
      w[1] = s;
      w[2] = -(1.0 - t);
      w[3] = -t;
      return;
    }
  }
}

// One contact at a state: its weights, its unit normal n (from the second side to the first), its
// gap d (m), and the relative motion of its two sides since the step's start along n (m) and
// across it (m, 3).
struct Geometry {
  double w[4] = {0.0, 0.0, 0.0, 0.0};
  double n[3] = {0.0, 0.0, 0.0};
  double gap = 0.0;
  double normal_move = 0.0;
  double slip[3] = {0.0, 0.0, 0.0};
};

// The geometry of contact c, its particle j at position(j) and at start + 3 j at the step's start.
// False when its gap is at or beyond the offset (no force) or zero (no direction).
template <typename Position>
bool geometry(const OffsetContactArrays& contacts, std::int64_t c, const Position& position,
              const double* start, Geometry& g) {
  const std::int32_t* particle = contacts.particle + 4 * c;
  const double* at[4] = {nullptr, nullptr, nullptr, nullptr};
  for (int s = 0; s < 4; ++s)
    if (particle[s] >= 0) at[s] = position(particle[s]);
  weights(contacts.kind[c], at, g.w);
  double r[3] = {0.0, 0.0, 0.0}, move[3] = {0.0, 0.0, 0.0};
  for (int s = 0; s < 4; ++s) {
    if (particle[s] < 0) continue;
    const double* from = start + 3 * static_cast<std::int64_t>(particle[s]);
    for (int d = 0; d < 3; ++d) {
      r[d] += g.w[s] * at[s][d];
      move[d] += g.w[s] * (at[s][d] - from[d]);
    }
  }
  g.gap = std::sqrt(dot(r, r));
  if (!(g.gap > 0.0) || g.gap >= contacts.offset) return false;
  for (int d = 0; d < 3; ++d) g.n[d] = r[d] / g.gap;
  g.normal_move = dot(move, g.n);
  for (int d = 0; d < 3; ++d) g.slip[d] = move[d] - g.normal_move * g.n[d];
  return true;
}

// Friction on the contact's first side (N, 3) for its slip over a step, with lagged load `load`
// (N) and the smooth stick-slip boundary `slip_scale` (m): a tangential spring of mu_s load /
// slip_scale below it, mu_k load against the slip beyond. `stiffness` (N/m) is the spring's, or
// mu_k load / |slip| when sliding (its Hessian is then that times the tangent plane less the slip
// direction).
struct Friction {
  double force[3] = {0.0, 0.0, 0.0};
  double stiffness = 0.0;
  bool sliding = false;
  double slip_length = 0.0;  // m
};
inline Friction friction(const Geometry& g, double load, double kinetic, double fixed,
                         double slip_scale) {
  Friction out;
  out.slip_length = std::sqrt(dot(g.slip, g.slip));
  if (!(load > 0.0) || !(slip_scale > 0.0)) return out;
  out.sliding = out.slip_length >= slip_scale;
  out.stiffness = out.sliding ? kinetic * load / out.slip_length : fixed * load / slip_scale;
  for (int d = 0; d < 3; ++d) out.force[d] = -out.stiffness * g.slip[d];
  return out;
}

}  // namespace offset_contact

// The contacts' totals at a state x (m) reached from `start` (m) over h (s): the barrier's
// energy, the contacts whose gap is inside the offset, their push and friction, and the power
// their dampers and friction take.
struct OffsetContactTotals {
  std::int64_t pushing = 0;
  double energy = 0.0;            // J
  double normal_force = 0.0;      // N, sum of the pushes
  double friction_force = 0.0;    // N, sum of |friction|
  double dissipated_power = 0.0;  // W, >= 0
  double smallest_gap = 0.0;      // m, the smallest gap of a pushing contact (the offset if none)
};
OffsetContactTotals offset_contact_totals(const OffsetContactArrays& contacts, const double* x,
                                          const double* start, double h, double friction_velocity);

}  // namespace drapelab
