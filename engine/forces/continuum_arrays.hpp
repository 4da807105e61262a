// The continuum elements (drapelab/continuum.hpp) seen as the plain arrays of continuum_loops.hpp.
#pragma once

#include "drapelab/continuum.hpp"
#include "forces/continuum_loops.hpp"

namespace drapelab {

// A view: valid while `elements` lives.
inline kernels::ContinuumArrays continuum_arrays(const ContinuumElements& elements) {
  kernels::ContinuumArrays c;
  c.particles = static_cast<std::int64_t>(elements.triangle_offsets.size()) - 1;
  c.mu = elements.lame.mu;
  c.lambda = elements.lame.lambda;
  c.alpha = elements.params.damping;
  c.triangles = static_cast<std::int64_t>(elements.triangle.size());
  c.triangle = elements.triangle.empty() ? nullptr : elements.triangle.front().data();
  c.shape_gradient = elements.shape_gradient.data();
  c.rest_area = elements.rest_area.data();
  c.hinges = static_cast<std::int64_t>(elements.hinge.size());
  c.hinge = elements.hinge.empty() ? nullptr : elements.hinge.front().data();
  c.hinge_triangle =
      elements.hinge_triangle.empty() ? nullptr : elements.hinge_triangle.front().data();
  c.hinge_second_sign = elements.hinge_second_sign.data();
  c.hinge_stiffness = elements.hinge_stiffness.data();
  c.rest_angle = elements.rest_angle.data();
  for (int k = 0; k < 3; ++k) c.triangle_corner[k] = elements.columns.triangle_corner[k].data();
  for (int k = 0; k < 4; ++k) c.gradient[k] = elements.columns.gradient[k].data();
  for (int k = 0; k < 4; ++k) c.hinge_corner[k] = elements.columns.hinge_corner[k].data();
  for (int k = 0; k < 2; ++k) c.hinge_wing[k] = elements.columns.hinge_triangle[k].data();
  c.families = elements.families.get();
  c.triangle_offsets = elements.triangle_offsets.data();
  c.triangle_of = elements.triangle_of.data();
  c.triangle_slot = elements.triangle_slot.data();
  c.hinge_offsets = elements.hinge_offsets.data();
  c.hinge_of = elements.hinge_of.data();
  c.hinge_slot = elements.hinge_slot.data();
  return c;
}

}  // namespace drapelab
