// Labels drawn into images with FreeType: glyphs rasterised from a TrueType font (DejaVu Sans from
// fonts-dejavu-core by default) as 8-bit coverage and blended over the pixels.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "drapelab/render/image.hpp"

namespace drapelab::render {

// The font built in at configure time (CMake's DRAPELAB_FONT_FILE).
std::filesystem::path default_font_file();

class Font {
 public:
  // Throws std::runtime_error naming the file when FreeType cannot open it.
  explicit Font(const std::filesystem::path& file);
  ~Font();
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;

  // Pixel size (em height) used by the calls below.
  void set_pixel_size(int pixels);
  int pixel_size() const { return pixels_; }
  int line_height() const;                  // pixels from one baseline to the next
  int ascent() const;                       // pixels above the baseline
  int text_width(const std::string& utf8);  // pixels advanced by the text
  // Draws UTF-8 text with its baseline at y, starting at x (pixels, y down), blended in `color`.
  void draw(Image& image, int x, int baseline, const std::string& utf8, Rgb color);

 private:
  struct Library;
  std::unique_ptr<Library> library_;
  int pixels_ = 0;
};

}  // namespace drapelab::render
