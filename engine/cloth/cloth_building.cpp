// Pieces every cloth builder shares (cloth_building.hpp).
#include "cloth/cloth_building.hpp"

#include <Eigen/Geometry>
#include <memory>
#include <stdexcept>

#include "drapelab/continuum.hpp"

namespace drapelab::building {

void add_spring(SpringSet& springs, const Eigen::Matrix3Xd& rest, int a, int b, SpringKind kind,
                const SpringParams& params) {
  springs.v0.push_back(a);
  springs.v1.push_back(b);
  springs.rest_length.push_back((rest.col(a) - rest.col(b)).norm());
  springs.ks.push_back(params.ks);
  springs.kd.push_back(params.kd);
  springs.kind.push_back(kind);
}

Eigen::VectorXd vertex_areas(const Eigen::Matrix3Xd& rest, const Eigen::Matrix3Xi& triangles) {
  Eigen::VectorXd area = Eigen::VectorXd::Zero(rest.cols());
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    const int a = triangles(0, t), b = triangles(1, t), c = triangles(2, t);
    const double third =
        0.5 * (rest.col(b) - rest.col(a)).cross(rest.col(c) - rest.col(a)).norm() / 3.0;
    area[a] += third;
    area[b] += third;
    area[c] += third;
  }
  return area;
}

void attach_continuum(const ClothPhysicsSpec& spec, ClothModel& model) {
  if (!spec.continuum) return;
  if (model.triangles.cols() == 0)
    throw std::invalid_argument(
        "model: continuum needs a two-dimensional cloth (a chain has no "
        "triangles)");
  model.continuum = std::make_shared<const ContinuumElements>(build_continuum_elements(
      model.rest_positions, model.triangles, *spec.continuum, held_particles(model)));
}

}  // namespace drapelab::building
