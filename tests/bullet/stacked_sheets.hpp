// Two square sheets stacked in one cloth model, for self-collision tests: the bottom sheet's
// particles come first, the top sheet's after them. Bullet's self-collision acts within one soft
// body, so both sheets are one cloth.
#pragma once

#include <memory>

#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"

namespace drapelab::fixtures {

struct StackedSheets {
  std::shared_ptr<const ClothModel> model;
  ClothState initial;    // at rest in the stacked pose
  int bottom_count = 0;  // particles [0, bottom_count) are the bottom sheet's
};

// An n x n bottom sheet `size` m wide at height `bottom_height` (m) and an n x n top sheet 0.8 x
// `size` wide `gap` m above it, both horizontal, centred on the y axis, `mass` kg each, with
// kUndampedSprings. `top_upside_down` turns the top sheet over (its triangles face down, as the
// upper layer of a folded cloth does); otherwise both face up.
StackedSheets stacked_sheets(int n, double size, double mass, double bottom_height, double gap,
                             bool top_upside_down);

// Mean height of the top sheet above the bottom sheet (m).
double mean_layer_gap(const StackedSheets& sheets, const ClothState& state);

// The lowest top-sheet particle's height above the highest bottom-sheet particle (m); negative
// when some top particle lies below some bottom particle.
double lowest_top_above_highest_bottom(const StackedSheets& sheets, const ClothState& state);

}  // namespace drapelab::fixtures
