// Cloths for the self-collision suites: sheets stacked as one cloth model, and a runner that
// steps our solver and audits every frame.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/spring_damper_solver.hpp"

namespace drapelab::fixtures {

// The sheets as one cloth: particles, triangles and springs of each in turn (indices offset), no
// grid layout. Every sheet must have the same thickness.
ClothModel stacked_cloth(const std::vector<GridClothSpec>& sheets);

// Steps `solver` for `duration` s in steps of `h` and calls `each_frame` every `frame` s (and at
// the start) with the state; stops early when the solver is not ok.
void run_frames(SpringDamperSolver& solver, double duration, double h, double frame,
                const std::function<void(const ClothState&)>& each_frame);

}  // namespace drapelab::fixtures
