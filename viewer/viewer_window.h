#pragma once
// One GLFW window whose OpenGL context comes from EGL (GLFW_EGL_CONTEXT_API), so that it can
// share a thread with the simulation's off-screen EGL renderer: GLX and EGL contexts may not be
// switched on one thread under glvnd (eglMakeCurrent fails with EGL_BAD_ACCESS). Keys, mouse
// drags and scrolls are queued as events. GLFW stays out of this header.
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace viqu::viewer {

struct InputEvent {
  enum class Kind { kKey, kDrag, kScroll };
  Kind kind = Kind::kKey;
  int key = 0;           // GLFW key code (kKey)
  int button = 0;        // 0 left, 1 right, 2 middle (kDrag)
  bool shift = false;    // shift held (kDrag)
  double dx = 0, dy = 0; // kDrag: pointer motion as a share of the window height; kScroll: wheel steps
};

class ViewerWindow {
 public:
  // Throws viqu::RunError with GLFW's description when there is no display or no EGL context.
  ViewerWindow(int width, int height, const std::string& title);
  ~ViewerWindow();
  ViewerWindow(const ViewerWindow&) = delete;
  ViewerWindow& operator=(const ViewerWindow&) = delete;

  // Makes the window's context current on this thread (whatever GLFW believes is current).
  void MakeCurrent();
  // Processes window-system events, waiting at most `timeout_s` (0: do not wait).
  void PollEvents(double timeout_s = 0);
  std::vector<InputEvent> TakeEvents();
  bool CloseRequested() const;
  void RequestClose();
  void FramebufferSize(int* width, int* height) const;
  void SwapBuffers();
  void SetTitle(const std::string& title);
  // The back buffer (drawn, not yet swapped) as an 8-bit BGR image, top row first.
  cv::Mat ReadBackBuffer() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace viqu::viewer
