// Mesh outputs of a run: rest.obj (positions, UVs, triangles), per-frame OBJ files, and a .pc2 point
// cache (Blender's Mesh Cache modifier reads it onto rest.obj; vertex order is particle order).
#pragma once

#include <Eigen/Core>
#include <cstdio>
#include <filesystem>
#include <string>

#include "drapelab/cloth_model.hpp"

namespace drapelab::runner {

// OBJ with one vertex and one texture coordinate per particle (v/vt share the index, so importers
// keep the vertex order), faces from the model's triangles, and polylines along a chain.
void write_obj(const std::filesystem::path& path, const ClothModel& model, const Eigen::Matrix3Xd& x,
               const std::string& comment);

// PC2 point cache: "POINTCACHE2\0", int32 version 1, int32 points, float32 start frame, float32
// sample rate (frames), int32 samples, then per sample points x 3 float32, little endian. The sample
// count in the header is rewritten after every frame, so the file is valid whenever it is read.
class Pc2Writer {
 public:
  Pc2Writer(const std::filesystem::path& path, int point_count);
  ~Pc2Writer();
  Pc2Writer(const Pc2Writer&) = delete;
  Pc2Writer& operator=(const Pc2Writer&) = delete;
  void append(const Eigen::Matrix3Xd& x);
  int sample_count() const { return samples_; }

 private:
  std::FILE* file_ = nullptr;
  int points_ = 0;
  int samples_ = 0;
};

}  // namespace drapelab::runner
