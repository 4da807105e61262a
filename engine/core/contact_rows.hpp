// Each particle's rows of (contact, slot) pairs, the layout the contact loops read: for contacts
// of `slots` particles each, listed in `particle` (slots per contact, -1 unused), particle i's
// pairs are rows[i] to rows[i + 1] - 1, in contact order. `scratch` is reused between calls, so a
// step that indexes as many contacts as the last allocates nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace drapelab {

inline void index_contact_rows(std::size_t particles, const std::vector<std::int32_t>& particle,
                               std::size_t slots, std::vector<std::int32_t>& rows,
                               std::vector<std::int32_t>& row_contact,
                               std::vector<std::int32_t>& row_slot,
                               std::vector<std::int32_t>& scratch) {
  rows.assign(particles + 1, 0);
  for (const std::int32_t i : particle)
    if (i >= 0) ++rows[static_cast<std::size_t>(i) + 1];
  for (std::size_t i = 0; i < particles; ++i) rows[i + 1] += rows[i];
  row_contact.resize(static_cast<std::size_t>(rows.back()));
  row_slot.resize(row_contact.size());
  scratch.assign(rows.begin(), rows.end() - 1);
  for (std::size_t k = 0; k < particle.size(); ++k) {
    const std::int32_t i = particle[k];
    if (i < 0) continue;
    const std::size_t at = static_cast<std::size_t>(scratch[static_cast<std::size_t>(i)]++);
    row_contact[at] = static_cast<std::int32_t>(k / slots);
    row_slot[at] = static_cast<std::int32_t>(k % slots);
  }
}

}  // namespace drapelab
