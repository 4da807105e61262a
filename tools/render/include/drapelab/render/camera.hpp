// The camera of a render: a pinhole at `eye` looking at `target`, y up, with a vertical field of
// view. Default framing from the bounds of what is drawn; `--camera` overrides any part of it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <optional>
#include <string>

namespace drapelab::render {

// An axis-aligned box that grows to hold points (m).
struct Bounds {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return !(min.array() <= max.array()).all(); }
  void add(const Eigen::Vector3d& p);  // non-finite points are ignored
  void add(const Bounds& other);
  Eigen::Vector3d center() const { return 0.5 * (min + max); }
  double radius() const {
    return empty() ? 0.0 : 0.5 * (max - min).norm();
  }  // of the bounding sphere
};

struct Camera {
  Eigen::Vector3d eye{0.0, 1.0, 3.0};     // m
  Eigen::Vector3d target{0.0, 0.0, 0.0};  // m, the point at the image centre
  Eigen::Vector3d up{0.0, 1.0, 0.0};  // world up (y); replaced by z when looking straight down y
  double fov_degrees = 35.0;          // vertical field of view
  double near = 0.01;                 // m, clip distances along the view direction
  double far = 100.0;                 // m
};

inline constexpr double kDefaultFovDegrees = 35.0;

// The parts of a camera given with --camera "eye=x,y,z;target=x,y,z;fov=deg" (any subset, any
// order, spaces allowed).
struct CameraSpec {
  std::optional<Eigen::Vector3d> eye;
  std::optional<Eigen::Vector3d> target;
  std::optional<double> fov_degrees;
};

// Parses --camera text; nullopt with `error` set ("fov must be in (0, 180) degrees, got 200").
std::optional<CameraSpec> parse_camera_spec(const std::string& text, std::string* error);

// The default framing: a 3/4 view from above (azimuth 30 degrees from +z towards +x, elevation 35
// degrees) looking at the centre of `bounds`, just far enough for the corners of `bounds` to fit in
// the view of an image of `aspect` = width / height (with a 4 % margin). Any part given in `spec`
// replaces the default one: a target alone keeps the default direction and distance from it, an eye
// alone looks at the default target. The clip distances hold the bounding sphere of `bounds` grown
// by `extra_radius` (m, for the floor patches).
Camera frame_camera(const Bounds& bounds, double aspect, const CameraSpec& spec,
                    double extra_radius);

// Column-major 4x4 matrices for glLoadMatrixd: world -> eye (gluLookAt's) and eye -> clip
// (gluPerspective's, vertical fov, `aspect` = width / height).
Eigen::Matrix4d view_matrix(const Camera& camera);
Eigen::Matrix4d projection_matrix(const Camera& camera, double aspect);

// Where a world point lands in a width x height image (pixels, x right, y down, (0, 0) = the
// top-left corner of the top-left pixel); nullopt when it is behind the eye.
std::optional<Eigen::Vector2d> project_to_pixel(const Camera& camera, const Eigen::Vector3d& p,
                                                int width, int height);

}  // namespace drapelab::render
