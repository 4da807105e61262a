// What the stability and study verbs share: loading the scene with --set and --duration, choosing
// the solver they vary, and steps that divide the frame period into whole steps.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/scene/scene.hpp"

namespace drapelab::runner {

// Loads the scene with the overrides, plus duration=S when `duration` > 0 (validated like the file:
// duration x frame_rate must be whole). Prints every error to stderr and returns nothing on bad
// input. `model`, when given, receives the cloth the loader built (for build_scene_setup).
std::optional<scene::Scene> load_trial_scene(const std::string& file,
                                             std::vector<std::string> overrides, double duration,
                                             std::shared_ptr<const ClothModel>* model = nullptr);

// The solver named `name`; without a name, the first spring_damper solver, else the first solver.
// With `spring_damper_only`, other types are refused; so is a solver with adaptive substeps (the
// verbs that choose a solver vary its step, which such a solver overrides). Returns its index, or
// nothing with `error` set to a message that names what was expected (the scene's solvers and their
// types).
std::optional<std::size_t> choose_solver(const scene::Scene& scene, const std::string& name,
                                         bool spring_damper_only, std::string* error);

// Steps per frame for a step h (s) when h divides the frame period into whole steps (within 1e-9
// relative, the loader's rule), else nothing.
std::optional<int> whole_steps_per_frame(double frame_period, double h);

// The spec with the step frame_period / steps_per_frame.
scene::SolverSpec with_steps_per_frame(scene::SolverSpec spec, double frame_period,
                                       int steps_per_frame);

}  // namespace drapelab::runner
