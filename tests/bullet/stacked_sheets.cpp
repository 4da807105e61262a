#include "stacked_sheets.hpp"

#include "drapelab/grid_cloth.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab::fixtures {
namespace {

template <typename Matrix>
Matrix stack_columns(const Matrix& a, const Matrix& b) {
  Matrix out(a.rows(), a.cols() + b.cols());
  out << a, b;
  return out;
}

Eigen::VectorXd stack(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  Eigen::VectorXd out(a.size() + b.size());
  out << a, b;
  return out;
}

// One model of both sheets: b's particle indices move up by a's particle count.
ClothModel join(const ClothModel& a, const ClothModel& b) {
  ClothModel out;
  const int offset = a.particle_count();
  out.rest_positions = stack_columns(a.rest_positions, b.rest_positions);
  out.mass = stack(a.mass, b.mass);
  out.inverse_mass = stack(a.inverse_mass, b.inverse_mass);
  out.vertex_area = stack(a.vertex_area, b.vertex_area);
  out.triangles = stack_columns(a.triangles, Eigen::Matrix3Xi(b.triangles.array() + offset));
  out.uvs = stack_columns(a.uvs, b.uvs);
  out.springs = a.springs;
  for (std::size_t e = 0; e < b.springs.size(); ++e) {
    out.springs.v0.push_back(b.springs.v0[e] + offset);
    out.springs.v1.push_back(b.springs.v1[e] + offset);
    out.springs.rest_length.push_back(b.springs.rest_length[e]);
    out.springs.ks.push_back(b.springs.ks[e]);
    out.springs.kd.push_back(b.springs.kd[e]);
    out.springs.kind.push_back(b.springs.kind[e]);
  }
  out.thickness = a.thickness;
  return out;  // grid stays {0, 0}: not one grid
}

}  // namespace

StackedSheets stacked_sheets(int n, double size, double mass, double bottom_height, double gap,
                             bool top_upside_down) {
  GridClothSpec bottom =
      with_springs(flat_sheet(n, size, {0.0, bottom_height, 0.0}, mass), kUndampedSprings);
  GridClothSpec top = bottom;
  top.size *= 0.8;  // every top particle lies over the bottom sheet
  top.center.y() += gap;
  if (top_upside_down) top.rotation = {180.0, 0.0, 0.0};
  const ClothModel bottom_model = build_grid_cloth(bottom);
  StackedSheets out;
  out.model = std::make_shared<const ClothModel>(join(bottom_model, build_grid_cloth(top)));
  out.bottom_count = bottom_model.particle_count();
  out.initial.x = out.model->rest_positions;
  out.initial.v = Eigen::Matrix3Xd::Zero(3, out.model->particle_count());
  return out;
}

double mean_layer_gap(const StackedSheets& sheets, const ClothState& state) {
  const int n = static_cast<int>(state.x.cols());
  const Eigen::VectorXd y = state.x.row(1).transpose();
  return y.tail(n - sheets.bottom_count).mean() - y.head(sheets.bottom_count).mean();
}

double lowest_top_above_highest_bottom(const StackedSheets& sheets, const ClothState& state) {
  const int n = static_cast<int>(state.x.cols());
  const Eigen::VectorXd y = state.x.row(1).transpose();
  return y.tail(n - sheets.bottom_count).minCoeff() - y.head(sheets.bottom_count).maxCoeff();
}

}  // namespace drapelab::fixtures
