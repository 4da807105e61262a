// The sweeps of vertex block descent (drapelab/vertex_block_descent.hpp) on plain arrays. Like
// particle_loops.hpp, this header and its source include no Eigen: the source is built with OpenMP
// for the build machine's CPU. Positions are 3 x n packed as in ClothState. Within a colour every
// particle reads only particles of other colours (or, for the contacts between particles, the
// positions at the sweep's start), and writes only itself, so the result is the same for any
// number of threads.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/feature_push.hpp"
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
// Collider planes kept per particle: a particle touches at most a corner's three faces in the
// scenes drapelab runs; a fourth slot leaves room for a second collider.
inline constexpr int kVbdPlaneSlots = 4;

struct VbdPlanes {
  int slots = 0;  // kVbdPlaneSlots
  const std::int32_t* count = nullptr;
  const double* point = nullptr;         // m, 3 per entry: a point of the surface
  const double* normal = nullptr;        // unit, 3 per entry: out of the collider
  const double* surface_move = nullptr;  // m, 3 per entry: the surface's motion over the step
  const double* kinetic = nullptr;       // Coulomb coefficients per entry
  const double* fixed = nullptr;         // static coefficient per entry
  // N per entry: friction's load, lagged at the step's start. A load that followed the iterate
  // would make friction no force of any energy, and the sweeps of a light particle on a stiff
  // contact would swing between sticking hard and slipping free (energy gained at rest).
  const double* load = nullptr;
  double radius = 0.0;     // m: the cloth's thickness
  double stiffness = 0.0;  // N/m
  double damping = 0.0;    // N*s/m
};

// Contacts between particles (soft constraints), linearised at the
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

// Collider edges against cloth edges and collider corners against cloth triangles
// (contact/edge_contact.hpp), found at the step's start within a margin and measured afresh from
// the positions wherever a particle's block is built, against the features where the collider is
// at the step's end. A contact is one cloth edge or triangle and one collider, with its candidate
// features (contact c's are features feature_offsets[c] to feature_offsets[c + 1] - 1): the
// nearest one that holds the cloth's closest point inside the cloth edge or triangle pushes, so a
// cloth edge that slides along a cylinder's rim passes from chord to chord. Particle i's entries
// are rows offsets[i] to offsets[i + 1] - 1 of (contact, slot) pairs.
struct VbdFeatures {
  const std::int32_t* offsets = nullptr;  // null: none
  const std::int32_t* contact = nullptr;
  const std::int32_t* slot = nullptr;
  const std::int32_t* particle = nullptr;  // 3 per contact: a cloth edge (a, b, -1) or triangle
  const std::int32_t* feature_offsets = nullptr;  // contacts + 1
  const double* surface_move = nullptr;  // m, 3 per contact: the collider's motion over the step
  const double* kinetic = nullptr;       // Coulomb coefficients per contact
  const double* fixed = nullptr;         // static coefficient per contact
  const double* load = nullptr;          // N per contact: friction's, lagged (as VbdPlanes's)
  const double* from = nullptr;          // m, 3 per feature: a collider edge's ends, or its
  const double* to = nullptr;            //    corner twice
  const double* outward = nullptr;       // unit, 3 per feature
  const double* faces = nullptr;         // unit, 9 per feature (core/feature_push.hpp)
  double radius = 0.0;                   // m: the cloth's thickness
  double stiffness = 0.0;                // N/m
  double damping = 0.0;                  // N*s/m
};

// One feature contact at a state: the cloth point's weights on its particles, the push's unit
// direction n, its depth (m, > 0 within the thickness) and the cloth point's move since the step's
// start (m, 3).
struct FeatureGeometry {
  double w[3] = {0.0, 0.0, 0.0};
  double n[3] = {0.0, 0.0, 0.0};
  double depth = 0.0;
  double move[3] = {0.0, 0.0, 0.0};
};

// Contact c's geometry with its particle j at position(j) and at start + 3 j at the step's start,
// the push by core/feature_push.hpp's law from the nearest candidate feature (it pushes while
// depth > 0). False where no candidate holds the cloth's closest point inside its edge or triangle
// (the particle contact holds it there; for a box's edge, inside the edge too: its corner holds
// its ends).
template <typename Position>
bool feature_geometry(const VbdFeatures& f, std::int64_t c, const Position& position,
                      const double* start, FeatureGeometry& g) {
  g = FeatureGeometry{};
  const std::int32_t* particle = f.particle + 3 * c;
  const int corners = particle[2] < 0 ? 2 : 3;
  const double* p[3] = {position(particle[0]), position(particle[1]),
                        corners == 3 ? position(particle[2]) : nullptr};
  double best = -1.0;  // m^2: the nearest candidate's squared distance
  double r[3] = {0.0, 0.0, 0.0};
  std::int32_t nearest = -1;
  for (std::int32_t e = f.feature_offsets[c]; e < f.feature_offsets[c + 1]; ++e) {
    const double* a = f.from + 3 * e;
    const double* b = f.to + 3 * e;
    double w[3] = {0.0, 0.0, 0.0}, on_feature[3] = {a[0], a[1], a[2]};
    if (corners == 2) {
      double s = 0.0, t = 0.0;
      offset_contact::segment_pair_parameters(p[0], p[1], a, b, s, t);
      if (!(s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0)) continue;
      w[0] = 1.0 - s;
      w[1] = s;
      for (int d = 0; d < 3; ++d) on_feature[d] += t * (b[d] - a[d]);
    } else {
      offset_contact::triangle_weights(a, p[0], p[1], p[2], w);
      if (!(w[0] > 0.0 && w[1] > 0.0 && w[2] > 0.0)) continue;
    }
    double gap[3] = {-on_feature[0], -on_feature[1], -on_feature[2]};
    for (int s = 0; s < corners; ++s)
      for (int d = 0; d < 3; ++d) gap[d] += w[s] * p[s][d];
    const double distance2 = offset_contact::dot(gap, gap);
    if (nearest >= 0 && distance2 >= best) continue;
    nearest = e;
    best = distance2;
    for (int d = 0; d < 3; ++d) {
      r[d] = gap[d];
      g.w[d] = w[d];
    }
  }
  if (nearest < 0) return false;
  for (int s = 0; s < corners; ++s) {
    const double* from = start + 3 * static_cast<std::int64_t>(particle[s]);
    for (int d = 0; d < 3; ++d) g.move[d] += g.w[s] * (p[s][d] - from[d]);
  }
  feature_push::push(r, f.outward + 3 * nearest, f.faces + 9 * nearest, f.radius, g.n, g.depth);
  return true;
}

// How much deeper (m) a collider contact of depth `depth` (m, > 0) is than at the step's start,
// counting only what lies within the thickness, when its point moved `along` (m) along the push
// since then (relative to the surface): the damper c closing / h acts on this. A particle arriving
// from outside the thickness meets a damper that grows from zero with its depth, as its spring
// does; a damper on the whole approach would switch on at full force at the thickness, and the
// step's energy, discontinuous there, would send a particle's Newton steps back and forth
// across it.
inline double contact_closing(double depth, double along) {
  const double start_depth = depth + along;  // m
  return depth - (start_depth > 0.0 ? start_depth : 0.0);
}

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
  VbdFeatures features;
  VbdCouplings couplings;  // offsets null: none
  // Offset self-contacts (self_collision/offset_contacts.hpp), offsets null: none. With them every
  // move stays within its particle's conservative bound.
  OffsetContactArrays self_contacts;
  // Colour c's particles are color_particles[color_offsets[c]] to [color_offsets[c + 1] - 1];
  // particle i's colour is color_of[i].
  const std::int32_t* color_offsets = nullptr;
  const std::int32_t* color_particles = nullptr;
  const std::int32_t* color_of = nullptr;
  int colors = 0;
};

// Where particle i's terms read particle j of a contact: x itself when j is of another colour
// (Gauss-Seidel: j is not written while i's colour is swept), the sweep's start when j shares i's
// colour (Jacobi: j may be written by another thread meanwhile). Reading a contact's other
// particles at the sweep's start even when they had moved lets two particles of a stiff contact
// both take the whole correction; their sum then overshoots and the contact rings.
inline const double* contact_partner(const VbdProblem& p, std::int64_t i, const double* xi,
                                     const double* x, std::int64_t j) {
  if (j == i) return xi;
  return (p.color_of[j] == p.color_of[i] ? p.sweep_start : x) + 3 * j;
}

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

// The coarse space of the coarse step: aggregates of free particles, each moving as a rigid
// patch (a translation and a small rotation about its mass centre). Aggregate a's members are
// members[offsets[a]] to members[offsets[a + 1] - 1]; of[i] is particle i's aggregate (-1 when
// pinned).
struct VbdAggregates {
  std::int64_t count = 0;
  const std::int32_t* offsets = nullptr;
  const std::int32_t* members = nullptr;
  const std::int32_t* of = nullptr;
  // The springs the coarse step models the cloth's stiffness with, per particle: the cloth's own,
  // also for a continuum cloth, whose forces come from its elements instead (`spring_forces`
  // false).
  VbdSprings springs;
  bool spring_forces = true;
  // Whether the aggregates turn; when they only translate, the terms are the blocks' top left
  // 3 x 3 and the forces, and the torques and turn terms stay zero.
  bool turns = true;
  // Pairs of aggregates joined by a spring: pair p joins aggregates[2 p] and aggregates[2 p + 1],
  // and its springs are entries offsets[p] to offsets[p + 1] - 1 of `joining`, each with its v0 in
  // the first aggregate.
  std::int64_t pair_count = 0;
  const std::int32_t* pair_aggregates = nullptr;
  const std::int32_t* pair_offsets = nullptr;
  VbdSpringList joining;
};

// The coarse step's system at x, a Newton step on G over each aggregate's translation t and
// rotation w (particle i of aggregate a moves by t + w x r_i, r_i = x_i - c_a):
// - per aggregate: its mass centre c_a (m, 3), its radius max |r_i| (m), its force and torque
//   about c_a (N and N*m, 6) and its 6 x 6 block (36, row-major) P_i^T H_ii P_i summed over its
//   members, with H_ii holding every term but the springs inside the aggregate, whose stiffness
//   against a rotation is their tension's alone;
// - per pair of aggregates a, b: the block -P_a^T B P_b (36, row-major) summed over the springs
//   joining them, B each one's block.
struct VbdCoarseTerms {
  double* centre = nullptr;
  double* radius = nullptr;
  double* force = nullptr;
  double* block = nullptr;
  double* pair_block = nullptr;
};
void vbd_coarse_terms(const VbdProblem& problem, const double* x, const VbdAggregates& aggregates,
                      const VbdCoarseTerms& terms);

}  // namespace drapelab::kernels
