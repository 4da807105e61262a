// A GL context without a display or GPU: Mesa's OSMesa renders into a buffer in main memory with
// its software rasteriser (legacy, fixed-function GL is available). One context per render; it is
// made current on the calling thread when created.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "drapelab/render/image.hpp"

namespace drapelab::render {

class OffscreenContext {
 public:
  // A width x height RGBA colour buffer with a 24-bit depth buffer. Throws std::runtime_error when
  // OSMesa cannot create or bind the context.
  OffscreenContext(int width, int height);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  // "Mesa 22.3.6 / llvmpipe (...)": the GL_VERSION and GL_RENDERER strings, for messages.
  std::string description() const;
  // Finishes drawing and reads the whole buffer with glReadPixels, as RGB with row 0 at the top.
  Image read_pixels() const;
  // The largest width or height OSMesa accepts (OSMESA_MAX_WIDTH / OSMESA_MAX_HEIGHT).
  static int max_size();

 private:
  struct Handle;
  std::unique_ptr<Handle> handle_;
  std::vector<unsigned char> buffer_;  // OSMesa draws here: width x height x RGBA, bottom row first
  int width_ = 0;
  int height_ = 0;
};

}  // namespace drapelab::render
