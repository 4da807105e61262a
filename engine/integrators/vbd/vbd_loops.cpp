// One sweep of vertex block descent over plain arrays (vbd_loops.hpp). Per particle i, the force
// f = -dG/dx_i and the block H = d2G/dx_i2 of the variational form are summed term by term, and
// x_i moves by H^-1 f. Every term's block is positive semidefinite (the springs' transverse term
// is dropped when compressed, as a Newton step needs), and the inertia m / h^2 I makes H positive
// definite, so each move lowers G.
#include "integrators/vbd/vbd_loops.hpp"

#include <algorithm>
#include <cmath>

#include "integrators/vbd/vbd_block.hpp"

namespace drapelab::kernels {
namespace {

void add_springs(const VbdProblem& p, std::int64_t i, const double* x, Block& b) {
  const VbdSprings& s = p.springs;
  for (std::int32_t e = s.offsets[i]; e < s.offsets[i + 1]; ++e) {
    const std::int64_t j = s.other[e];
    add_spring(x + 3 * i, p.start + 3 * i, x + 3 * j, p.start + 3 * j, s.rest_length[e], s.ks[e],
               s.kd[e], p.h, true, b);
  }
}

// Collider contact planes: E = k depth^2 / 2 with depth = radius - (x - p) . n, the damper
// c closing^2 / (2 h) (contact_closing), and friction under the load lagged at the step's start.
void add_planes(const VbdProblem& p, std::int64_t i, const double* xi, const double* move_i,
                Block& b) {
  const VbdPlanes& q = p.planes;
  const double slip_scale = p.friction_velocity * p.h;  // m: the stick-slip boundary of a step
  for (int k = 0; k < q.count[i]; ++k) {
    const std::int64_t e = i * q.slots + k;
    const double* n = q.normal + 3 * e;
    const double* point = q.point + 3 * e;
    const double* surface = q.surface_move + 3 * e;
    const double rel[3] = {move_i[0] - surface[0], move_i[1] - surface[1], move_i[2] - surface[2]};
    // Friction wherever the plane bore a load at the step's start: a fixed energy of the step.
    if (q.load[e] > 0.0)
      add_friction(q.load[e], n, rel, q.kinetic[e], q.fixed[e], slip_scale, 1.0, b);
    const double offset[3] = {xi[0] - point[0], xi[1] - point[1], xi[2] - point[2]};
    const double depth = q.radius - dot(offset, n);  // m
    if (depth <= 0.0) continue;
    const double fn =
        q.stiffness * depth + q.damping * contact_closing(depth, dot(rel, n)) / p.h;  // N
    if (fn <= 0.0) continue;
    b.add_force(fn, n);
    b.add_outer(q.stiffness + q.damping / p.h, n);
  }
}

// A soft distance constraint between two particles (a seam's stitch, a string between cloth
// points) as the damped spring it is, at the current positions: force k (L - l) - c rate along the
// ends' direction u, and the spring's stiffness matrix k [u u^T + max(0, 1 - L/l) (I - u u^T)] plus
// c/h u u^T. Linearised along its direction at the step's start, a short stitch would pull only
// along that direction, which is noise near zero length: the sideways gap would stay, and the
// sweeps would push the pair along a stale direction. w is particle i's weight (+1 at the first
// end, -1 at the other); L is the length at the step's start, depth + the ends' distance there.
void add_particle_spring(const VbdProblem& p, std::int64_t contact, double w, std::int64_t i,
                         const double* xi, const double* x, Block& b) {
  const VbdCouplings& c = p.couplings;
  const std::int64_t ja = c.particle[4 * contact], jb = c.particle[4 * contact + 1];
  const double* xa = contact_partner(p, i, xi, x, ja);
  const double* xb = contact_partner(p, i, xi, x, jb);
  const double* sa = p.start + 3 * ja;
  const double* sb = p.start + 3 * jb;
  const double start_gap[3] = {sa[0] - sb[0], sa[1] - sb[1], sa[2] - sb[2]};
  const double length = c.depth[contact] + std::sqrt(dot(start_gap, start_gap));  // m
  const double d[3] = {xa[0] - xb[0], xa[1] - xb[1], xa[2] - xb[2]};
  const double l = std::sqrt(dot(d, d));  // m
  double u[3] = {c.normal[3 * contact], c.normal[3 * contact + 1], c.normal[3 * contact + 2]};
  if (l > 1e-12)
    for (int k = 0; k < 3; ++k) u[k] = d[k] / l;
  const double move[3] = {(xa[0] - sa[0]) - (xb[0] - sb[0]), (xa[1] - sa[1]) - (xb[1] - sb[1]),
                          (xa[2] - sa[2]) - (xb[2] - sb[2])};
  const double k = c.stiffness[contact];  // N/m
  const double fn =
      k * (length - l) - c.damping[contact] * dot(move, u) / p.h;  // N, on the first end
  b.add_force(w * fn, u);
  const double sideways = l > length ? k * (1.0 - length / l) : 0.0;  // N/m
  b.add_identity(w * w * sideways);
  b.add_outer(w * w * (k + c.damping[contact] / p.h - sideways), u);
}

// Contacts between particles, linearised at the step's start; the other particles are read as
// contact_partner says.
void add_couplings(const VbdProblem& p, std::int64_t i, const double* xi, const double* x,
                   Block& b) {
  const VbdCouplings& c = p.couplings;
  for (std::int32_t e = c.offsets[i]; e < c.offsets[i + 1]; ++e) {
    const std::int64_t contact = c.contact[e];
    if (c.two_sided[contact] && c.particle[4 * contact + 1] >= 0) {
      add_particle_spring(p, contact, c.weight[4 * contact + c.slot[e]], i, xi, x, b);
      continue;
    }
    const double* n = c.normal + 3 * contact;
    double along = 0.0;  // m: n . sum_j w_j (x_j - x_j(n))
    for (int s = 0; s < 4; ++s) {
      const std::int64_t j = c.particle[4 * contact + s];
      if (j < 0) continue;
      const double* xj = contact_partner(p, i, xi, x, j);
      const double* sj = p.start + 3 * j;
      const double d[3] = {xj[0] - sj[0], xj[1] - sj[1], xj[2] - sj[2]};
      along += c.weight[4 * contact + s] * dot(d, n);
    }
    const double depth = c.depth[contact] - along;
    const double rate = along / p.h - c.end_rate[contact];  // m/s, relative to the far end
    const double fn = c.stiffness[contact] * depth - c.damping[contact] * rate;  // N
    if (fn <= 0.0 && !c.two_sided[contact]) continue;
    const double w = c.weight[4 * contact + c.slot[e]];
    b.add_force(w * fn, n);
    b.add_outer(w * w * (c.stiffness[contact] + c.damping[contact] / p.h), n);
  }
}

}  // namespace

void particle_block(const VbdProblem& p, std::int64_t i, const double* x, SpringTerms terms,
                    Block& b) {
  const double* xi = x + 3 * i;
  const double* si = p.start + 3 * i;
  const double* yi = p.inertia + 3 * i;
  const double move_i[3] = {xi[0] - si[0], xi[1] - si[1], xi[2] - si[2]};
  // Inertia m |x - y|^2 / (2 h^2) and air drag a m |x - x(n)|^2 / (2 h).
  const double inertia = p.mass[i] / (p.h * p.h);       // N/m
  const double drag = p.air_damping * p.mass[i] / p.h;  // N/m
  for (int d = 0; d < 3; ++d) b.f[d] = -inertia * (xi[d] - yi[d]) - drag * move_i[d];
  b.add_identity(inertia + drag);
  if (terms == SpringTerms::all) add_springs(p, i, x, b);
  if (p.continuum) {
    // The coarse step models the cloth's stiffness with its springs; it takes only the elements'
    // forces here.
    double unused[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    continuum_particle_terms(*p.continuum, i, x, p.start, p.h, b.f,
                             terms == SpringTerms::all ? b.h : unused);
  }
  if (p.planes.count) add_planes(p, i, xi, move_i, b);
  if (p.features.offsets) add_feature_contacts(p, i, xi, x, b);
  if (p.couplings.offsets) add_couplings(p, i, xi, x, b);
  if (p.self_contacts.offsets) add_self_contacts(p, i, xi, x, b);
}

namespace {

// The fraction of a Newton move (m) from xi at which the particle's block energy is least, when
// the move crosses into collider planes it starts outside of. A plane's energy is zero up to its
// onset and a spring k depth^2 / 2 past it, so the block of a particle outside the thickness holds
// none of it, and its move goes all the way to where inertia and the springs alone would take it,
// through the plane. Along the move, the block's energy is the quadratic the move minimises
// (its minimum at t = 1) plus each crossed plane's spring from where the move crosses its onset:
// a convex function of t whose least value lies between the first crossing and 1. Without it such a
// particle sat up to 8 mm deep after a sweep and dragged its neighbours down: a 65 x 65 sheet
// landing flat on a table at 0.94 m/s ended the step 2.1 mm into the 5 mm thickness, where one
// particle alone comes to rest 8 um in; with it, 0.14 mm. A second Newton step from inside the
// plane did as well there, but it turns the move, and a sheet on a sphere then gained energy
// (6e-5 J, against 8e-7 J with this). The features (edges and corners) take no part: measured each
// sweep afresh, their direction turns along the move, and on the table drape taking them in (with
// the second step) left the penetration as it was and raised the skirt's stretch to 2.2 %.

double onset_fraction(const VbdPlanes& q, std::int64_t i, const double* xi, const double* move,
                      const Block& b) {
  // Along the move, the quadratic's slope is a (t - 1) with a = move . H move (N m).
  const double hm[3] = {b.h[0] * move[0] + b.h[3] * move[1] + b.h[4] * move[2],
                        b.h[3] * move[0] + b.h[1] * move[1] + b.h[5] * move[2],
                        b.h[4] * move[0] + b.h[5] * move[1] + b.h[2] * move[2]};
  const double a = dot(move, hm);
  if (!(a > 0.0)) return 1.0;
  // Each crossed plane: depth d0 + s t (m), d0 <= 0 < d0 + s; its slope k s (d0 + s t) past the
  // onset t0 = -d0 / s. Planes in slot order; kVbdPlaneSlots is small, so the crossings are sorted
  // by a pass each.
  double onset[kVbdPlaneSlots], rate[kVbdPlaneSlots], depth0[kVbdPlaneSlots];
  int crossed = 0;
  for (int k = 0; k < std::min(q.count[i], kVbdPlaneSlots); ++k) {
    const std::int64_t e = i * q.slots + k;
    const double* n = q.normal + 3 * e;
    const double* point = q.point + 3 * e;
    const double offset[3] = {xi[0] - point[0], xi[1] - point[1], xi[2] - point[2]};
    const double d0 = q.radius - dot(offset, n);  // m
    const double s = -dot(move, n);               // m per unit of t
    if (d0 > 0.0 || d0 + s <= 0.0) continue;      // inside already, or not reached
    onset[crossed] = -d0 / s;
    rate[crossed] = s;
    depth0[crossed] = d0;
    ++crossed;
  }
  if (crossed == 0) return 1.0;
  // Past the onsets passed so far, the slope is a (t - 1) + sum k s (d0 + s t) = A t - B; its
  // root, if it comes before the next onset, is the least energy.
  double slope_t = a, slope_0 = a;  // A and B
  bool used[kVbdPlaneSlots] = {};
  for (int passed = 0; passed < crossed; ++passed) {
    int next = -1;
    for (int c = 0; c < crossed; ++c)
      if (!used[c] && (next < 0 || onset[c] < onset[next])) next = c;
    used[next] = true;
    slope_t += q.stiffness * rate[next] * rate[next];
    slope_0 -= q.stiffness * rate[next] * depth0[next];
    double following = 1.0;
    for (int c = 0; c < crossed; ++c)
      if (!used[c]) following = std::min(following, onset[c]);
    const double t = slope_0 / slope_t;
    if (t <= following) return std::max(t, onset[next]);
  }
  return 1.0;
}

// Particle i's Newton step; returns how far it moved (m). `truncated` counts a move cut short at
// the particle's conservative bound.
double solve_particle(const VbdProblem& p, std::int64_t i, double* x, std::int64_t& truncated) {
  if (p.inverse_mass[i] == 0.0) return 0.0;  // pinned
  Block b;
  particle_block(p, i, x, SpringTerms::all, b);
  double move[3];
  if (!b.solve(move)) return 0.0;
  double* xi = x + 3 * i;
  if (p.planes.count && p.planes.count[i] > 0) {
    const double t = onset_fraction(p.planes, i, xi, move, b);
    for (double& m : move) m *= t;
  }
  xi[0] += move[0];
  xi[1] += move[1];
  xi[2] += move[2];
  if (p.self_contacts.offsets && keep_within_bound(p.self_contacts, i, xi)) ++truncated;
  return std::sqrt(dot(move, move));
}

}  // namespace

VbdSweepResult vbd_sweep(const VbdProblem& problem, double* x) {
  double largest = 0.0;
  std::int64_t truncated = 0;
#pragma omp parallel if (problem.n >= 2048)
  for (int c = 0; c < problem.colors; ++c) {
    const std::int32_t begin = problem.color_offsets[c], end = problem.color_offsets[c + 1];
#pragma omp for schedule(static) reduction(max : largest) reduction(+ : truncated)
    for (std::int32_t k = begin; k < end; ++k)
      largest =
          std::max(largest, solve_particle(problem, problem.color_particles[k], x, truncated));
  }
  return {largest, truncated};
}

std::int64_t vbd_keep_within_bounds(const VbdProblem& problem, double* x) {
  if (!problem.self_contacts.offsets) return 0;
  std::int64_t truncated = 0;
#pragma omp parallel for schedule(static) reduction(+ : truncated) if (problem.n >= 4096)
  for (std::int64_t i = 0; i < problem.n; ++i)
    if (problem.inverse_mass[i] != 0.0 && keep_within_bound(problem.self_contacts, i, x + 3 * i))
      ++truncated;
  return truncated;
}

}  // namespace drapelab::kernels
