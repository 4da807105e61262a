// The OBJ reader's fuzz entry (fuzz_inputs.hpp).
#include <sstream>

#include "drapelab/mesh_cloth.hpp"
#include "drapelab/obj_reader.hpp"
#include "fuzz_inputs.hpp"

namespace drapelab::fuzz {

std::optional<std::string> read_obj_input(std::string_view data) {
  std::istringstream in{std::string(data)};
  const ObjReadResult read = read_obj(in);
  if (!read.mesh) {
    if (read.error.empty()) return "the read failed, yet there is no error message";
    return std::nullopt;
  }
  if (!read.error.empty()) return "the mesh was read with an error: " + read.error;

  const TriangleMesh& mesh = *read.mesh;
  const Eigen::Index vertices = mesh.vertices.cols();
  if (mesh.triangles.cols() == 0) return "the mesh was read without a triangle";
  if (mesh.triangles.minCoeff() < 0 || mesh.triangles.maxCoeff() >= vertices)
    return "a triangle's vertex index is out of range";
  if (mesh.uvs.cols() != 0 && mesh.uvs.cols() != vertices)
    return "the mesh has " + std::to_string(mesh.uvs.cols()) + " UVs for " +
           std::to_string(vertices) + " vertices";
  if (!mesh.vertices.allFinite() || !mesh.uvs.allFinite())
    return "the mesh has a coordinate that is not finite";
  if (mesh_problem(mesh)) return std::nullopt;

  // A mesh without a problem is a cloth: build_mesh_cloth throws only on what mesh_problem finds.
  MeshClothSpec spec;
  spec.mesh = mesh;
  spec.mass = 0.1;
  const ClothModel model = build_mesh_cloth(spec);
  if (model.particle_count() != vertices)
    return "the cloth has " + std::to_string(model.particle_count()) + " particles for " +
           std::to_string(vertices) + " vertices";
  return std::nullopt;
}

}  // namespace drapelab::fuzz
