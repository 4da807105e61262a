// The cloth's texture: a procedural checker by default, or a PNG file; uploaded once to GL with
// mipmaps so a dense checker does not shimmer from frame to frame.
#pragma once

#include <filesystem>

#include "drapelab/render/image.hpp"

namespace drapelab::render {

// An RGBA checker of `squares` x `squares` squares over UV [0, 1]^2, `size` pixels square, in two
// colours (a warm cream and a brick red).
Image checker_texture(int squares = 8, int size = 512);

// A texture from a PNG file (any PNG libpng reads). Throws std::runtime_error naming the file.
Image load_texture(const std::filesystem::path& path);

// Uploads `image` (RGBA) as the current GL_TEXTURE_2D with box-filtered mipmaps (made here: the
// image is first resampled to a power-of-two square of at most 1024 pixels), trilinear filtering
// and repeat wrapping. The image's top row is at v = 1 (OBJ's convention: v grows upwards in the
// image). Returns the GL texture name.
unsigned upload_texture(const Image& image);

}  // namespace drapelab::render
