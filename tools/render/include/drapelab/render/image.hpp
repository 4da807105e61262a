// An 8-bit image in memory: rows top first, channels interleaved (3 = RGB, 4 = RGBA).
#pragma once

#include <cstdint>
#include <vector>

namespace drapelab::render {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

struct Image {
  int width = 0;
  int height = 0;
  int channels = 3;
  std::vector<std::uint8_t> pixels;  // width x height x channels, row 0 at the top

  Image() = default;
  Image(int w, int h, int c)
      : width(w), height(h), channels(c), pixels(std::size_t(w) * h * c, 0) {}
  std::uint8_t* at(int x, int y) { return pixels.data() + (std::size_t(y) * width + x) * channels; }
  const std::uint8_t* at(int x, int y) const {
    return pixels.data() + (std::size_t(y) * width + x) * channels;
  }
};

// Averages factor x factor blocks (box filter): supersampled rendering down to the output size.
// The width and height must be multiples of factor.
Image downsample(const Image& image, int factor);

// Blends `color` over the rectangle [x0, x1) x [y0, y1) (clipped to the image) with opacity alpha
// in [0, 1].
void blend_rectangle(Image& image, int x0, int y0, int x1, int y1, Rgb color, double alpha);

}  // namespace drapelab::render
