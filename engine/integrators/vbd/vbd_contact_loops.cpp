// vbd's contact terms between a particle and others on plain arrays (vbd_block.hpp): the offset
// self-contacts and the collider feature contacts.
//
// Offset self-contacts. For particle i in slot s of a
// contact with weights w and gap d = |sum_j w_j x_j| along n, the energy g(d) (core/
// offset_barrier.hpp) gives the force -g'(d) w_s n and the block g''(d) w_s^2 n n^T; the distance's
// own curvature, g'(d) w_s^2 (I - n n^T) / d, is negative (g' < 0) and is dropped, so the block
// stays positive semidefinite. The damper c (n . du)^2 / (2 h) and friction with the load lagged at
// the detection join them as at the collider planes. The contact's other particles are read as
// contact_partner (vbd_loops.hpp) says.
#include <cmath>

#include "core/offset_barrier.hpp"
#include "integrators/vbd/vbd_block.hpp"

namespace drapelab::kernels {

void add_self_contacts(const VbdProblem& p, std::int64_t i, const double* xi, const double* x,
                       Block& b) {
  const OffsetContactArrays& c = p.self_contacts;
  const OffsetBarrier barrier{c.offset, c.stiffness};
  const double slip_scale = p.friction_velocity * p.h;  // m: the stick-slip boundary of a step
  const auto position = [&](std::int32_t j) { return contact_partner(p, i, xi, x, j); };
  for (std::int32_t row = c.offsets[i]; row < c.offsets[i + 1]; ++row) {
    const std::int64_t contact = c.contact[row];
    offset_contact::Geometry g;
    if (!offset_contact::geometry(c, contact, position, p.start, g)) continue;
    const double w = g.w[c.slot[row]];
    // The push along n: the barrier and the damper on the rate the gap opens.
    const double push = -barrier.slope(g.gap) - c.damping * g.normal_move / p.h;  // N
    b.add_force(w * push, g.n);
    b.add_outer(w * w * (barrier.curvature(g.gap) + c.damping / p.h), g.n);
    const offset_contact::Friction rub = offset_contact::friction(
        g, c.normal_force[contact], c.kinetic_friction, c.static_friction, slip_scale);
    if (!(rub.stiffness > 0.0)) continue;
    b.add_force(w, rub.force);
    b.add_identity(w * w * rub.stiffness);
    // Sliding or sticking, the curvature over the whole tangent plane (add_friction says why).
    b.add_outer(-w * w * rub.stiffness, g.n);
  }
}

void add_feature_contacts(const VbdProblem& p, std::int64_t i, const double* xi, const double* x,
                          Block& b) {
  const VbdFeatures& f = p.features;
  const double slip_scale = p.friction_velocity * p.h;  // m: the stick-slip boundary of a step
  const auto position = [&](std::int32_t j) { return contact_partner(p, i, xi, x, j); };
  for (std::int32_t row = f.offsets[i]; row < f.offsets[i + 1]; ++row) {
    const std::int64_t contact = f.contact[row];
    FeatureGeometry g;
    if (!feature_geometry(f, contact, position, p.start, g)) continue;
    const double* surface = f.surface_move + 3 * contact;
    const double rel[3] = {g.move[0] - surface[0], g.move[1] - surface[1],
                           g.move[2] - surface[2]};  // m, relative to the feature
    if (f.load[contact] > 0.0)
      add_friction(f.load[contact], g.n, rel, f.kinetic[contact], f.fixed[contact], slip_scale,
                   g.w[f.slot[row]], b);
    const double fn = g.depth > 0.0 ? f.stiffness * g.depth +
                                          f.damping * contact_closing(g.depth, dot(rel, g.n)) / p.h
                                    : 0.0;  // N
    if (fn <= 0.0) continue;
    const double w = g.w[f.slot[row]];
    b.add_force(w * fn, g.n);
    b.add_outer(w * w * (f.stiffness + f.damping / p.h), g.n);
  }
}

bool keep_within_bound(const OffsetContactArrays& contacts, std::int64_t i, double* xi) {
  const double* anchor = contacts.anchor + 3 * i;
  const double bound = contacts.bound[i];  // m
  const double u[3] = {xi[0] - anchor[0], xi[1] - anchor[1], xi[2] - anchor[2]};
  const double length2 = dot(u, u);
  if (length2 <= bound * bound) return false;
  const double scale = bound / std::sqrt(length2);
  for (int d = 0; d < 3; ++d) xi[d] = anchor[d] + scale * u[d];
  return true;
}

}  // namespace drapelab::kernels
