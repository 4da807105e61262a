// Vectorised, threaded loops of the spring fast path (spring_family_loops.hpp). One parallel region
// per call: split the state into unit-stride arrays, compute every family's slot forces, then
// gather each particle's forces; each loop is split among threads with a static schedule, and every
// value is computed by the same expression whichever thread computes it, so no sum depends on the
// thread count.
#include "forces/spring_family_loops.hpp"

#include <algorithm>
#include <cmath>

#include "core/thread_blocks.hpp"
#include "forces/body_force_loops.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace drapelab::kernels {
namespace {

// Below this many slots in all, starting threads costs more than it saves (a parallel region costs
// a few microseconds; a slot about a nanosecond).
constexpr std::int64_t kParallelSlots = 16384;
// Particles per block of the gather, so a block's accumulators and force rows stay in cache; the
// contact phase's blocks too (core/thread_blocks.hpp).
constexpr std::int64_t kGatherBlock = kPhaseBlock;

}  // namespace

void FamilyScratch::resize(std::int64_t particle_count, std::int64_t families,
                           std::int64_t max_offset) {
  particles = particle_count;
  padding = max_offset;
  state.assign(static_cast<std::size_t>(6 * (particles + padding)), 0.0);
  forces.assign(static_cast<std::size_t>(3 * families * (padding + particles)), 0.0);
  block_damper_power.assign(static_cast<std::size_t>((particles + kGatherBlock - 1) / kGatherBlock),
                            0.0);
}

double FamilyScratch::damper_power() const {
  double total = 0.0;
  for (const double block : block_damper_power) total += block;
  return total;
}

namespace {

// The force on the first particle of every spring slot in [begin, end) of one family (N), into the
// family's three slot rows: -[ks (l - l0) + kd (dv . d) / l] d / l with d = x(i) - x(i + offset).
// A family with shared stiffness then clears its empty slots in the range (they computed a force
// towards a non-neighbour or the padding). Returns the power the range's dampers take (W),
// kd ((dv . d) / l)^2 per spring.
double family_slot_forces(const SpringFamily& fam, const double* px, const double* py,
                          const double* pz, const double* vx, const double* vy, const double* vz,
                          double* tx, double* ty, double* tz, std::int64_t begin,
                          std::int64_t end) {
  const std::int64_t o = fam.offset;
  // The same expression for both layouts, so a slot's force does not depend on which one ran.
  const auto slot_force = [&](std::int64_t i, double rest, double ks, double kd) {
    const double dx = px[i] - px[i + o], dy = py[i] - py[i + o], dz = pz[i] - pz[i + o];
    const double dvx = vx[i] - vx[i + o], dvy = vy[i] - vy[i + o], dvz = vz[i] - vz[i + o];
    const double l = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double inverse =
        l > 0.0 ? 1.0 / l : 0.0;  // a zero-length spring has no direction: no force
    const double closing = dvx * dx + dvy * dy + dvz * dz;              // m^2/s, (dv . d)
    const double magnitude = ks * (l - rest) + kd * closing * inverse;  // N
    const double scale = -magnitude * inverse;
    tx[i] = scale * dx;
    ty[i] = scale * dy;
    tz[i] = scale * dz;
    const double rate = closing * inverse;  // m/s, the spring's rate of stretch
    return kd * rate * rate;                // W
  };
  double power = 0.0;  // W
  if (fam.uniform || fam.uniform_stiffness) {
    const double ks = fam.uniform_ks, kd = fam.uniform_kd;
    if (fam.uniform) {
      const double rest = fam.uniform_rest;
#pragma omp simd reduction(+ : power)
      for (std::int64_t i = begin; i < end; ++i) power += slot_force(i, rest, ks, kd);
    } else {
      const double* rest = fam.rest.data();
#pragma omp simd reduction(+ : power)
      for (std::int64_t i = begin; i < end; ++i) power += slot_force(i, rest[i], ks, kd);
    }
    // An empty slot's "damper" joins unrelated particles: its power is taken back out.
    const auto first = std::lower_bound(fam.empty_slots.begin(), fam.empty_slots.end(), begin);
    for (auto e = first; e != fam.empty_slots.end() && *e < end; ++e) {
      power -= slot_force(*e, fam.uniform ? fam.uniform_rest : fam.rest[*e], ks, kd);
      tx[*e] = ty[*e] = tz[*e] = 0.0;
    }
  } else {
    const double* rest = fam.rest.data();
    const double* ks = fam.ks.data();
    const double* kd = fam.kd.data();
#pragma omp simd reduction(+ : power)
    for (std::int64_t i = begin; i < end; ++i) power += slot_force(i, rest[i], ks[i], kd[i]);
  }
  return power;
}

// Particle i of [begin, end) gathers f(i) + sum over families, in order, of t(i) - t(i - offset).
void gather(const std::vector<SpringFamily>& families, FamilyScratch& scratch, double* f,
            std::int64_t begin, std::int64_t end) {
  double sum[3][kGatherBlock];
  for (std::int64_t i = begin; i < end; ++i)
    for (int c = 0; c < 3; ++c) sum[c][i - begin] = f[3 * i + c];
  const std::int64_t family_count = static_cast<std::int64_t>(families.size());
  for (std::int64_t family = 0; family < family_count; ++family) {
    const std::int64_t o = families[static_cast<std::size_t>(family)].offset;
    for (int c = 0; c < 3; ++c) {
      const double* t =
          scratch.force_row(family, c) + begin;  // t[j - o] may read the leading zeros
      double* s = sum[c];
#pragma omp simd
      for (std::int64_t j = 0; j < end - begin; ++j) s[j] = (s[j] + t[j]) - t[j - o];
    }
  }
  for (std::int64_t i = begin; i < end; ++i)
    for (int c = 0; c < 3; ++c) f[3 * i + c] = sum[c][i - begin];
}

}  // namespace

void split_state_range(const double* x, const double* v, FamilyScratch& scratch, std::int64_t begin,
                       std::int64_t end) {
  double* const px = scratch.state_row(0);
  double* const py = scratch.state_row(1);
  double* const pz = scratch.state_row(2);
  double* const vx = scratch.state_row(3);
  double* const vy = scratch.state_row(4);
  double* const vz = scratch.state_row(5);
  for (std::int64_t i = begin; i < end; ++i) {
    px[i] = x[3 * i];
    py[i] = x[3 * i + 1];
    pz[i] = x[3 * i + 2];
    vx[i] = v[3 * i];
    vy[i] = v[3 * i + 1];
    vz[i] = v[3 * i + 2];
  }
}

void add_family_forces(const double* x, const double* v, const std::vector<SpringFamily>& families,
                       FamilyScratch& scratch, double* f, const BodyForceInputs* body,
                       bool state_split, const ForcesFinalHook* after) {
  const std::int64_t n = scratch.particles;
  const std::int64_t family_count = static_cast<std::int64_t>(families.size());
  const std::int64_t max_offset = scratch.padding;
  const double* const px = scratch.state_row(0);
  const double* const py = scratch.state_row(1);
  const double* const pz = scratch.state_row(2);
  const double* const vx = scratch.state_row(3);
  const double* const vy = scratch.state_row(4);
  const double* const vz = scratch.state_row(5);
  const std::int64_t blocks = (n + kGatherBlock - 1) / kGatherBlock;
#pragma omp parallel if (n * family_count >= kParallelSlots)
  {
    // 1. The packed state into six unit-stride arrays (their padding stays zero), unless the caller
    // split it already (then the end of the phase that did so is the barrier); the barrier ending
    // this pass precedes every slot loop, which reads particles of the other thread's run.
    if (!state_split) {
      const ThreadRun share = thread_run(n, 1, n, 0);  // an equal share of the particles
      split_state_range(x, v, scratch, share.begin, share.end);
#pragma omp barrier
    }
    // 2. Each thread walks its own run of blocks in order: a block's slot forces of every family,
    // then its body forces (by a function of body_force_loops.cpp, built without fused
    // multiply-adds, so f has the bits of set_body_forces) and the gather of its particles, while
    // those slots are still in cache. Particle i reads slots i and i - offset, computed by this
    // block or an earlier one; only the first max_offset particles of a thread's run read slots of
    // the thread before, so their gather waits for the barrier (their body forces, set here by the
    // same thread, wait with them).
    const ThreadRun run = thread_run(blocks, kGatherBlock, n, max_offset);
    for (std::int64_t block = run.first_block; block < run.end_block; ++block) {
      const std::int64_t begin = block * kGatherBlock, end = std::min(n, begin + kGatherBlock);
      double damper_power = 0.0;  // W
      for (std::int64_t family = 0; family < family_count; ++family)
        damper_power +=
            family_slot_forces(families[static_cast<std::size_t>(family)], px, py, pz, vx, vy, vz,
                               scratch.force_row(family, 0), scratch.force_row(family, 1),
                               scratch.force_row(family, 2), begin, end);
      scratch.block_damper_power[static_cast<std::size_t>(block)] = damper_power;
      if (body) set_body_forces_range(begin, end, body->weight, body->mass, body->air, v, f);
      const std::int64_t gather_begin = std::max(begin, run.deferred_end);
      if (gather_begin < end) gather(families, scratch, f, gather_begin, end);
    }
#pragma omp barrier
    // 3. The deferred particles at the start of each run (none for the first thread).
    for (std::int64_t begin = run.begin; begin < run.deferred_end; begin += kGatherBlock)
      gather(families, scratch, f, begin, std::min(run.deferred_end, begin + kGatherBlock));
    // 4. This thread's particles are final: the caller's work on them, with no barrier before it.
    // The slot loops, the only readers of other threads' particles, ended at the barrier above; the
    // deferred gathers still read other threads' slot rows, which nothing writes after that barrier
    // (a hook must not write them either).
    if (after) after->run(after->context, run.first_block, run.end_block);
  }
}

}  // namespace drapelab::kernels
