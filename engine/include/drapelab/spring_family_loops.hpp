// The inner loops of the spring fast path (spring_families.hpp) on plain arrays. This header and its
// source include no Eigen: the source is compiled for the build machine's full vector width
// (-march=native), and Eigen types must have one layout across the whole program.
#pragma once

#include <cstdint>
#include <vector>

namespace drapelab {

// Springs (k, k + offset) for k in runs of consecutive first particles.
struct SpringFamily {
  std::int32_t offset = 0;
  std::vector<std::int32_t> run_start;   // first particle of each run
  std::vector<std::int32_t> run_length;  // springs in the run
  std::vector<std::int32_t> run_slot;    // index of the run's first spring in the arrays below
  std::vector<double> rest, ks, kd;      // per spring: m, N/m, N*s/m
  std::int64_t size() const { return static_cast<std::int64_t>(rest.size()); }
};

namespace kernels {

// Positions and velocities as stored in ClothState: x, y, z of particle k at [3k], [3k+1], [3k+2]
// (m, m/s).
struct PackedState {
  const double* x;
  const double* v;
};
// t[c][slot] = the damped spring force on the first particle of every spring of the family (N):
// -[ks (l - l0) + kd (dv . d) / l] d / l with d = x(k) - x(k + offset); zero for a zero length.
void family_forces(const PackedState& s, const SpringFamily& family, double* const t[3]);
// f[3k + c] += t[c] for the first particles, then f[3(k + offset) + c] -= t[c] for the second ones.
void family_scatter(const SpringFamily& family, double* const t[3], double* f);
// Threads the loops use (OpenMP); always 1 in a build without OpenMP.
void set_thread_count(int threads);
int thread_count();

}  // namespace kernels
}  // namespace drapelab
