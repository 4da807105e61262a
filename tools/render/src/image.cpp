// Pixel operations on Image: box-filter downsampling and translucent rectangles.
#include "drapelab/render/image.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace drapelab::render {

Image downsample(const Image& image, int factor) {
  if (factor == 1) return image;
  if (factor < 1 || image.width % factor || image.height % factor)
    throw std::invalid_argument("downsample: the size must be a multiple of the factor");
  Image out(image.width / factor, image.height / factor, image.channels);
  const int samples = factor * factor;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < image.channels; ++c) {
        int sum = 0;
        for (int dy = 0; dy < factor; ++dy)
          for (int dx = 0; dx < factor; ++dx) sum += image.at(x * factor + dx, y * factor + dy)[c];
        out.at(x, y)[c] = static_cast<std::uint8_t>((sum + samples / 2) / samples);  // rounded mean
      }
  return out;
}

void blend_rectangle(Image& image, int x0, int y0, int x1, int y1, Rgb color, double alpha) {
  x0 = std::clamp(x0, 0, image.width);
  x1 = std::clamp(x1, 0, image.width);
  y0 = std::clamp(y0, 0, image.height);
  y1 = std::clamp(y1, 0, image.height);
  const std::uint8_t rgb[3] = {color.r, color.g, color.b};
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      std::uint8_t* p = image.at(x, y);
      for (int c = 0; c < 3; ++c)
        p[c] = static_cast<std::uint8_t>(std::lround(p[c] + alpha * (rgb[c] - p[c])));
    }
}

}  // namespace drapelab::render
