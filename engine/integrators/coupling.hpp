// A contact between particles (weighted_contact.hpp) as backward Euler's matrix sees it: it adds
// coefficient (w w^T) (x) n n^T, coefficient = h c + h^2 k (kg), to the matrix. Its diagonal blocks
// go where the matrix keeps each particle's own block (so the preconditioner sees them);
// products add the rest (coupling_product.hpp). Plain values only: the matrix-free loops include
// no Eigen.
#pragma once

#include <cstdint>

namespace drapelab::kernels {

struct Coupling {
  std::int32_t particle[4] = {-1, -1, -1, -1};  // -1: unused slot
  double weight[4] = {0.0, 0.0, 0.0, 0.0};
  double normal[3] = {0.0, 1.0, 0.0};  // unit
  double coefficient = 0.0;            // kg
};

}  // namespace drapelab::kernels
