// PNG reading and writing with libpng's simplified API.
#include "drapelab/render/png_io.hpp"

#include <png.h>

#include <stdexcept>
#include <string>

namespace drapelab::render {

void write_png(const std::filesystem::path& path, const Image& image) {
  if (image.channels != 3 && image.channels != 4)
    throw std::invalid_argument("write_png: 3 or 4 channels expected");
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = image.channels == 3 ? PNG_FORMAT_RGB : PNG_FORMAT_RGBA;
  const png_int_32 row_stride = image.width * image.channels;  // bytes; positive = top row first
  if (!png_image_write_to_file(&png, path.string().c_str(), 0, image.pixels.data(), row_stride,
                               nullptr)) {
    const std::string message = png.message;
    png_image_free(&png);
    throw std::runtime_error("cannot write " + path.string() + ": " + message);
  }
}

Image read_png_rgba(const std::filesystem::path& path) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.string().c_str()))
    throw std::runtime_error("cannot read " + path.string() + " as a PNG image: " + png.message);
  png.format = PNG_FORMAT_RGBA;
  Image image(static_cast<int>(png.width), static_cast<int>(png.height), 4);
  if (!png_image_finish_read(&png, nullptr, image.pixels.data(), 0, nullptr)) {
    const std::string message = png.message;
    png_image_free(&png);
    throw std::runtime_error("cannot read " + path.string() + ": " + message);
  }
  return image;
}

}  // namespace drapelab::render
