// PNG files through libpng.
#include <png.h>

#include <cstring>

#include "files/atomic_file.h"
#include "renders/image.h"
#include "scene/history.h"

namespace rockbench::renders {
namespace {

void AppendToString(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(png));
  out->append(reinterpret_cast<const char*>(data), length);
}

void NoFlush(png_structp) {}

[[noreturn]] void OnPngError(png_structp, png_const_charp message) {
  throw RenderError(std::string("libpng: ") + message);
}

void OnPngWarning(png_structp, png_const_charp) {}

}  // namespace

std::string EncodePng(const Image& image, const PngConfig& config) {
  if (image.width_px <= 0 || image.height_px <= 0 ||
      image.rgb.size() != static_cast<size_t>(image.width_px) * image.height_px * 3) {
    throw RenderError("EncodePng: the image has no pixels or the wrong buffer size");
  }
  std::string out;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, OnPngError, OnPngWarning);
  if (!png) throw RenderError("libpng: png_create_write_struct failed");
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw RenderError("libpng: png_create_info_struct failed");
  }
  try {
    png_set_write_fn(png, &out, AppendToString, NoFlush);
    png_set_compression_level(png, config.compression_level);
    png_set_filter(png, PNG_FILTER_TYPE_BASE,
                   config.filter == PngFilter::kNone  ? PNG_FILTER_NONE
                   : config.filter == PngFilter::kSub ? PNG_FILTER_SUB
                                                      : PNG_ALL_FILTERS);
    png_set_IHDR(png, info, static_cast<png_uint_32>(image.width_px),
                 static_cast<png_uint_32>(image.height_px), 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < image.height_px; ++y) {
      png_write_row(png,
                    const_cast<png_bytep>(&image.rgb[static_cast<size_t>(y) * image.width_px * 3]));
    }
    png_write_end(png, nullptr);
  } catch (...) {
    png_destroy_write_struct(&png, &info);
    throw;
  }
  png_destroy_write_struct(&png, &info);
  return out;
}

void WritePng(const Image& image, const std::filesystem::path& path, const PngConfig& config) {
  WriteFileAtomic(path, EncodePng(image, config));
}

Image ReadPng(const std::filesystem::path& path) {
  png_image img;
  std::memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path.c_str())) {
    throw RenderError(path.string() + ": cannot read PNG: " + img.message);
  }
  img.format = PNG_FORMAT_RGB;
  Image out(static_cast<int>(img.width), static_cast<int>(img.height));
  if (!png_image_finish_read(&img, nullptr, out.rgb.data(), 0, nullptr)) {
    std::string message = img.message;
    png_image_free(&img);
    throw RenderError(path.string() + ": cannot read PNG: " + message);
  }
  return out;
}

}  // namespace rockbench::renders
