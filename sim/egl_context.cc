#include "sim/egl_context.h"

#include <cstring>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>

#include "common/errors.h"

namespace viqu::sim {
namespace {

std::string EglErrorName(EGLint code) {
  switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: {
      std::ostringstream s;
      s << "0x" << std::hex << code;
      return s.str();
    }
  }
}

// Last EGL error of this thread, as text.
std::string LastEglError() { return EglErrorName(eglGetError()); }

bool HasExtension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
    const bool starts = (p == list || p[-1] == ' ');
    const bool ends = (p[n] == '\0' || p[n] == ' ');
    if (starts && ends) return true;
  }
  return false;
}

// eglInitialize is not reference counted and eglTerminate destroys every context of a display,
// so displays shared by several EglContext objects in one process are counted here.
std::mutex g_display_mutex;
std::map<EGLDisplay, int> g_display_refs;

void AcquireDisplay(EGLDisplay display) {
  std::lock_guard<std::mutex> lock(g_display_mutex);
  ++g_display_refs[display];
}

void ReleaseDisplay(EGLDisplay display) {
  std::lock_guard<std::mutex> lock(g_display_mutex);
  auto it = g_display_refs.find(display);
  if (it == g_display_refs.end()) return;
  if (--it->second == 0) {
    g_display_refs.erase(it);
    eglTerminate(display);
  }
}

struct Attempt {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

// Initialises `display`, creates a desktop-GL context on it and makes it current without a
// surface. On failure appends the reason to `log` and returns an empty attempt.
Attempt TryDisplay(EGLDisplay display, const std::string& what, std::ostringstream* log) {
  if (display == EGL_NO_DISPLAY) {
    *log << "  " << what << ": no display (" << LastEglError() << ")\n";
    return {};
  }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    *log << "  " << what << ": eglInitialize failed (" << LastEglError() << ")\n";
    return {};
  }
  AcquireDisplay(display);
  auto fail = [&](const std::string& step) {
    *log << "  " << what << ": " << step << " failed (" << LastEglError() << ")\n";
    ReleaseDisplay(display);
    return Attempt{};
  };
  if (!HasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
    *log << "  " << what << ": no EGL_KHR_surfaceless_context\n";
    ReleaseDisplay(display);
    return {};
  }
  if (!eglBindAPI(EGL_OPENGL_API)) return fail("eglBindAPI(EGL_OPENGL_API)");

  // The framebuffer is an FBO made by MuJoCo, so the config only has to support desktop GL.
  const EGLint attribs_pbuffer[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                    EGL_OPENGL_BIT, EGL_NONE};
  const EGLint attribs_any[] = {EGL_SURFACE_TYPE, EGL_DONT_CARE, EGL_RENDERABLE_TYPE,
                                EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint num_configs = 0;
  if (!eglChooseConfig(display, attribs_pbuffer, &config, 1, &num_configs) || num_configs < 1) {
    if (!eglChooseConfig(display, attribs_any, &config, 1, &num_configs) || num_configs < 1) {
      return fail("eglChooseConfig (desktop OpenGL)");
    }
  }
  // No profile requested: MuJoCo 2.2 renders with the compatibility profile.
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
  if (context == EGL_NO_CONTEXT) return fail("eglCreateContext");
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    const std::string err = LastEglError();
    eglDestroyContext(display, context);
    *log << "  " << what << ": eglMakeCurrent(EGL_NO_SURFACE) failed (" << err << ")\n";
    ReleaseDisplay(display);
    return {};
  }
  return Attempt{display, context};
}

std::string DeviceLabel(EGLDeviceEXT device, PFNEGLQUERYDEVICESTRINGEXTPROC query_string) {
  if (!query_string) return "";
  const char* ext = query_string(device, EGL_EXTENSIONS);
  std::string label;
  if (HasExtension(ext, "EGL_EXT_device_drm")) {
    const char* file = query_string(device, EGL_DRM_DEVICE_FILE_EXT);
    if (file) label = file;
  }
  if (HasExtension(ext, "EGL_MESA_device_software")) label += label.empty() ? "software" : ", software";
  eglGetError();  // a device without a DRM file may leave an error behind; it is not ours
  return label;
}

}  // namespace

std::unique_ptr<EglContext> EglContext::Create(Platform platform) {
  std::ostringstream log;
  const char* client_ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!client_ext) eglGetError();  // EGL 1.4 without client extensions: handled below

  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  const bool has_platform_base = HasExtension(client_ext, "EGL_EXT_platform_base") && get_platform_display;

  // 1. EGL device platform: every device, in the order EGL lists them.
  if (platform == Platform::kSurfaceless) {
    log << "  EGL device platform: not asked for\n";
  } else if (!has_platform_base || !HasExtension(client_ext, "EGL_EXT_platform_device")) {
    log << "  EGL device platform: not offered (client extensions: "
        << (client_ext ? client_ext : "none") << ")\n";
  } else {
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto query_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    EGLint num_devices = 0;
    if (!query_devices || !query_devices(0, nullptr, &num_devices) || num_devices < 1) {
      log << "  EGL device platform: eglQueryDevicesEXT found no device (" << LastEglError() << ")\n";
    } else {
      std::vector<EGLDeviceEXT> devices(static_cast<size_t>(num_devices));
      query_devices(num_devices, devices.data(), &num_devices);
      for (EGLint i = 0; i < num_devices; ++i) {
        const std::string label = DeviceLabel(devices[i], query_string);
        const std::string what =
            "EGL device platform, device " + std::to_string(i) + (label.empty() ? "" : " (" + label + ")");
        EGLDisplay display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        const Attempt a = TryDisplay(display, what, &log);
        if (a.context != EGL_NO_CONTEXT) {
          return std::unique_ptr<EglContext>(new EglContext(a.display, a.context, what));
        }
      }
    }
  }

  // 2. Mesa's surfaceless platform.
  if (platform == Platform::kDevice) {
    log << "  Mesa surfaceless platform: not asked for\n";
  } else if (!has_platform_base || !HasExtension(client_ext, "EGL_MESA_platform_surfaceless")) {
    log << "  Mesa surfaceless platform: not offered\n";
  } else {
    const std::string what = "Mesa surfaceless platform";
    EGLDisplay display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    const Attempt a = TryDisplay(display, what, &log);
    if (a.context != EGL_NO_CONTEXT) {
      return std::unique_ptr<EglContext>(new EglContext(a.display, a.context, what));
    }
  }
  throw RunError(
      "cannot create a headless OpenGL context through EGL; tried:\n" + log.str() +
      "Install Mesa's EGL drivers (libegl-mesa0, libgl1-mesa-dri) or a GPU driver with EGL device support.");
}

EglContext::EglContext(void* display, void* context, std::string description)
    : display_(display), context_(context) {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  description_ = std::move(description) + ": " + (renderer ? renderer : "unknown GL renderer");
}

EglContext::~EglContext() {
  if (eglGetCurrentContext() == static_cast<EGLContext>(context_)) {
    eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  eglDestroyContext(static_cast<EGLDisplay>(display_), static_cast<EGLContext>(context_));
  ReleaseDisplay(static_cast<EGLDisplay>(display_));
}

void EglContext::MakeCurrent() const {
  if (eglGetCurrentContext() == static_cast<EGLContext>(context_)) return;
  if (!eglBindAPI(EGL_OPENGL_API) ||
      !eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE,
                      static_cast<EGLContext>(context_))) {
    throw RunError("EGL: cannot make the rendering context current (" + LastEglError() + ") on " +
                   description_);
  }
}

}  // namespace viqu::sim
