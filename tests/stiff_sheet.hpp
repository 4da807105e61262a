// The implicit-Euler tests' cloth: a stiff sheet held at its top corners, upright in the xy plane,
// whose explicit stable step is about 1e-4 s (so a 1/60 s step needs an implicit scheme).
#pragma once

#include "drapelab/grid_cloth.hpp"

namespace drapelab {

inline GridClothSpec stiff_sheet(int nx, int ny) {
  GridClothSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.plane = GridPlane::xy;
  spec.center = {0, 1, 0};
  spec.mass = 0.1;               // kg: 0.44 g per particle at 15 x 15
  spec.stretch = {2.0e4, 0.05};  // N/m, N*s/m: stiff
  spec.shear = {2.0e3, 0.01};
  spec.bend = {50.0, 0.002};
  spec.pins = {PinNamed{"top_corners"}};
  return spec;
}

}  // namespace drapelab
