// Stacked sheets and the frame loop of the self-collision suites (layered_cloth.hpp).
#include "layered_cloth.hpp"

#include <cmath>
#include <stdexcept>

namespace drapelab::fixtures {

ClothModel stacked_cloth(const std::vector<GridClothSpec>& sheets) {
  std::vector<ClothModel> parts;
  int particles = 0, triangles = 0;
  for (const GridClothSpec& spec : sheets) {
    parts.push_back(build_grid_cloth(spec));
    particles += parts.back().particle_count();
    triangles += static_cast<int>(parts.back().triangles.cols());
  }
  ClothModel all;
  all.rest_positions.resize(3, particles);
  all.mass.resize(particles);
  all.inverse_mass.resize(particles);
  all.vertex_area.resize(particles);
  all.uvs.resize(2, particles);
  all.triangles.resize(3, triangles);
  all.thickness = parts.front().thickness;
  int p0 = 0, t0 = 0;
  for (const ClothModel& part : parts) {
    if (part.thickness != all.thickness) throw std::invalid_argument("sheets of two thicknesses");
    const int n = part.particle_count();
    const auto t = static_cast<int>(part.triangles.cols());
    all.rest_positions.middleCols(p0, n) = part.rest_positions;
    all.mass.segment(p0, n) = part.mass;
    all.inverse_mass.segment(p0, n) = part.inverse_mass;
    all.vertex_area.segment(p0, n) = part.vertex_area;
    all.uvs.middleCols(p0, n) = part.uvs;
    all.triangles.middleCols(t0, t) = part.triangles.array() + p0;
    const SpringSet& s = part.springs;
    for (std::size_t e = 0; e < s.size(); ++e) {
      all.springs.v0.push_back(s.v0[e] + p0);
      all.springs.v1.push_back(s.v1[e] + p0);
      all.springs.rest_length.push_back(s.rest_length[e]);
      all.springs.ks.push_back(s.ks[e]);
      all.springs.kd.push_back(s.kd[e]);
      all.springs.kind.push_back(s.kind[e]);
    }
    p0 += n;
    t0 += t;
  }
  return all;
}

void run_frames(SpringDamperSolver& solver, double duration, double h, double frame,
                const std::function<void(const ClothState&)>& each_frame) {
  each_frame(solver.state());
  const int steps_per_frame = static_cast<int>(std::lround(frame / h));
  const int frames = static_cast<int>(std::lround(duration / frame));
  for (int f = 0; f < frames && solver.status() == SolverStatus::ok; ++f) {
    for (int k = 0; k < steps_per_frame && solver.status() == SolverStatus::ok; ++k) solver.step(h);
    each_frame(solver.state());
  }
}

}  // namespace drapelab::fixtures
