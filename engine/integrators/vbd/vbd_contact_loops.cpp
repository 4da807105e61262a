// vbd's offset self-contacts on plain arrays (vbd_block.hpp). For particle i in slot s of a
// contact with weights w and gap d = |sum_j w_j x_j| along n, the energy g(d) (core/
// offset_barrier.hpp) gives the force -g'(d) w_s n and the block g''(d) w_s^2 n n^T; the distance's
// own curvature, g'(d) w_s^2 (I - n n^T) / d, is negative (g' < 0) and is dropped, so the block
// stays positive semidefinite. The damper c (n . du)^2 / (2 h) and friction with the load lagged at
// the detection join them as at the collider planes. The contact's other particles are read at the
// sweep's start (Jacobi): a contact may join two particles of one colour.
#include <cmath>

#include "core/offset_barrier.hpp"
#include "integrators/vbd/vbd_block.hpp"

namespace drapelab::kernels {

void add_self_contacts(const VbdProblem& p, std::int64_t i, const double* xi, Block& b) {
  const OffsetContactArrays& c = p.self_contacts;
  const OffsetBarrier barrier{c.offset, c.stiffness};
  const double slip_scale = p.friction_velocity * p.h;  // m: the stick-slip boundary of a step
  const auto position = [&](std::int32_t j) {
    return j == i ? xi : p.sweep_start + 3 * static_cast<std::int64_t>(j);
  };
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
    b.add_outer(-w * w * rub.stiffness, g.n);
    if (rub.sliding) {
      const double inv = 1.0 / rub.slip_length;
      const double dir[3] = {g.slip[0] * inv, g.slip[1] * inv, g.slip[2] * inv};
      b.add_outer(-w * w * rub.stiffness, dir);
    }
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
