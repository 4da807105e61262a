// The off-diagonal part of the couplings' product (coupling.hpp), for any vector layout: y_j +=
// coefficient w_j n (n . sum_{k != j} w_k p_k) for every moving particle j of each coupling, in
// one fixed order (serial: the results do not depend on the thread count).
#pragma once

#include <vector>

#include "integrators/coupling.hpp"

namespace drapelab::kernels {

// `p(j, c)` reads component c of particle j of p (zero for a pinned particle), `y(j, c)` gives
// that of y to add into; `free[j]` is 0 for a pinned particle. Returns the p . y it adds.
template <typename ReadP, typename WriteY>
double add_coupling_products(const std::vector<Coupling>& couplings, const double* free, ReadP&& p,
                             WriteY&& y) {
  double added = 0.0;
  for (const Coupling& coupling : couplings) {
    const double* n = coupling.normal;
    double along[4] = {0.0, 0.0, 0.0, 0.0};  // n . p_j
    double sum = 0.0;                        // n . sum_j w_j p_j
    double own = 0.0;                        // sum_j w_j^2 (n . p_j)^2: the diagonal blocks' share
    for (int k = 0; k < 4; ++k) {
      const std::int32_t j = coupling.particle[k];
      if (j < 0) continue;
      along[k] = n[0] * p(j, 0) + n[1] * p(j, 1) + n[2] * p(j, 2);
      sum += coupling.weight[k] * along[k];
      own += coupling.weight[k] * coupling.weight[k] * along[k] * along[k];
    }
    for (int k = 0; k < 4; ++k) {
      const std::int32_t j = coupling.particle[k];
      if (j < 0 || free[j] == 0.0) continue;
      const double scale =
          coupling.coefficient * coupling.weight[k] * (sum - coupling.weight[k] * along[k]);
      for (int c = 0; c < 3; ++c) y(j, c) += scale * n[c];
    }
    added += coupling.coefficient * (sum * sum - own);
  }
  return added;
}

}  // namespace drapelab::kernels
