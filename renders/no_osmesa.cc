// Built instead of the GL, libpng and FreeType parts when the build has no OSMesa
// (ROCKBENCH_WITH_OSMESA=OFF): every entry point that would draw or write a picture says so.
#include "renders/gl_context.h"
#include "renders/image.h"
#include "renders/renderer.h"

namespace rockbench::renders {
namespace {

const char* const kNoOsmesa =
    "this build of rockbench has no OSMesa, so it cannot render pictures (install "
    "libosmesa6-dev, libpng-dev and libfreetype-dev and configure with "
    "-DROCKBENCH_WITH_OSMESA=ON)";

[[noreturn]] void NoOsmesa() {
  throw RenderError(kNoOsmesa);
}

}  // namespace

bool GlAvailable() {
  return false;
}
std::string GlUnavailableReason() {
  return kNoOsmesa;
}
std::unique_ptr<GlContext> CreateGlContext(int, int) {
  NoOsmesa();
}

std::string EncodePng(const Image&, const PngConfig&) {
  NoOsmesa();
}
void WritePng(const Image&, const std::filesystem::path&, const PngConfig&) {
  NoOsmesa();
}
Image ReadPng(const std::filesystem::path&) {
  NoOsmesa();
}

struct FrameRenderer::Impl {
  FrameLayout layout;
  RenderConfig config;
  Palette palette;
};

FrameRenderer::FrameRenderer(const Scene&, std::vector<Track>, BaseDisplacement, RenderConfig) {
  NoOsmesa();
}
FrameRenderer::~FrameRenderer() = default;
void FrameRenderer::Render(double, Image*) {
  NoOsmesa();
}
Image FrameRenderer::Render(double) {
  NoOsmesa();
}
const FrameLayout& FrameRenderer::layout() const {
  return impl_->layout;
}
const RenderConfig& FrameRenderer::config() const {
  return impl_->config;
}
const Palette& FrameRenderer::palette() const {
  return impl_->palette;
}

}  // namespace rockbench::renders
