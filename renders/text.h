#pragma once
/// Text drawn on finished frames with FreeType (anti-aliased glyphs, alpha-blended).
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

#include "renders/image.h"

namespace rockbench::renders {

/// The font every frame uses unless told otherwise (Debian package fonts-dejavu-core).
inline constexpr const char* kDefaultFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

/// A TrueType font at one pixel size, with a glyph cache.
class Font {
 public:
  /// Throws RenderError naming the file (and the Debian package for the default font) when the
  /// file is missing or not a font.
  Font(const std::filesystem::path& path, int pixel_size);
  ~Font();
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;

  /// Draws UTF-8 text with the left end of its baseline at (x_px, baseline_px), pixel
  /// coordinates of `image` (y down). Returns the advance, px.
  int Draw(Image* image, int x_px, int baseline_px, std::string_view utf8, Rgb colour);
  /// Advance of the text, px.
  int Measure(std::string_view utf8);
  int ascender_px() const;
  int descender_px() const;  ///< positive, below the baseline
  int line_height_px() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// `text`, shortened with an ellipsis to at most room_px wide in `font` (a whole code point at a
/// time); empty when not even the ellipsis fits.
std::string Fitted(Font* font, const std::string& text, int room_px);

}  // namespace rockbench::renders
