// FreeType text rendering onto Image.
#include "drapelab/render/text.hpp"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <cmath>
#include <stdexcept>
#include <vector>

namespace drapelab::render {
namespace {

// Code points of UTF-8 text; a malformed byte stands for itself (Latin-1), so nothing is lost.
std::vector<char32_t> decode_utf8(const std::string& text) {
  std::vector<char32_t> out;
  for (std::size_t k = 0; k < text.size();) {
    const auto c = static_cast<unsigned char>(text[k]);
    int length = c < 0x80           ? 1
                 : (c >> 5) == 0x6  ? 2
                 : (c >> 4) == 0xE  ? 3
                 : (c >> 3) == 0x1E ? 4
                                    : 0;
    if (length == 0 || k + length > text.size()) {
      out.push_back(c);
      ++k;
      continue;
    }
    char32_t code = length == 1 ? c : c & (0x7F >> length);
    for (int j = 1; j < length; ++j)
      code = (code << 6) | (static_cast<unsigned char>(text[k + j]) & 0x3F);
    out.push_back(code);
    k += length;
  }
  return out;
}

}  // namespace

std::filesystem::path default_font_file() { return DRAPELAB_FONT_FILE; }

struct Font::Library {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
};

Font::Font(const std::filesystem::path& file) : library_(std::make_unique<Library>()) {
  if (FT_Init_FreeType(&library_->library)) throw std::runtime_error("FreeType could not start");
  if (FT_New_Face(library_->library, file.string().c_str(), 0, &library_->face)) {
    FT_Done_FreeType(library_->library);
    throw std::runtime_error("FreeType cannot open the font " + file.string() +
                             " (install fonts-dejavu-core: bash tools/install-deps.sh)");
  }
  set_pixel_size(14);
}

Font::~Font() {
  if (library_->face) FT_Done_Face(library_->face);
  if (library_->library) FT_Done_FreeType(library_->library);
}

void Font::set_pixel_size(int pixels) {
  pixels_ = std::max(4, pixels);
  FT_Set_Pixel_Sizes(library_->face, 0, static_cast<FT_UInt>(pixels_));
}

// FreeType's size metrics are 26.6 fixed point: 64 units per pixel.
int Font::line_height() const {
  return static_cast<int>((library_->face->size->metrics.height + 63) / 64);
}
int Font::ascent() const {
  return static_cast<int>((library_->face->size->metrics.ascender + 63) / 64);
}

int Font::text_width(const std::string& utf8) {
  long width = 0;
  for (const char32_t code : decode_utf8(utf8)) {
    if (FT_Load_Char(library_->face, code, FT_LOAD_DEFAULT)) continue;
    width += library_->face->glyph->advance.x;
  }
  return static_cast<int>((width + 63) / 64);
}

void Font::draw(Image& image, int x, int baseline, const std::string& utf8, Rgb color) {
  long pen = static_cast<long>(x) * 64;  // 26.6 fixed point
  const int rgb[3] = {color.r, color.g, color.b};
  for (const char32_t code : decode_utf8(utf8)) {
    if (FT_Load_Char(library_->face, code, FT_LOAD_RENDER)) continue;  // a missing glyph is skipped
    const FT_GlyphSlot glyph = library_->face->glyph;
    const FT_Bitmap& bitmap = glyph->bitmap;
    const int left = static_cast<int>(pen / 64) + glyph->bitmap_left;
    const int top = baseline - glyph->bitmap_top;
    for (unsigned row = 0; row < bitmap.rows; ++row)
      for (unsigned column = 0; column < bitmap.width; ++column) {
        const int px = left + static_cast<int>(column), py = top + static_cast<int>(row);
        if (px < 0 || py < 0 || px >= image.width || py >= image.height) continue;
        const int coverage = bitmap.buffer[row * bitmap.pitch + column];  // 0..255 grey coverage
        std::uint8_t* p = image.at(px, py);
        for (int c = 0; c < 3; ++c)
          p[c] =
              static_cast<std::uint8_t>((p[c] * (255 - coverage) + rgb[c] * coverage + 127) / 255);
      }
    pen += glyph->advance.x;
  }
}

}  // namespace drapelab::render
