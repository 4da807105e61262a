// The sweeps of vertex block descent (drapelab/vertex_block_descent.hpp) on plain arrays. Like
// particle_loops.hpp, this header and its source include no Eigen: the source is built with OpenMP
// for the build machine's CPU. Positions are 3 x n packed as in ClothState. Within a colour every
// particle reads only particles of other colours (or, for the contacts between particles, the
// positions at the sweep's start), and writes only itself, so the result is the same for any
// number of threads.
#pragma once

#include <cstdint>

#include "core/offset_contact_arrays.hpp"
#include "forces/continuum_loops.hpp"

namespace drapelab::kernels {

// Each particle's springs, as compressed rows: particle i's are entries offsets[i] to
// offsets[i + 1] - 1.
struct VbdSprings {
  const std::int32_t* offsets = nullptr;
  const std::int32_t* other = nullptr;  // the particle at the spring's other end
  const double* rest_length = nullptr;  // m
  const double* ks = nullptr;           // N/m
  const double* kd = nullptr;           // N*s/m
};

// Collider contacts as planes fixed for the step, at most `slots` per particle: particle i's k-th
// plane is entry i * slots + k, valid for k < count[i]. The plane is where the collider's surface
// is at the step's end; the particle keeps `radius` off it.
struct VbdPlanes {
  int slots = 0;
  const std::int32_t* count = nullptr;
  const double* point = nullptr;         // m, 3 per entry: a point of the surface
  const double* normal = nullptr;        // unit, 3 per entry: out of the collider
  const double* surface_move = nullptr;  // m, 3 per entry: the surface's motion over the step
  const double* kinetic = nullptr;       // Coulomb coefficients per entry
  const double* fixed = nullptr;         // static coefficient per entry
  double radius = 0.0;                   // m: the cloth's thickness
  double stiffness = 0.0;                // N/m
  double damping = 0.0;                  // N*s/m
};

// Contacts between particles (self-collision, collider edges on cloth edges), linearised at the
// step's start: the contact's depth is depth - n . sum_j w_j (x_j - x_j(n)). Particle i's entries
// are rows offsets[i] to offsets[i + 1] - 1 of (contact, slot) pairs.
struct VbdCouplings {
  const std::int32_t* offsets = nullptr;
  const std::int32_t* contact = nullptr;
  const std::int32_t* slot = nullptr;
  const std::int32_t* particle = nullptr;   // 4 per contact, -1 unused
  const double* weight = nullptr;           // 4 per contact
  const double* normal = nullptr;           // 3 per contact
  const double* depth = nullptr;            // m per contact, at the step's start
  const double* stiffness = nullptr;        // N/m per contact
  const double* damping = nullptr;          // N*s/m per contact
  const std::uint8_t* two_sided = nullptr;  // 1: pulls as well as pushes (a soft constraint)
  const double* end_rate = nullptr;         // m/s per contact: its far end's rate along n
};

struct VbdProblem {
  std::int64_t n = 0;
  double h = 0.0;                        // s
  double air_damping = 0.0;              // 1/s
  double friction_velocity = 0.0;        // m/s
  const double* mass = nullptr;          // kg per particle
  const double* inverse_mass = nullptr;  // 1/kg per particle, 0 when pinned
  const double* start = nullptr;         // m: x(n)
  const double* inertia = nullptr;       // m: y = x(n) + h v(n) + h^2 a
  const double* sweep_start = nullptr;   // m: the positions at the start of the sweep
  VbdSprings springs;
  const ContinuumArrays* continuum =
      nullptr;  // cloth.model: continuum (its springs are then empty)
  VbdPlanes planes;
  VbdCouplings couplings;  // offsets null: none
  // Offset self-contacts (self_collision/offset_contacts.hpp), offsets null: none. With them every
  // move stays within its particle's conservative bound.
  OffsetContactArrays self_contacts;
  // Colour c's particles are color_particles[color_offsets[c]] to [color_offsets[c + 1] - 1].
  const std::int32_t* color_offsets = nullptr;
  const std::int32_t* color_particles = nullptr;
  int colors = 0;
};

// One sweep: every colour in turn, each particle's Newton step on G with the others held. Updates
// x in place; returns the largest distance one particle moved (m) and how many moves were cut
// short at a conservative bound.
struct VbdSweepResult {
  double largest_move = 0.0;
  std::int64_t truncated = 0;
};
VbdSweepResult vbd_sweep(const VbdProblem& problem, double* x);

// Pulls every particle outside its conservative bound back to it (after a move of many particles
// at once: the initial guess, a coarse step, an acceleration); returns how many were outside.
std::int64_t vbd_keep_within_bounds(const VbdProblem& problem, double* x);

// Springs as a list, each once.
struct VbdSpringList {
  std::int64_t count = 0;
  const std::int32_t* v0 = nullptr;
  const std::int32_t* v1 = nullptr;
  const double* rest_length = nullptr;  // m
  const double* ks = nullptr;           // N/m
  const double* kd = nullptr;           // N*s/m
};

// Aggregates of free particles: aggregate a's members are members[offsets[a]] to
// members[offsets[a + 1] - 1].
struct VbdAggregates {
  std::int64_t count = 0;
  const std::int32_t* offsets = nullptr;
  const std::int32_t* members = nullptr;
};

// The terms of the coarse correction, a Newton step on G over the translations of the aggregates:
// each aggregate's summed force (N, 3 per aggregate) and summed block of everything but the springs
// (N/m, the 6 entries xx, yy, zz, xy, xz, yz per aggregate), and the block (6 entries) of each
// spring of `crossing`, the springs whose ends lie in different aggregates or at a pin. A crossing
// spring's block B joins the aggregates' as K_aa += B, K_bb += B, K_ab = K_ba -= B.
void vbd_coarse_terms(const VbdProblem& problem, const double* x, const VbdAggregates& aggregates,
                      const VbdSpringList& crossing, double* force, double* diagonal,
                      double* spring_blocks);

}  // namespace drapelab::kernels
