// A run folder read back for drawing: the scene (resolved.yaml), the cloth's topology and UVs
// (scene::build_scene_cloth), the solvers in summary.json's order, each one's positions per
// recorded frame from its point cache (meshes/SOLVER.pc2) or per-frame OBJ files
// (meshes/SOLVER_NNNN.obj), and the legend values of metrics.csv.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/scene/scene.hpp"

namespace drapelab::render {

// A run folder that cannot be rendered as it is (exit code 2): the message says what to do.
class RunInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Positions of one solver's cloth at its recorded frames (frame 0 = the initial state).
class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual int frame_count() const = 0;  // frames recorded, frame 0 included
  virtual Eigen::Matrix3Xd positions(
      int frame) const = 0;                     // m, 3 x particles; throws if unreadable
  virtual std::string description() const = 0;  // "meshes/ours.pc2"
};

// PC2 point cache as tools/runner/src/mesh_output.cpp writes it (float32, little endian). The
// sample count is the header's, or fewer if the file is shorter (a run still being written).
std::unique_ptr<FrameSource> open_point_cache(const std::filesystem::path& file,
                                              int particle_count);
// SOLVER_0000.obj, SOLVER_0001.obj, ... in `folder`: the frames run while the files are
// consecutive.
std::unique_ptr<FrameSource> open_obj_sequence(const std::filesystem::path& folder,
                                               const std::string& solver, int particle_count);

// The legend's numbers for one solver at one frame, from metrics.csv.
struct FrameMetrics {
  double time = 0.0;                        // s
  std::optional<double> max_stretch;        // fraction (0.01 = 1 %)
  std::optional<double> drape_coefficient;  // empty unless the scene names a drape support
};

// Collider index -> the pose (collider frame -> world) one solver's body has at one frame.
using BodyPoses = std::map<int, Eigen::Isometry3d>;

struct SolverFrames {
  std::string name;
  std::string type;          // spring_damper, bullet_softbody, bullet_deformable, mujoco
  std::string status;        // ok, unstable, error (summary.json)
  int frames_recorded = -1;  // summary.json's frames_recorded (frame 0 included); -1 when absent
  std::unique_ptr<FrameSource> source;
  std::map<int, FrameMetrics> metrics;  // by frame; empty when metrics.csv is missing
  // Where this solver's dynamic colliders are (bodies.csv), by frame, then by collider index in the
  // scene; empty without dynamic colliders.
  std::map<int, BodyPoses> bodies;
};

struct RunFrames {
  std::filesystem::path dir;
  scene::Scene scene;
  ClothModel model;
  std::vector<SolverFrames> solvers;  // in summary.json's order
  int frame_count = 0;                // frames to render: the most any solver recorded (0 included)
};

// Reads a run folder. Throws RunInputError when it is not a run folder, its resolved.yaml does not
// load, a solver has neither a point cache nor per-frame OBJ files (the message says to run with
// --meshes pc2), or a point cache or OBJ sequence holds fewer frames than its header or
// summary.json says (a cut file); std::runtime_error for unreadable files.
RunFrames load_run_frames(const std::filesystem::path& dir);

}  // namespace drapelab::render
