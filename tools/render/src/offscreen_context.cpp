// OSMesa context creation and pixel read-back.
#include "drapelab/render/offscreen_context.hpp"

#include <GL/osmesa.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace drapelab::render {

struct OffscreenContext::Handle {
  OSMesaContext context = nullptr;
};

OffscreenContext::OffscreenContext(int width, int height)
    : handle_(std::make_unique<Handle>()), width_(width), height_(height) {
  if (width < 1 || height < 1 || width > max_size() || height > max_size())
    throw std::runtime_error("offscreen buffer of " + std::to_string(width) + " x " +
                             std::to_string(height) + " pixels is outside 1.." +
                             std::to_string(max_size()));
  // RGBA colour, 24-bit depth, no stencil or accumulation buffer; no shared context.
  handle_->context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (!handle_->context)
    throw std::runtime_error("OSMesa could not create an offscreen GL context");
  buffer_.assign(std::size_t(width) * height * 4, 0);
  if (!OSMesaMakeCurrent(handle_->context, buffer_.data(), GL_UNSIGNED_BYTE, width, height)) {
    OSMesaDestroyContext(handle_->context);
    throw std::runtime_error("OSMesa could not bind a " + std::to_string(width) + " x " +
                             std::to_string(height) + " buffer");
  }
}

OffscreenContext::~OffscreenContext() {
  // Mesa 22 keeps the framebuffer OSMesaMakeCurrent made in a list of its own that is never freed
  // (480 bytes per process; tools/lsan-suppressions.txt); unbinding first does not release it.
  if (handle_ && handle_->context) OSMesaDestroyContext(handle_->context);
}

int OffscreenContext::max_size() {
  GLint width = 0, height = 0;
  OSMesaGetIntegerv(OSMESA_MAX_WIDTH, &width);
  OSMesaGetIntegerv(OSMESA_MAX_HEIGHT, &height);
  const int limit = std::min(width, height);
  return limit > 0 ? limit : 4096;  // queried before any context exists it may be 0 on old Mesa
}

std::string OffscreenContext::description() const {
  auto text = [](GLenum name) {
    const GLubyte* value = glGetString(name);
    return value ? std::string(reinterpret_cast<const char*>(value)) : std::string("?");
  };
  return "GL " + text(GL_VERSION) + " / " + text(GL_RENDERER);
}

Image OffscreenContext::read_pixels() const {
  glFinish();
  std::vector<unsigned char> rgb(std::size_t(width_) * height_ * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);  // rows of 3 x width bytes, no padding
  glReadPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  Image image(width_, height_, 3);
  const std::size_t row = std::size_t(width_) * 3;
  for (int y = 0; y < height_; ++y)  // GL's row 0 is the bottom one
    std::memcpy(image.pixels.data() + y * row, rgb.data() + std::size_t(height_ - 1 - y) * row,
                row);
  return image;
}

}  // namespace drapelab::render
