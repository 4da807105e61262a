// The plain spring phase: adds into `force` (N, 3 x N) and allocates nothing.
#include "drapelab/spring_forces.hpp"
#include "forces/spring_force.hpp"

namespace drapelab {

double add_spring_forces(const ClothModel& model, const Eigen::Matrix3Xd& x,
                         const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force) {
  const SpringSet& s = model.springs;
  const std::size_t count = s.size();
  double damper_power = 0.0;  // W
  for (std::size_t e = 0; e < count; ++e) {
    const int a = s.v0[e], b = s.v1[e];
    const Eigen::Vector3d f = damped_spring_force(x.col(a), x.col(b), v.col(a), v.col(b), s.ks[e],
                                                  s.kd[e], s.rest_length[e]);
    force.col(a) += f;
    force.col(b) -= f;
    damper_power += spring_damper_power(x.col(a), x.col(b), v.col(a), v.col(b), s.kd[e]);
  }
  return damper_power;
}

}  // namespace drapelab
