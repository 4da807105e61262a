// The inner loops of the spring fast path (spring_families.hpp) on plain arrays. This header and
// its source include no Eigen: the source is compiled for the build machine's full vector width
// (-march=native), and Eigen types must have one layout across the whole program.
#pragma once

#include <cstdint>
#include <vector>

#include "drapelab/loop_threads.hpp"

namespace drapelab {

// The springs (i, i + offset) of one family, stored densely by first particle: slot i of every
// array describes the spring whose first particle is i, and holds zeros where there is none (a grid
// row's last particle has no +1 neighbour), so the loops run over every slot without branches. When
// every spring of the family has the same rest length, ks and kd (a regular grid), the loops read
// those three numbers instead of three arrays and then clear the empty slots; when only ks and kd
// are shared, they read the rest lengths alone.
struct SpringFamily {
  std::int32_t offset = 0;
  std::int64_t springs = 0;          // slots holding a real spring
  std::vector<double> rest, ks, kd;  // per slot: m, N/m, N*s/m (0, 0, 0 for no spring)
  bool uniform = false;              // every spring has uniform_rest, uniform_ks, uniform_kd
  // Every spring has uniform_ks and uniform_kd but rest lengths vary (a sheet built from perturbed
  // positions): the loops read the rest array only.
  bool uniform_stiffness = false;
  double uniform_rest = 0.0, uniform_ks = 0.0, uniform_kd = 0.0;  // m, N/m, N*s/m
  std::vector<std::int32_t>
      empty_slots;  // uniform or uniform_stiffness: the slots holding no spring
};

namespace kernels {

// Scratch of the loops, sized once for a cloth of `particles` and `families` families whose largest
// offset is `max_offset`: the state split into six arrays of x, y, z, vx, vy, vz (each padded by
// max_offset zeros, so that slot i may read particle i + offset), and per family the three force
// components of every slot (each preceded by max_offset zeros, so that particle i may read slot
// i - offset).
struct FamilyScratch {
  std::int64_t particles = 0;
  std::int64_t padding = 0;
  std::vector<double> state;   // 6 x (particles + padding)
  std::vector<double> forces;  // families x 3 x (padding + particles)
  // W: per block of kPhaseBlock particles, the power its springs' dampers took in the last call,
  // kd ((v_i - v_j) . d / l)^2 summed over the springs whose first particle is in the block.
  std::vector<double> block_damper_power;
  void resize(std::int64_t particles, std::int64_t families, std::int64_t max_offset);
  // The last call's damper power over every spring (W), summed in block order: the same bits on
  // any number of threads.
  double damper_power() const;
  double* state_row(int row) { return state.data() + row * (particles + padding); }
  double* force_row(std::int64_t family, int component) {
    return forces.data() + (3 * family + component) * (padding + particles) + padding;
  }
};

// Gravity and air drag to start f from instead of its contents (body_force_loops.hpp
// set_body_forces: per coordinate, weight in N, mass in kg, air in 1/s).
struct BodyForceInputs {
  const double* weight = nullptr;
  const double* mass = nullptr;
  double air = 0.0;
};

// Work run inside the loops' parallel region once a thread's particles have their final forces: on
// every thread of the region, once, with that thread's run of blocks of kPhaseBlock particles
// [first_block, end_block) (core/thread_blocks.hpp thread_run's split; all of them on one thread
// when the region does not split). It may read and write only those particles' data, x, v, f and
// the split state (the other threads may still be gathering theirs, reading the slot rows, which it
// must not write), and must not wait for the other threads. It saves the contact phase a parallel
// region of its own.
struct ForcesFinalHook {
  void (*run)(const void* context, std::int64_t first_block, std::int64_t end_block) = nullptr;
  const void* context = nullptr;
};

// f[3i + c] += (sum over families, in order) t_f[c][i] - t_f[c][i - offset_f], where t_f[c][i] is
// the damped force on the first particle of the spring in slot i,
//   -[ks (l - l0) + kd (dv . d) / l] d / l,   d = x(i) - x(i + offset),   zero for a zero length
//   (N).
// x, v, f: 3 x particles, packed as in ClothState (m, m/s, N). Every particle's terms are summed in
// the same order whatever the thread count, so the result is bitwise identical for any thread
// count. With `body`, f is first overwritten with the body forces, block by block in the same
// parallel region (one pass over the particles and one start of the threads fewer than
// set_body_forces, then this). `state_split`: the scratch's six state arrays already hold x and v
// (split_state_range was run over every particle since they last changed), so the loops skip that
// pass and its barrier. `after`, when given, runs as ForcesFinalHook says; the forces are then
// final for its particles only, and for every particle once the call returns.
void add_family_forces(const double* x, const double* v, const std::vector<SpringFamily>& families,
                       FamilyScratch& scratch, double* f, const BodyForceInputs* body = nullptr,
                       bool state_split = false, const ForcesFinalHook* after = nullptr);
// Particles begin <= i < end of x and v (3 x particles, packed) into the scratch's six state
// arrays, on the calling thread: for a phase that has just written those particles (the Euler
// update), so the next force evaluation need not split the whole state again.
void split_state_range(const double* x, const double* v, FamilyScratch& scratch, std::int64_t begin,
                       std::int64_t end);

}  // namespace kernels
}  // namespace drapelab
