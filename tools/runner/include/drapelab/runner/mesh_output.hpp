// Mesh outputs of a run: rest.obj (positions, UVs, triangles) and per-frame OBJ files. Point caches
// and the files' names belong to the run folder (drapelab/run_folder/point_cache.hpp).
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>

#include "drapelab/cloth_model.hpp"

namespace drapelab::runner {

// OBJ with one vertex and one texture coordinate per particle (v/vt share the index, so importers
// keep the vertex order), faces from the model's triangles, and polylines along a chain. Throws
// run_folder::WriteError; a file not written whole is removed.
void write_obj(const std::filesystem::path& path, const ClothModel& model,
               const Eigen::Matrix3Xd& x, const std::string& comment);

}  // namespace drapelab::runner
