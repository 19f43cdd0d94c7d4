// Frames as pixels: the box filter and flip that turn the supersampled GL buffer into a frame,
// and PNG files.
#include "renders/image.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace rockbench::renders {
namespace {

TEST(DownsampleFlip, FactorOneFlipsRowsAndDropsAlpha) {
  // Bottom-up RGBA, 2x2: bottom row (10,20,30) (40,50,60); top row (70,80,90) (100,110,120).
  const uint8_t src[] = {10, 20, 30, 255, 40, 50, 60, 255, 70, 80, 90, 255, 100, 110, 120, 255};
  Image out(2, 2);
  DownsampleFlip(src, 1, &out);
  EXPECT_EQ(out.at(0, 0), (Rgb{70, 80, 90}));
  EXPECT_EQ(out.at(1, 0), (Rgb{100, 110, 120}));
  EXPECT_EQ(out.at(0, 1), (Rgb{10, 20, 30}));
  EXPECT_EQ(out.at(1, 1), (Rgb{40, 50, 60}));
}

TEST(DownsampleFlip, FactorTwoAveragesEachBlockRounded) {
  // One output pixel from a 2x2 block: red 0+1+2+4 = 7 -> 7/4 = 1.75 -> 2; green 255 x 4 -> 255;
  // blue 0,0,0,2 -> 0.5 -> rounds half up to 1.
  const uint8_t src[] = {0, 255, 0, 255, 1, 255, 0, 255, 2, 255, 0, 255, 4, 255, 2, 255};
  Image out(1, 1);
  DownsampleFlip(src, 2, &out);
  EXPECT_EQ(out.at(0, 0), (Rgb{2, 255, 1}));
}

TEST(DownsampleFlip, FactorThreeKeepsAnEdgeAsAnIntermediateShade) {
  // A 6x3 buffer (2x1 output): the left output pixel sees a vertical edge after its first column
  // (one third white, two thirds black): 255/3 = 85.
  std::vector<uint8_t> src(6 * 3 * 4, 0);
  for (int y = 0; y < 3; ++y) {
    for (int c = 0; c < 3; ++c) src[(y * 6 + 0) * 4 + c] = 255;
  }
  Image out(2, 1);
  DownsampleFlip(src.data(), 3, &out);
  EXPECT_EQ(out.at(0, 0), (Rgb{85, 85, 85}));
  EXPECT_EQ(out.at(1, 0), (Rgb{0, 0, 0}));
  EXPECT_THROW(DownsampleFlip(src.data(), 5, &out), std::invalid_argument);
}

#if ROCKBENCH_HAVE_OSMESA
TEST(Png, RoundTripsAndIsDeterministic) {
  Image img(7, 5);
  for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = static_cast<uint8_t>(i * 37 % 251);
  const std::string a = EncodePng(img), b = EncodePng(img);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a.substr(1, 3), "PNG");
  const auto path = std::filesystem::temp_directory_path() / "rockbench_image_test.png";
  WritePng(img, path);
  const Image back = ReadPng(path);
  std::filesystem::remove(path);
  EXPECT_EQ(back.width_px, 7);
  EXPECT_EQ(back.height_px, 5);
  EXPECT_EQ(back.rgb, img.rgb);
}

TEST(Png, RejectsAnImageWithoutPixels) {
  EXPECT_THROW(EncodePng(Image{}), RenderError);
}
#else
TEST(Png, SaysThisBuildHasNoOsmesa) {
  try {
    EncodePng(Image(2, 2));
    FAIL() << "EncodePng should throw without OSMesa";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("no OSMesa"), std::string::npos) << e.what();
  }
}
#endif

}  // namespace
}  // namespace rockbench::renders
