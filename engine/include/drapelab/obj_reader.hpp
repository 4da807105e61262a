// Reading a triangle mesh from a Wavefront OBJ file: `v x y z` vertices (m), optional `vt u v`
// texture coordinates, `f` faces (v, v/vt, v//vn or v/vt/vn corners, negative indices counted from
// the end, polygons split into a fan of triangles). Normals, groups, objects, materials, smoothing
// groups and lines are ignored. A vertex's UV is the first `vt` a face gives it (a seam keeps one
// side's); without any `vt` the mesh has no UVs. A file is read only when it is a regular file of
// at most kMaxObjFileBytes, and reading stops with an error past the cloth limits of
// cloth_limits.hpp (vertices, triangles).
#pragma once

#include <cstdint>
#include <filesystem>
#include <istream>
#include <optional>
#include <string>

#include "drapelab/bounded_file.hpp"
#include "drapelab/mesh_cloth.hpp"

namespace drapelab {

inline constexpr std::uintmax_t kMaxObjFileBytes = kMaxInputFileBytes;  // bytes (64 MB)

struct ObjReadResult {
  std::optional<TriangleMesh> mesh;
  int error_line = 0;  // 1-based line of the problem (0: the file as a whole)
  std::string error;   // what is wrong and what was expected
};

ObjReadResult read_obj(std::istream& in);
ObjReadResult read_obj_file(const std::filesystem::path& path);

}  // namespace drapelab
