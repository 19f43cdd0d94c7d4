#include "renders/text.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace rockbench::renders {
namespace {

struct Glyph {
  int left = 0, top = 0, width = 0, rows = 0, advance = 0;
  std::vector<uint8_t> coverage;  // rows x width, 0..255
};

// Next code point of UTF-8 text (U+FFFD for a malformed byte).
char32_t NextCodePoint(std::string_view s, size_t* i) {
  const auto b0 = static_cast<unsigned char>(s[*i]);
  int extra = b0 < 0x80 ? 0 : (b0 >> 5) == 6 ? 1 : (b0 >> 4) == 14 ? 2 : (b0 >> 3) == 30 ? 3 : -1;
  ++*i;
  if (extra < 0) return 0xFFFD;
  char32_t cp = extra == 0 ? b0 : (b0 & (0x3F >> extra));
  for (int k = 0; k < extra; ++k) {
    if (*i >= s.size()) return 0xFFFD;
    const auto b = static_cast<unsigned char>(s[*i]);
    if ((b >> 6) != 2) return 0xFFFD;
    cp = (cp << 6) | (b & 0x3F);
    ++*i;
  }
  return cp;
}

}  // namespace

struct Font::Impl {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  std::unordered_map<char32_t, Glyph> cache;

  const Glyph& Get(char32_t cp) {
    auto it = cache.find(cp);
    if (it != cache.end()) return it->second;
    Glyph g;
    if (FT_Load_Char(face, cp, FT_LOAD_RENDER | FT_LOAD_TARGET_NORMAL) == 0) {
      const FT_GlyphSlot slot = face->glyph;
      g.left = slot->bitmap_left;
      g.top = slot->bitmap_top;
      g.width = static_cast<int>(slot->bitmap.width);
      g.rows = static_cast<int>(slot->bitmap.rows);
      g.advance = static_cast<int>(slot->advance.x >> 6);
      g.coverage.resize(static_cast<size_t>(g.width) * g.rows);
      for (int r = 0; r < g.rows; ++r) {
        const uint8_t* src = slot->bitmap.buffer + static_cast<ptrdiff_t>(r) * slot->bitmap.pitch;
        std::copy(src, src + g.width, g.coverage.begin() + static_cast<ptrdiff_t>(r) * g.width);
      }
    }
    return cache.emplace(cp, std::move(g)).first->second;
  }
};

Font::Font(const std::filesystem::path& path, int pixel_size) : impl_(std::make_unique<Impl>()) {
  const std::string hint =
      path == kDefaultFontPath ? " (install the Debian package fonts-dejavu-core)" : "";
  if (!std::filesystem::exists(path)) {
    throw RenderError("font file " + path.string() + " not found" + hint);
  }
  if (FT_Init_FreeType(&impl_->library) != 0) throw RenderError("FreeType: cannot initialise");
  if (FT_New_Face(impl_->library, path.c_str(), 0, &impl_->face) != 0) {
    FT_Done_FreeType(impl_->library);
    throw RenderError("font file " + path.string() + " cannot be read as a font" + hint);
  }
  FT_Set_Pixel_Sizes(impl_->face, 0, static_cast<FT_UInt>(std::max(1, pixel_size)));
}

Font::~Font() {
  if (impl_->face) FT_Done_Face(impl_->face);
  if (impl_->library) FT_Done_FreeType(impl_->library);
}

int Font::Draw(Image* image, int x_px, int baseline_px, std::string_view utf8, Rgb colour) {
  int pen = x_px;
  for (size_t i = 0; i < utf8.size();) {
    const Glyph& g = impl_->Get(NextCodePoint(utf8, &i));
    const int x0 = pen + g.left, y0 = baseline_px - g.top;
    for (int r = 0; r < g.rows; ++r) {
      const int y = y0 + r;
      if (y < 0 || y >= image->height_px) continue;
      for (int c = 0; c < g.width; ++c) {
        const int x = x0 + c;
        if (x < 0 || x >= image->width_px) continue;
        const unsigned a = g.coverage[static_cast<size_t>(r) * g.width + c];
        if (a == 0) continue;
        uint8_t* p = &image->rgb[(static_cast<size_t>(y) * image->width_px + x) * 3];
        // Integer alpha blend, rounded.
        p[0] = static_cast<uint8_t>((p[0] * (255 - a) + colour.r * a + 127) / 255);
        p[1] = static_cast<uint8_t>((p[1] * (255 - a) + colour.g * a + 127) / 255);
        p[2] = static_cast<uint8_t>((p[2] * (255 - a) + colour.b * a + 127) / 255);
      }
    }
    pen += g.advance;
  }
  return pen - x_px;
}

int Font::Measure(std::string_view utf8) {
  int w = 0;
  for (size_t i = 0; i < utf8.size();) w += impl_->Get(NextCodePoint(utf8, &i)).advance;
  return w;
}

int Font::ascender_px() const {
  return static_cast<int>(std::lround(impl_->face->size->metrics.ascender / 64.0));
}
int Font::descender_px() const {
  return static_cast<int>(std::lround(-impl_->face->size->metrics.descender / 64.0));
}
int Font::line_height_px() const {
  return static_cast<int>(std::lround(impl_->face->size->metrics.height / 64.0));
}

std::string Fitted(Font* font, const std::string& text, int room_px) {
  if (font->Measure(text) <= room_px) return text;
  std::string kept = text;
  while (!kept.empty()) {
    while (!kept.empty()) {
      const auto c = static_cast<unsigned char>(kept.back());
      kept.pop_back();
      if ((c & 0xC0) != 0x80) break;
    }
    const std::string shortened = kept + "…";
    if (font->Measure(shortened) <= room_px) return shortened;
  }
  return std::string();
}

}  // namespace rockbench::renders
