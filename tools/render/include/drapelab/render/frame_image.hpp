// One frame of a run as one image: a panel per solver, side by side, same camera and lights, each
// with a legend (solver, time, key metrics).
#pragma once

#include <string>
#include <vector>

#include "drapelab/render/camera.hpp"
#include "drapelab/render/image.hpp"
#include "drapelab/render/offscreen_context.hpp"
#include "drapelab/render/panel_renderer.hpp"
#include "drapelab/render/text.hpp"

namespace drapelab::render {

struct Panel {
  std::string title;                        // the solver's name (and status when it stopped)
  std::vector<std::string> legend;          // lines drawn at the panel's bottom left
  const Eigen::Matrix3Xd* cloth = nullptr;  // positions to draw (m)
  const BodyPoses* bodies = nullptr;        // this solver's dynamic colliders (none: null)
};

// Where panel k of n lies in an image `width` pixels wide: [x0, x1).
struct PanelSpan {
  int x0 = 0, x1 = 0;
};
PanelSpan panel_span(int k, int n, int width);

// Renders the panels into the context (whose size is the output size times `supersample`), reads
// the pixels back, averages supersample x supersample blocks (antialiasing), and draws the legends
// and a 1-pixel line between panels. `time` (s) poses the colliders.
Image render_frame(const OffscreenContext& context, const PanelRenderer& renderer,
                   const Camera& camera, const std::vector<Panel>& panels, double time,
                   int supersample, Font& font);

// The legend lines of a solver at a frame: "t = 0.500 s (frame 30)", "max stretch 1.23 %" and, when
// present, "drape coefficient 0.612".
std::vector<std::string> legend_lines(double time, int frame, const FrameMetrics* metrics);

}  // namespace drapelab::render
