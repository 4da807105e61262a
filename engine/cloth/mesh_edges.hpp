// The edges of a triangle mesh, each once, as particle pairs with the lower index first, sorted.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace drapelab {

std::vector<std::array<std::int32_t, 2>> mesh_edges(const Eigen::Matrix3Xi& triangles);

}  // namespace drapelab
