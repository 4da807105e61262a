// The offset self-contacts' totals at a state (offset_contact_arrays.hpp).
#include <algorithm>

#include "core/offset_barrier.hpp"
#include "core/offset_contact_arrays.hpp"

namespace drapelab {

OffsetContactTotals offset_contact_totals(const OffsetContactArrays& contacts, const double* x,
                                          const double* start, double h, double friction_velocity) {
  OffsetContactTotals totals;
  totals.smallest_gap = contacts.offset;
  const OffsetBarrier barrier{contacts.offset, contacts.stiffness};
  const auto position = [x](std::int32_t j) { return x + 3 * static_cast<std::int64_t>(j); };
  for (std::int64_t c = 0; c < contacts.count; ++c) {
    offset_contact::Geometry g;
    if (!offset_contact::geometry(contacts, c, position, start, g)) continue;
    ++totals.pushing;
    totals.energy += barrier.energy(g.gap);
    totals.normal_force += -barrier.slope(g.gap);
    totals.smallest_gap = std::min(totals.smallest_gap, g.gap);
    const double rate = g.normal_move / h;  // m/s, > 0 opening
    totals.dissipated_power += contacts.damping * rate * rate;
    const offset_contact::Friction rub =
        offset_contact::friction(g, contacts.normal_force[c], contacts.kinetic_friction,
                                 contacts.static_friction, friction_velocity * h);
    const double rub_force = std::sqrt(offset_contact::dot(rub.force, rub.force));
    totals.friction_force += rub_force;
    totals.dissipated_power -= offset_contact::dot(rub.force, g.slip) / h;
  }
  return totals;
}

}  // namespace drapelab
