#pragma once
/// The off-screen GL context behind the renderer: the one place that knows OSMesa, so that
/// another back end (EGL with a pbuffer or surfaceless context) can replace it.
#include <cstdint>
#include <memory>
#include <string>

namespace rockbench::renders {

/// A current GL context (legacy, fixed-function GL is available) drawing into an RGBA8 buffer
/// of fixed size. Rows of pixels() are bottom-up, as glReadPixels returns them.
class GlContext {
 public:
  virtual ~GlContext() = default;
  /// Makes this context current on the calling thread.
  virtual void MakeCurrent() = 0;
  /// Finishes all GL drawing and returns the RGBA pixels, bottom row first.
  virtual const uint8_t* Finish() = 0;
  virtual int width_px() const = 0;
  virtual int height_px() const = 0;
};

/// True when this build can create a GL context (built with OSMesa).
bool GlAvailable();
/// Why GlAvailable() is false, as a message for the user ("" when it is true).
std::string GlUnavailableReason();

/// A context of w x h pixels, made current. Throws RenderError: "this build has no OSMesa" when
/// built without it, or when the context cannot be created.
std::unique_ptr<GlContext> CreateGlContext(int width_px, int height_px);

}  // namespace rockbench::renders
