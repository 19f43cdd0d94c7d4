// GlContext on OSMesa (Mesa's off-screen software renderer, llvmpipe in Debian 12).
#include <GL/osmesa.h>

#include <string>
#include <vector>

#include "renders/gl_context.h"
#include "renders/image.h"

namespace rockbench::renders {
namespace {

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext(int w, int h) : w_(w), h_(h), buffer_(static_cast<size_t>(w) * h * 4, 0) {
    GLint max_w = 0, max_h = 0;
    // RGBA, no depth/stencil/accumulation buffers (everything is drawn in painter's order).
    ctx_ = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
    if (!ctx_) throw RenderError("OSMesa: cannot create a context (OSMesaCreateContextExt failed)");
    try {
      MakeCurrent();
    } catch (...) {
      OSMesaDestroyContext(ctx_);
      throw;
    }
    OSMesaGetIntegerv(OSMESA_MAX_WIDTH, &max_w);
    OSMesaGetIntegerv(OSMESA_MAX_HEIGHT, &max_h);
    if (w > max_w || h > max_h) {
      OSMesaDestroyContext(ctx_);
      throw RenderError("OSMesa: " + std::to_string(w) + "x" + std::to_string(h) +
                        " pixels is larger than this OSMesa allows (" + std::to_string(max_w) +
                        "x" + std::to_string(max_h) + "); use a smaller --size or supersampling");
    }
  }
  ~OsMesaContext() override { OSMesaDestroyContext(ctx_); }

  void MakeCurrent() override {
    if (!OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, w_, h_)) {
      throw RenderError("OSMesa: OSMesaMakeCurrent failed for " + std::to_string(w_) + "x" +
                        std::to_string(h_) + " pixels");
    }
    // Rows bottom-up in the buffer (OSMesa's default, stated for clarity).
    OSMesaPixelStore(OSMESA_Y_UP, 1);
  }

  const uint8_t* Finish() override {
    glFinish();
    return buffer_.data();
  }
  int width_px() const override { return w_; }
  int height_px() const override { return h_; }

 private:
  int w_, h_;
  std::vector<uint8_t> buffer_;
  OSMesaContext ctx_ = nullptr;
};

}  // namespace

bool GlAvailable() {
  return true;
}
std::string GlUnavailableReason() {
  return "";
}

std::unique_ptr<GlContext> CreateGlContext(int width_px, int height_px) {
  if (width_px <= 0 || height_px <= 0) throw RenderError("GL context size must be positive");
  return std::make_unique<OsMesaContext>(width_px, height_px);
}

}  // namespace rockbench::renders
