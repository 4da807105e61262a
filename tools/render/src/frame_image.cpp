// Composition of a frame: panels, antialiasing, legends.
#include "drapelab/render/frame_image.hpp"

#include <algorithm>
#include <cstdio>

namespace drapelab::render {
namespace {

const Rgb kInk{25, 28, 34};
const Rgb kPaper{255, 255, 255};
const Rgb kSeparator{60, 64, 72};
constexpr double kPaperOpacity = 0.72;  // the legend's backing box: readable, the scene still shows

// A block of text lines with a translucent box behind it; (x, y) is its top-left corner (pixels).
void draw_block(Image& image, Font& font, int x, int y, const std::vector<std::string>& lines) {
  if (lines.empty()) return;
  const int pad = std::max(2, font.pixel_size() / 4);
  int width = 0;
  for (const auto& line : lines) width = std::max(width, font.text_width(line));
  const int height = font.line_height() * static_cast<int>(lines.size());
  blend_rectangle(image, x, y, x + width + 2 * pad, y + height + 2 * pad, kPaper, kPaperOpacity);
  for (std::size_t k = 0; k < lines.size(); ++k)
    font.draw(image, x + pad, y + pad + font.ascent() + static_cast<int>(k) * font.line_height(),
              lines[k], kInk);
}

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

}  // namespace

PanelSpan panel_span(int k, int n, int width) {
  return {static_cast<int>(static_cast<long long>(k) * width / n),
          static_cast<int>(static_cast<long long>(k + 1) * width / n)};
}

std::vector<std::string> legend_lines(double time, int frame, const FrameMetrics* metrics) {
  std::vector<std::string> lines{format("t = %.3f s", time) + " (frame " + std::to_string(frame) +
                                 ")"};
  if (metrics && metrics->max_stretch)
    lines.push_back(format("max stretch %.2f %%", 100.0 * *metrics->max_stretch));
  if (metrics && metrics->drape_coefficient)
    lines.push_back(format("drape coefficient %.3f", *metrics->drape_coefficient));
  return lines;
}

Image render_frame(const OffscreenContext& context, const PanelRenderer& renderer,
                   const Camera& camera, const std::vector<Panel>& panels, double time,
                   int supersample, Font& font) {
  const int n = static_cast<int>(panels.size());
  const int big_width = context.width();
  for (int k = 0; k < n; ++k) {
    // Spans computed at the output size and scaled, so panel edges fall on whole output pixels.
    const PanelSpan span = panel_span(k, n, big_width / supersample);
    renderer.draw(camera, span.x0 * supersample, 0, (span.x1 - span.x0) * supersample,
                  context.height(), *panels[k].cloth, time, panels[k].bodies);
  }
  Image image = downsample(context.read_pixels(), supersample);

  // Labels scale with the image: about 1/24 of its height for the title, 1/30 for the legend.
  const int margin = std::max(3, image.height / 80);
  for (int k = 0; k < n; ++k) {
    const PanelSpan span = panel_span(k, n, image.width);
    if (k > 0) blend_rectangle(image, span.x0, 0, span.x0 + 1, image.height, kSeparator, 1.0);
    font.set_pixel_size(std::max(10, image.height / 24));
    draw_block(image, font, span.x0 + margin, margin, {panels[k].title});
    font.set_pixel_size(std::max(9, image.height / 30));
    const int height = font.line_height() * static_cast<int>(panels[k].legend.size()) +
                       2 * std::max(2, font.pixel_size() / 4);
    draw_block(image, font, span.x0 + margin, image.height - margin - height, panels[k].legend);
  }
  return image;
}

}  // namespace drapelab::render
