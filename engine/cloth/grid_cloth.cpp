// Grid cloth: particles on a lattice, springs between lattice neighbours, pins by selector.
#include "drapelab/grid_cloth.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <random>
#include <stdexcept>

#include "cloth/cloth_building.hpp"
#include "drapelab/cloth_limits.hpp"
#include "drapelab/collider.hpp"

namespace drapelab {
namespace {

using building::add_spring;
using building::vertex_areas;

int grid_index(int nx, int i, int j) { return j * nx + i; }

Eigen::Vector3d second_axis(GridPlane plane) {
  return plane == GridPlane::xz ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
}

Eigen::Vector3d sheet_normal(GridPlane plane) {
  return plane == GridPlane::xz ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ();
}

// Stretch springs join lattice neighbours, shear springs both diagonals of a cell, bend springs
// particles two apart along a lattice line. Counts: stretch nx(ny-1) + ny(nx-1), shear
// 2(nx-1)(ny-1), bend nx(ny-2) + ny(nx-2) (negative terms count as zero).
SpringSet build_grid_springs(const GridClothSpec& spec, const Eigen::Matrix3Xd& rest) {
  const int nx = spec.nx, ny = spec.ny;
  SpringSet springs;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int k = grid_index(nx, i, j);
      if (i + 1 < nx)
        add_spring(springs, rest, k, grid_index(nx, i + 1, j), SpringKind::stretch, spec.stretch);
      if (j + 1 < ny)
        add_spring(springs, rest, k, grid_index(nx, i, j + 1), SpringKind::stretch, spec.stretch);
    }
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      add_spring(springs, rest, grid_index(nx, i, j), grid_index(nx, i + 1, j + 1),
                 SpringKind::shear, spec.shear);
      add_spring(springs, rest, grid_index(nx, i + 1, j), grid_index(nx, i, j + 1),
                 SpringKind::shear, spec.shear);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int k = grid_index(nx, i, j);
      if (i + 2 < nx)
        add_spring(springs, rest, k, grid_index(nx, i + 2, j), SpringKind::bend, spec.bend);
      if (j + 2 < ny)
        add_spring(springs, rest, k, grid_index(nx, i, j + 2), SpringKind::bend, spec.bend);
    }
  return springs;
}

// Two triangles per cell, wound counter-clockwise about the sheet normal. With springs every cell
// is split along the same diagonal (i, j)-(i+1, j+1). With the continuum model the diagonal turns
// from one row of cells to the next: on a single diagonal direction the hinges couple bending to
// twist (a sheet bent along x twists, and a strip bends as if 0.8 times as rigid at most), and
// turning it every row cancels that coupling while every interior particle still touches six
// triangles and gets one cell of vertex area (a checkerboard of diagonals would give 4/3 and 2/3
// of a cell, and bends strips measurably softer than rows do: docs/physics.md).
Eigen::Matrix3Xi build_grid_triangles(const GridClothSpec& spec, const Eigen::Matrix3Xd& rest) {
  const int nx = spec.nx, ny = spec.ny;
  const int cells = std::max(0, nx - 1) * std::max(0, ny - 1);
  Eigen::Matrix3Xi triangles(3, 2 * cells);
  const Eigen::Vector3d normal = euler_rotation(spec.rotation) * sheet_normal(spec.plane);
  const bool turn_by_row = spec.continuum.has_value();
  int t = 0;
  auto emit = [&](int a, int b, int c) {
    const Eigen::Vector3d n = (rest.col(b) - rest.col(a)).cross(rest.col(c) - rest.col(a));
    if (n.dot(normal) < 0.0) std::swap(b, c);
    triangles.col(t++) << a, b, c;
  };
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int k00 = grid_index(nx, i, j), k10 = grid_index(nx, i + 1, j);
      const int k01 = grid_index(nx, i, j + 1), k11 = grid_index(nx, i + 1, j + 1);
      if (turn_by_row && j % 2 == 1) {  // the other diagonal, (i+1, j)-(i, j+1)
        emit(k00, k10, k01);
        emit(k10, k11, k01);
      } else {
        emit(k00, k10, k11);
        emit(k00, k11, k01);
      }
    }
  return triangles;
}

std::vector<int> all_matching(const GridClothSpec& spec, auto&& predicate) {
  std::vector<int> picked;
  for (int j = 0; j < spec.ny; ++j)
    for (int i = 0; i < spec.nx; ++i)
      if (predicate(i, j)) picked.push_back(grid_index(spec.nx, i, j));
  return picked;
}

std::vector<int> select_named(const GridClothSpec& spec, const std::string& name,
                              std::string* error) {
  const int last_i = spec.nx - 1, last_j = spec.ny - 1;
  const bool xz = spec.plane == GridPlane::xz;
  if (name == "corners")
    return all_matching(
        spec, [&](int i, int j) { return (i == 0 || i == last_i) && (j == 0 || j == last_j); });
  if (name ==
      "top_corners")  // greatest y (vertical sheet) or greatest z (horizontal sheet): j = ny-1
    return all_matching(spec, [&](int i, int j) { return (i == 0 || i == last_i) && j == last_j; });
  if (name == "edge_min_x") return all_matching(spec, [&](int i, int) { return i == 0; });
  if (name == "edge_max_x") return all_matching(spec, [&](int i, int) { return i == last_i; });
  if (name == (xz ? "edge_min_z" : "edge_min_y"))
    return all_matching(spec, [&](int, int j) { return j == 0; });
  if (name == (xz ? "edge_max_z" : "edge_max_y"))
    return all_matching(spec, [&](int, int j) { return j == last_j; });
  if (name == "center") {
    // The particle nearest the sheet's centre; ties go to the lowest index.
    int best = 0;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) {
        const double distance = (grid_rest_position(spec, i, j) - spec.center).squaredNorm();
        if (distance < best_distance - 1e-15) {
          best_distance = distance;
          best = grid_index(spec.nx, i, j);
        }
      }
    return {best};
  }
  if (error) {
    *error = "unknown pin set '" + name + "'; expected one of:";
    for (const auto& valid : pin_set_names(spec.plane)) *error += " " + valid;
  }
  return {};
}

}  // namespace

std::vector<std::string> pin_set_names(GridPlane plane) {
  if (plane == GridPlane::xz)
    return {"corners",    "top_corners", "edge_min_x", "edge_max_x",
            "edge_min_z", "edge_max_z",  "center"};
  return {"corners",    "top_corners", "edge_min_x", "edge_max_x",
          "edge_min_y", "edge_max_y",  "center"};
}

Eigen::Vector3d grid_rest_position(const GridClothSpec& spec, int i, int j) {
  // A side with a single particle sits at the centre on that axis.
  const double u = spec.nx > 1 ? static_cast<double>(i) / (spec.nx - 1) - 0.5 : 0.0;
  const double w = spec.ny > 1 ? static_cast<double>(j) / (spec.ny - 1) - 0.5 : 0.0;
  const Eigen::Vector3d offset =
      u * spec.size.x() * Eigen::Vector3d::UnitX() + w * spec.size.y() * second_axis(spec.plane);
  return spec.center + euler_rotation(spec.rotation) * offset;
}

std::vector<int> select_pins(const GridClothSpec& spec, const PinSelector& selector,
                             std::string* error) {
  if (const auto* named = std::get_if<PinNamed>(&selector))
    return select_named(spec, named->name, error);
  if (const auto* coord = std::get_if<PinGridCoord>(&selector)) {
    if (coord->i < 0 || coord->i >= spec.nx || coord->j < 0 || coord->j >= spec.ny) {
      if (error)
        *error = "grid coordinate [" + std::to_string(coord->i) + ", " + std::to_string(coord->j) +
                 "] is outside the " + std::to_string(spec.nx) + " x " + std::to_string(spec.ny) +
                 " grid (i in 0.." + std::to_string(spec.nx - 1) + ", j in 0.." +
                 std::to_string(spec.ny - 1) + ")";
      return {};
    }
    return {grid_index(spec.nx, coord->i, coord->j)};
  }
  if (const auto* index = std::get_if<PinIndex>(&selector)) {
    const int count = spec.nx * spec.ny;
    if (index->index < 0 || index->index >= count) {
      if (error)
        *error = "particle index " + std::to_string(index->index) + " is outside 0.." +
                 std::to_string(count - 1);
      return {};
    }
    return {index->index};
  }
  const auto& ball = std::get<PinWithin>(selector);
  auto picked = all_matching(spec, [&](int i, int j) {
    return (grid_rest_position(spec, i, j) - ball.center).norm() <= ball.radius;
  });
  if (picked.empty() && error) *error = "no particle lies within the ball (rest positions)";
  return picked;
}

ClothModel build_grid_cloth(const GridClothSpec& spec) {
  if (spec.nx < 1 || spec.ny < 1 || static_cast<long long>(spec.nx) * spec.ny < 2)
    throw std::invalid_argument("grid cloth needs nx, ny >= 1 and at least 2 particles");
  if (const auto problem = cloth_size_problem(grid_cloth_size(spec.nx, spec.ny)))
    throw std::invalid_argument("the grid " + *problem);
  if (spec.mass.has_value() == spec.areal_density.has_value())
    throw std::invalid_argument("grid cloth needs exactly one of mass and areal_density");

  ClothModel model;
  const int count = spec.nx * spec.ny;
  model.grid = {spec.nx, spec.ny};
  model.thickness = spec.thickness;
  model.rest_positions.resize(3, count);
  model.uvs.resize(2, count);
  for (int j = 0; j < spec.ny; ++j)
    for (int i = 0; i < spec.nx; ++i) {
      const int k = grid_index(spec.nx, i, j);
      model.rest_positions.col(k) = grid_rest_position(spec, i, j);
      model.uvs(0, k) = spec.nx > 1 ? static_cast<double>(i) / (spec.nx - 1) : 0.5;
      model.uvs(1, k) = spec.ny > 1 ? static_cast<double>(j) / (spec.ny - 1) : 0.5;
    }
  model.triangles = build_grid_triangles(spec, model.rest_positions);
  model.vertex_area = vertex_areas(model.rest_positions, model.triangles);
  model.springs = build_grid_springs(spec, model.rest_positions);

  if (spec.mass) {
    model.mass = Eigen::VectorXd::Constant(count, *spec.mass / count);
  } else {
    if (model.triangles.cols() == 0)
      throw std::invalid_argument(
          "areal_density needs a two-dimensional cloth (a chain has no area)");
    model.mass = *spec.areal_density * model.vertex_area;
  }
  model.inverse_mass = model.mass.cwiseInverse();
  for (const auto& selector : spec.pins) {
    std::string error;
    const auto picked = select_pins(spec, selector, &error);
    if (picked.empty()) throw std::invalid_argument("pin selector: " + error);
    for (int k : picked) model.inverse_mass[k] = 0.0;
  }
  building::attach_continuum(spec, model);
  return model;
}

ClothState initial_grid_state(const ClothModel& model, const GridClothSpec& spec, double amplitude,
                              std::uint64_t seed) {
  ClothState state;
  state.x = model.rest_positions;
  state.v = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  if (amplitude > 0.0) {
    // mt19937_64 is specified bit for bit; the mapping to [-1, 1) is ours, so runs are reproducible
    // across standard libraries (std::uniform_real_distribution is not).
    std::mt19937_64 random(seed);
    const Eigen::Vector3d normal = euler_rotation(spec.rotation) * sheet_normal(spec.plane);
    for (int k = 0; k < model.particle_count(); ++k) {
      const double unit = static_cast<double>(random() >> 11) * 0x1.0p-53;  // [0, 1)
      if (!model.is_pinned(k)) state.x.col(k) += amplitude * (2.0 * unit - 1.0) * normal;
    }
  }
  return state;
}

}  // namespace drapelab
