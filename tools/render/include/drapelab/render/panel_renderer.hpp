// Draws one panel with fixed-function GL: a background gradient, the colliders posed at the frame's
// time (collider_pose), and the cloth textured through the model's UVs and shaded with per-vertex
// normals, lit on both sides. Every panel of a frame uses the same camera and lights.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/render/camera.hpp"
#include "drapelab/render/collider_meshes.hpp"
#include "drapelab/render/image.hpp"
#include "drapelab/render/run_frames.hpp"
#include "drapelab/scene/scene.hpp"

namespace drapelab::render {

// What the default camera frames: the cloth at up to `samples` frames spread over the run (of every
// solver whose status is ok; the others only at frame 0, so an exploded cloth does not shrink the
// view) and the solid colliders posed at the same times. Planes are left out (they are unbounded).
Bounds framing_bounds(const RunFrames& run, int samples = 16);

// Area-weighted vertex normals of a triangle mesh (unit; +y where no triangle touches a vertex).
Eigen::Matrix3Xd vertex_normals(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xi& triangles);

class PanelRenderer {
 public:
  // Builds the collider meshes (planes as floor patches around `framing`) and uploads `texture`
  // (RGBA); needs the current GL context.
  PanelRenderer(const scene::Scene& scene, const ClothModel& model, const Image& texture,
                const Bounds& framing);
  // Distance (m) beyond the framing sphere that the floor patches reach: for the camera's far
  // plane.
  double extra_radius() const { return extra_radius_; }
  // Draws into the GL viewport (x, y, width, height) (pixels, y up from the buffer's bottom), with
  // the cloth at `cloth` (3 x particles, m) and the colliders posed at `time` (s), each dynamic
  // collider where `bodies` puts it (the solver's own body; at its start without an entry).
  void draw(const Camera& camera, int x, int y, int width, int height,
            const Eigen::Matrix3Xd& cloth, double time, const BodyPoses* bodies = nullptr) const;

 private:
  struct ColliderDrawable {
    const Collider* collider;
    DrawMesh mesh;
  };
  // The constraints as lines from particle a to their other end at `time` (s): strings and rods.
  void draw_constraints(const Eigen::Matrix3Xd& cloth, double time, const BodyPoses* bodies) const;

  const ClothModel& model_;
  DistanceConstraints constraints_;  // the scene's, drawn as lines
  std::vector<ColliderDrawable> colliders_;
  unsigned texture_ = 0;
  double extra_radius_ = 0.0;
};

}  // namespace drapelab::render
