// Wavefront OBJ to TriangleMesh (obj_reader.hpp).
#include "drapelab/obj_reader.hpp"

#include <cmath>
#include <sstream>
#include <vector>

#include "drapelab/bounded_file.hpp"
#include "drapelab/cloth_limits.hpp"

namespace drapelab {
namespace {

struct Corner {
  int vertex = -1;  // 0-based
  int uv = -1;      // 0-based, -1 when absent
};

// An OBJ index (1-based, or negative from the end) to 0-based, or nullopt when out of range.
std::optional<int> resolve_index(long long index, std::size_t count) {
  const long long n = static_cast<long long>(count);
  const long long resolved = index > 0 ? index - 1 : n + index;
  if (index == 0 || resolved < 0 || resolved >= n) return std::nullopt;
  return static_cast<int>(resolved);
}

bool parse_integer(const std::string& text, long long& value) {
  if (text.empty()) return false;
  std::size_t used = 0;
  try {
    value = std::stoll(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == text.size();
}

}  // namespace

ObjReadResult read_obj(std::istream& in) {
  ObjReadResult result;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector2d> uvs;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<int> vertex_uv;  // per vertex, the uv index the first face gave it
  auto fail = [&](int line, std::string message) {
    result.mesh.reset();
    result.error_line = line;
    result.error = std::move(message);
    return result;
  };
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    if (const auto hash = text.find('#'); hash != std::string::npos) text.erase(hash);
    std::istringstream words(text);
    std::string tag;
    if (!(words >> tag)) continue;
    if (tag == "v" || tag == "vt") {
      const int needed = tag == "v" ? 3 : 2;
      double value[3] = {0, 0, 0};
      for (int c = 0; c < needed; ++c) {
        std::string word;
        if (!(words >> word))
          return fail(line, "'" + tag + "' needs " + std::to_string(needed) + " numbers");
        try {
          std::size_t used = 0;
          value[c] = std::stod(word, &used);
          if (used != word.size()) throw std::invalid_argument(word);
        } catch (const std::exception&) {
          return fail(line, "'" + word + "' is not a number");
        }
        if (!std::isfinite(value[c])) return fail(line, "'" + word + "' is not a finite number");
      }
      if (vertices.size() + uvs.size() >= static_cast<std::size_t>(2 * kMaxClothParticles))
        return fail(line, "more than " + std::to_string(2 * kMaxClothParticles) +
                              " vertices and texture coordinates; a cloth has at most " +
                              std::to_string(kMaxClothParticles) + " particles");
      if (tag == "v")
        vertices.emplace_back(value[0], value[1], value[2]);
      else
        uvs.emplace_back(value[0], value[1]);
      continue;
    }
    if (tag != "f") continue;  // vn, o, g, s, usemtl, mtllib, l, ...: not needed for a cloth
    std::vector<Corner> corners;
    std::string word;
    while (words >> word) {
      Corner corner;
      const std::size_t slash = word.find('/');
      long long index = 0;
      if (!parse_integer(word.substr(0, slash), index))
        return fail(line, "face corner '" + word + "' does not start with a vertex index");
      const auto vertex = resolve_index(index, vertices.size());
      if (!vertex)
        return fail(line, "face uses vertex " + std::to_string(index) + " but " +
                              std::to_string(vertices.size()) + " vertices are defined so far");
      corner.vertex = *vertex;
      if (slash != std::string::npos) {
        const std::string rest = word.substr(slash + 1);
        const std::string uv_text = rest.substr(0, rest.find('/'));
        if (!uv_text.empty()) {
          if (!parse_integer(uv_text, index))
            return fail(line, "face corner '" + word + "' has a bad texture index");
          const auto uv = resolve_index(index, uvs.size());
          if (!uv)
            return fail(line, "face uses texture coordinate " + std::to_string(index) + " but " +
                                  std::to_string(uvs.size()) + " are defined so far");
          corner.uv = *uv;
        }
      }
      corners.push_back(corner);
    }
    if (corners.size() < 3)
      return fail(line, "a face needs at least 3 corners, got " + std::to_string(corners.size()));
    vertex_uv.resize(vertices.size(), -1);
    for (const Corner& c : corners)
      if (c.uv >= 0 && vertex_uv[static_cast<std::size_t>(c.vertex)] < 0)
        vertex_uv[static_cast<std::size_t>(c.vertex)] = c.uv;
    if (triangles.size() + corners.size() - 2 > static_cast<std::size_t>(kMaxClothTriangles))
      return fail(line, "the faces so far give more than " + std::to_string(kMaxClothTriangles) +
                            " triangles, the most a cloth may have");
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      triangles.emplace_back(corners[0].vertex, corners[k].vertex, corners[k + 1].vertex);
  }
  if (in.bad()) return fail(0, "the file could not be read");
  if (vertices.empty()) return fail(0, "no vertices ('v' lines)");
  if (triangles.empty()) return fail(0, "no faces ('f' lines)");

  TriangleMesh mesh;
  mesh.vertices.resize(3, static_cast<Eigen::Index>(vertices.size()));
  for (std::size_t i = 0; i < vertices.size(); ++i)
    mesh.vertices.col(static_cast<Eigen::Index>(i)) = vertices[i];
  mesh.triangles.resize(3, static_cast<Eigen::Index>(triangles.size()));
  for (std::size_t t = 0; t < triangles.size(); ++t)
    mesh.triangles.col(static_cast<Eigen::Index>(t)) = triangles[t];
  vertex_uv.resize(vertices.size(), -1);
  bool every_vertex_has_uv = !uvs.empty();
  for (int uv : vertex_uv) every_vertex_has_uv = every_vertex_has_uv && uv >= 0;
  if (every_vertex_has_uv) {
    mesh.uvs.resize(2, static_cast<Eigen::Index>(vertices.size()));
    for (std::size_t i = 0; i < vertices.size(); ++i)
      mesh.uvs.col(static_cast<Eigen::Index>(i)) = uvs[static_cast<std::size_t>(vertex_uv[i])];
  }
  result.mesh = std::move(mesh);
  return result;
}

ObjReadResult read_obj_file(const std::filesystem::path& path) {
  BoundedFile file = read_bounded_file(path, kMaxObjFileBytes);
  if (!file.ok) {
    ObjReadResult result;
    result.error = file.error;
    return result;
  }
  std::istringstream stream(std::move(file.text));
  return read_obj(stream);
}

}  // namespace drapelab
