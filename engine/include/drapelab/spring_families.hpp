// The fast path of the spring phase for cloths whose springs come in a few "families" of constant
// index offset (every regular grid: stretch along x is +1, along the second axis +nx, the shear
// diagonals +nx+1 and +nx-1, bend +2 and +2nx). Within a family the second particle of each spring is
// the first plus the offset, so the positions stream through memory instead of being gathered, the
// force loop vectorises, and the rows of a family are independent, so they are shared among OpenMP
// threads.
//
// Determinism: each family's spring forces are computed into a per-spring buffer, then added to the
// first particles and subtracted from the second ones in two separate passes; a particle receives at
// most one term per pass, in a fixed family order. The result is therefore bitwise identical for
// any number of threads. It equals add_spring_forces (forces.hpp) to rounding: the same terms, summed
// in a different order.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/spring_family_loops.hpp"

namespace drapelab {

class SpringFamilies {
 public:
  // Groups the model's springs by offset; empty (no fast path) when that gives more than
  // `max_families` families or runs shorter than 4 springs on average (meshes, discs).
  static std::unique_ptr<SpringFamilies> build(const ClothModel& model, int max_families = 16);

  // force += every spring's damped force, +f on the first particle and -f on the second (N).
  void add_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force);

  int family_count() const { return static_cast<int>(families_.size()); }


 private:
  std::vector<SpringFamily> families_;
  // The per-spring force of the family being applied, per coordinate (the largest family's size).
  std::vector<double> t_[3];
};

}  // namespace drapelab
