// PNG files through libpng's simplified API (png_image): 8-bit RGB or RGBA, sRGB as stored.
#pragma once

#include <filesystem>

#include "drapelab/render/image.hpp"

namespace drapelab::render {

// Writes an RGB (3 channels) or RGBA (4) image. Throws std::runtime_error with libpng's message.
void write_png(const std::filesystem::path& path, const Image& image);

// Reads any PNG (grey, palette, 16-bit, with or without alpha) converted to 8-bit RGBA. Throws
// std::runtime_error naming the file when it cannot be read or is not a PNG.
Image read_png_rgba(const std::filesystem::path& path);

}  // namespace drapelab::render
