#include "renders/image.h"

namespace rockbench::renders {
namespace {

template <int kFactor>
void Downsample(const uint8_t* src, Image* out) {
  constexpr unsigned kCount = kFactor * kFactor;
  const int w = out->width_px, h = out->height_px;
  const size_t src_row = static_cast<size_t>(w) * kFactor * 4;
  for (int y = 0; y < h; ++y) {
    // Output row y (from the top) comes from source rows counted from the bottom.
    const uint8_t* rows[kFactor];
    const int src_y0 = (h - 1 - y) * kFactor;
    for (int j = 0; j < kFactor; ++j) rows[j] = src + static_cast<size_t>(src_y0 + j) * src_row;
    uint8_t* o = &out->rgb[static_cast<size_t>(y) * w * 3];
    for (int x = 0; x < w; ++x) {
      unsigned r = 0, g = 0, b = 0;
      for (int j = 0; j < kFactor; ++j) {
        const uint8_t* p = rows[j] + static_cast<size_t>(x) * kFactor * 4;
        for (int i = 0; i < kFactor; ++i) {
          r += p[4 * i];
          g += p[4 * i + 1];
          b += p[4 * i + 2];
        }
      }
      o[3 * x] = static_cast<uint8_t>((r + kCount / 2) / kCount);
      o[3 * x + 1] = static_cast<uint8_t>((g + kCount / 2) / kCount);
      o[3 * x + 2] = static_cast<uint8_t>((b + kCount / 2) / kCount);
    }
  }
}

}  // namespace

void DownsampleFlip(const uint8_t* rgba_bottom_up, int factor, Image* out) {
  out->rgb.resize(static_cast<size_t>(out->width_px) * out->height_px * 3);
  switch (factor) {
    case 1:
      Downsample<1>(rgba_bottom_up, out);
      break;
    case 2:
      Downsample<2>(rgba_bottom_up, out);
      break;
    case 3:
      Downsample<3>(rgba_bottom_up, out);
      break;
    case 4:
      Downsample<4>(rgba_bottom_up, out);
      break;
    default:
      throw std::invalid_argument("supersampling factor must be 1..4");
  }
}

}  // namespace rockbench::renders
