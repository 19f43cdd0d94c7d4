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

// No frame renderer is ever made (its constructor throws): nothing to hold, and no accessor is
// reached.
struct FrameRenderer::Impl {};

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
  NoOsmesa();
}
const RenderConfig& FrameRenderer::config() const {
  NoOsmesa();
}
const Palette& FrameRenderer::palette() const {
  NoOsmesa();
}

}  // namespace rockbench::renders
