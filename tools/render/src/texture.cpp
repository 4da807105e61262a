// Cloth textures: the default checker, PNG textures, and their upload with mipmaps.
#include "drapelab/render/texture.hpp"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "drapelab/render/png_io.hpp"

namespace drapelab::render {
namespace {

constexpr int kMaxTextureSize = 1024;  // pixels; more detail than a panel can show

int power_of_two_at_least(int n) {
  int p = 1;
  while (p < n && p < kMaxTextureSize) p *= 2;
  return p;
}

// Bilinear resampling of an RGBA image to size x size (texel centres mapped onto texel centres).
Image resample_square(const Image& image, int size) {
  Image out(size, size, 4);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double sx = std::clamp((x + 0.5) * image.width / size - 0.5, 0.0, image.width - 1.0);
      const double sy = std::clamp((y + 0.5) * image.height / size - 0.5, 0.0, image.height - 1.0);
      const int x0 = static_cast<int>(sx), y0 = static_cast<int>(sy);
      const int x1 = std::min(x0 + 1, image.width - 1), y1 = std::min(y0 + 1, image.height - 1);
      const double fx = sx - x0, fy = sy - y0;
      for (int c = 0; c < 4; ++c) {
        const double top = (1 - fx) * image.at(x0, y0)[c] + fx * image.at(x1, y0)[c];
        const double bottom = (1 - fx) * image.at(x0, y1)[c] + fx * image.at(x1, y1)[c];
        out.at(x, y)[c] = static_cast<std::uint8_t>(std::lround((1 - fy) * top + fy * bottom));
      }
    }
  return out;
}

Image half_size(const Image& image) {  // 2 x 2 box filter; sizes are powers of two
  Image out(std::max(1, image.width / 2), std::max(1, image.height / 2), 4);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 4; ++c) {
        const int x1 = std::min(2 * x + 1, image.width - 1),
                  y1 = std::min(2 * y + 1, image.height - 1);
        const int sum = image.at(2 * x, 2 * y)[c] + image.at(x1, 2 * y)[c] +
                        image.at(2 * x, y1)[c] + image.at(x1, y1)[c];
        out.at(x, y)[c] = static_cast<std::uint8_t>((sum + 2) / 4);
      }
  return out;
}

}  // namespace

Image checker_texture(int squares, int size) {
  const std::uint8_t light[4] = {238, 225, 196, 255};  // cream
  const std::uint8_t dark[4] = {178, 64, 48, 255};     // brick red
  Image image(size, size, 4);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const bool odd = ((x * squares / size) + (y * squares / size)) % 2 == 1;
      std::copy(odd ? dark : light, (odd ? dark : light) + 4, image.at(x, y));
    }
  return image;
}

Image load_texture(const std::filesystem::path& path) { return read_png_rgba(path); }

unsigned upload_texture(const Image& image) {
  if (image.channels != 4) throw std::invalid_argument("upload_texture: RGBA expected");
  const int size = power_of_two_at_least(std::max(image.width, image.height));
  Image level = resample_square(image, size);
  // GL's first row is v = 0: upload bottom row first, so the image's top row is at v = 1.
  auto flipped = [](const Image& im) {
    Image out(im.width, im.height, 4);
    const std::size_t row = std::size_t(im.width) * 4;
    for (int y = 0; y < im.height; ++y)
      std::copy_n(im.pixels.data() + std::size_t(im.height - 1 - y) * row, row,
                  out.pixels.data() + y * row);
    return out;
  };
  GLuint name = 0;
  glGenTextures(1, &name);
  glBindTexture(GL_TEXTURE_2D, name);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int lod = 0;; ++lod) {
    const Image rows = flipped(level);
    glTexImage2D(GL_TEXTURE_2D, lod, GL_RGBA8, rows.width, rows.height, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, rows.pixels.data());
    if (level.width == 1 && level.height == 1) break;
    level = half_size(level);
  }
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return name;
}

}  // namespace drapelab::render
