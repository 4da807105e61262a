// Pieces every cloth builder shares (grid_cloth.cpp, mesh_cloth.cpp).
#pragma once

#include <Eigen/Core>

#include "drapelab/cloth_model.hpp"
#include "drapelab/grid_cloth.hpp"

namespace drapelab::building {

// Appends the spring (a, b) of `kind` with its rest length from `rest` (m) and the kind's ks, kd.
void add_spring(SpringSet& springs, const Eigen::Matrix3Xd& rest, int a, int b, SpringKind kind,
                const SpringParams& params);

// One third of the rest area of every triangle incident to each particle (m^2).
Eigen::VectorXd vertex_areas(const Eigen::Matrix3Xd& rest, const Eigen::Matrix3Xi& triangles);

// cloth.model: continuum: builds the membrane and hinge elements when the spec asks for them.
// Throws std::invalid_argument for a cloth without triangles (a chain).
void attach_continuum(const ClothPhysicsSpec& spec, ClothModel& model);

}  // namespace drapelab::building
