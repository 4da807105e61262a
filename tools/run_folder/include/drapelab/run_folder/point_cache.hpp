// The run folder's meshes/: per-solver PC2 point caches (Blender's Mesh Cache modifier reads them
// onto the frame-0 OBJ, docs/outputs.md; vertex order is particle order, the first sample frame 0)
// and the names of the per-frame OBJ files. PC2:
// "POINTCACHE2\0", int32 version 1, int32 points, float32 start frame, float32 sample rate
// (frames), int32 samples, then per sample points x 3 float32, little endian.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "drapelab/run_folder/output_file.hpp"

namespace drapelab::run_folder {

// "SOLVER.pc2" and "SOLVER_NNNN.obj" (frame with four digits), inside meshes/.
std::string point_cache_name(const std::string& solver);
std::string obj_frame_name(const std::string& solver, int frame);

// Writes a point cache a frame at a time. The sample count in the header is rewritten after every
// frame, so the file is valid whenever it is read; commit() marks the samples so far complete and
// rollback() cuts the file back to them after a write error. Writes throw WriteError.
class Pc2Writer {
 public:
  Pc2Writer(const std::filesystem::path& path, int point_count);
  void append(const Eigen::Matrix3Xd& x);  // m, 3 x points
  void commit();
  bool rollback() noexcept;
  int sample_count() const { return samples_; }

 private:
  OutputFile file_;
  int points_ = 0;
  int samples_ = 0;            // in the file
  int committed_samples_ = 0;  // at the last commit
};

struct Pc2Header {
  int points = 0;
  int samples = 0;  // whole samples in the file: the header's count, capped by the file's size
};
// The header of a PC2 file; nullopt when the file cannot be read or is not PC2 version 1.
std::optional<Pc2Header> read_pc2_header(const std::filesystem::path& path);
// Sample `frame` of a point cache of `points` points (m, 3 x points); nullopt when it cannot be
// read.
std::optional<Eigen::Matrix3Xd> read_pc2_frame(const std::filesystem::path& path, int points,
                                               int frame);

}  // namespace drapelab::run_folder
