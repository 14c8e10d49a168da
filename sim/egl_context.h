#pragma once
// A headless OpenGL context through EGL, without any window system or surface.
#include <memory>
#include <string>

namespace viqu::sim {

// Owns one EGL display reference and one desktop-OpenGL context made current on the creating
// thread with no surface (EGL_NO_SURFACE; rendering goes to framebuffer objects only).
//
// Create() tries, in order: every device of the EGL device platform (EGL_EXT_platform_device:
// GPUs, and Mesa's software device), then Mesa's surfaceless platform. eglGetDisplay with the
// default display is not tried: it needs a window system. Not thread-safe: use a context from
// one thread at a time (MakeCurrent binds it to the calling thread).
class EglContext {
 public:
  // Which EGL platforms Create() may use.
  enum class Platform {
    kAuto,         // device platform first, then Mesa surfaceless
    kDevice,       // only the EGL device platform
    kSurfaceless,  // only Mesa's surfaceless platform
  };

  // Throws viqu::RunError naming every platform/device tried and the EGL error codes.
  static std::unique_ptr<EglContext> Create(Platform platform = Platform::kAuto);

  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  // Makes this context current on the calling thread (no-op if it already is).
  // Throws viqu::RunError on failure.
  void MakeCurrent() const;

  // Which platform and device the context lives on, and the GL renderer string,
  // e.g. "EGL device platform, device 0 (software): llvmpipe (LLVM 15.0.6, 256 bits)".
  const std::string& Description() const { return description_; }

 private:
  EglContext(void* display, void* context, std::string description);

  void* display_ = nullptr;  // EGLDisplay (void* to keep EGL headers out of this header)
  void* context_ = nullptr;  // EGLContext
  std::string description_;
};

}  // namespace viqu::sim
