// The fast path of the spring phase for cloths whose springs come in a few "families" of constant
// index offset (every regular grid: stretch along x is +1, along the second axis +nx, the shear
// diagonals +nx+1 and +nx-1, bend +2 and +2nx). A family is stored densely by its springs' first
// particle, so the loops stream through unit-stride arrays with no index lists, vectorise fully and
// split among OpenMP threads (spring_family_loops.hpp).
//
// Determinism: every spring's force is computed into its family's slot array, then each particle
// gathers its terms in a fixed family order (+ as a first particle, - as a second). The result is
// therefore bitwise identical for any number of threads. It equals add_spring_forces (forces.hpp)
// to rounding: the same terms, summed in a different order.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "forces/spring_family_loops.hpp"

namespace drapelab {

class SpringFamilies {
 public:
  // Groups the model's springs by offset; empty (no fast path) when that gives more than
  // `max_families` families, two springs share a first particle within a family, or fewer than half
  // of the families' slots hold a spring (meshes, discs).
  static std::unique_ptr<SpringFamilies> build(const ClothModel& model, int max_families = 16);

  // force += every spring's damped force, +f on the first particle and -f on the second (N).
  void add_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force);
  // force = gravity and air drag (per coordinate: weight m g in N, mass in kg, air in 1/s; as
  // body_force_loops.hpp set_body_forces, bit for bit) + every spring's force, in one threaded
  // pass. `state_split`: split_state has been given every particle of this x and v since they last
  // changed. `after`: work on each thread's particles once their forces are final, in the same
  // parallel region (spring_family_loops.hpp ForcesFinalHook).
  void set_body_and_spring_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                                  const Eigen::Matrix3Xd& weight, const Eigen::Matrix3Xd& mass,
                                  double air, Eigen::Matrix3Xd& force, bool state_split = false,
                                  const kernels::ForcesFinalHook* after = nullptr);
  // Copies particles [begin, end) of x and v (3 x N, packed) into the loops' unit-stride state, on
  // the calling thread (spring_family_loops.hpp split_state_range).
  void split_state(const double* x, const double* v, std::int64_t begin, std::int64_t end) {
    kernels::split_state_range(x, v, scratch_, begin, end);
  }

  // The power the springs' dampers took in the last call of either of the above (W).
  double damper_power() const { return scratch_.damper_power(); }

  int family_count() const { return static_cast<int>(families_.size()); }
  const std::vector<SpringFamily>& families() const { return families_; }

 private:
  std::vector<SpringFamily> families_;
  kernels::FamilyScratch scratch_;
};

}  // namespace drapelab
