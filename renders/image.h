#pragma once
/// A frame: 8-bit RGB pixels, top row first (ready for PNG and for ffmpeg's rgb24).
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace rockbench::renders {

/// Rendering is not possible in this build or on this machine (no OSMesa, no font, ...).
struct RenderError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb&) const = default;
};

struct Image {
  int width_px = 0;
  int height_px = 0;
  std::vector<uint8_t> rgb;  ///< width_px * height_px * 3 bytes, rows top to bottom

  Image() = default;
  Image(int w, int h) : width_px(w), height_px(h), rgb(static_cast<size_t>(w) * h * 3, 0) {}
  /// Pixel (x right, y down from the top-left corner).
  Rgb at(int x, int y) const {
    const uint8_t* p = &rgb[(static_cast<size_t>(y) * width_px + x) * 3];
    return {p[0], p[1], p[2]};
  }
};

/// Box-filters a bottom-up RGBA buffer of (factor*w) x (factor*h) pixels (as OSMesa leaves it)
/// down to w x h RGB, flipping it to top-down. factor is 1..4.
void DownsampleFlip(const uint8_t* rgba_bottom_up, int factor, Image* out);

/// PNG row filter. Frames are mostly flat colour: no filter compresses them best; "sub" is
/// faster at low zlib levels; libpng's adaptive choice is slowest and no smaller here.
enum class PngFilter { kNone, kSub, kAdaptive };

/// Settings of PNG files (docs/renders.md has the measured sizes and times).
struct PngConfig {
  int compression_level = 6;  ///< zlib level 0..9 (6 is libpng's default)
  PngFilter filter = PngFilter::kNone;
};

/// PNG bytes of an image (deterministic: no time or text chunks). Throws RenderError when this
/// build has no libpng.
std::string EncodePng(const Image& image, const PngConfig& config = {});
/// Writes a PNG atomically (temporary name, then rename). Throws RenderError / runtime_error.
void WritePng(const Image& image, const std::filesystem::path& path, const PngConfig& config = {});
/// Reads an 8-bit RGB or RGBA PNG (alpha dropped); for tests and golden images. Throws.
Image ReadPng(const std::filesystem::path& path);

}  // namespace rockbench::renders
