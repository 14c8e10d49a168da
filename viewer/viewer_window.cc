#include "viewer/viewer_window.h"

#include <algorithm>

#include <GLFW/glfw3.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "common/errors.h"

namespace viqu::viewer {
namespace {

std::string GlfwError() {
  const char* text = nullptr;
  const int code = glfwGetError(&text);
  if (code == GLFW_NO_ERROR) return "no GLFW error reported";
  return text != nullptr ? text : "GLFW error " + std::to_string(code);
}

}  // namespace

struct ViewerWindow::Impl {
  GLFWwindow* window = nullptr;
  std::vector<InputEvent> events;
  bool pressed[3] = {false, false, false};
  double last_x = 0, last_y = 0;

  static Impl* Of(GLFWwindow* w) { return static_cast<Impl*>(glfwGetWindowUserPointer(w)); }

  static void OnKey(GLFWwindow* w, int key, int /*scancode*/, int action, int /*mods*/) {
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
    InputEvent e;
    e.kind = InputEvent::Kind::kKey;
    e.key = key;
    Of(w)->events.push_back(e);
  }

  static void OnButton(GLFWwindow* w, int button, int action, int /*mods*/) {
    if (button < 0 || button > 2) return;
    Impl* self = Of(w);
    self->pressed[button] = action == GLFW_PRESS;
    glfwGetCursorPos(w, &self->last_x, &self->last_y);
  }

  static void OnCursor(GLFWwindow* w, double x, double y) {
    Impl* self = Of(w);
    const int button = self->pressed[0] ? 0 : self->pressed[1] ? 1 : self->pressed[2] ? 2 : -1;
    if (button >= 0) {
      int width = 0, height = 0;
      glfwGetWindowSize(w, &width, &height);
      InputEvent e;
      e.kind = InputEvent::Kind::kDrag;
      e.button = button;
      e.shift = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
      e.dx = (x - self->last_x) / std::max(height, 1);
      e.dy = (y - self->last_y) / std::max(height, 1);
      self->events.push_back(e);
    }
    self->last_x = x;
    self->last_y = y;
  }

  static void OnScroll(GLFWwindow* w, double /*dx*/, double dy) {
    InputEvent e;
    e.kind = InputEvent::Kind::kScroll;
    e.dy = dy;
    Of(w)->events.push_back(e);
  }
};

ViewerWindow::ViewerWindow(int width, int height, const std::string& title) : impl_(std::make_unique<Impl>()) {
  if (glfwInit() != GLFW_TRUE) throw RunError("viewer: cannot start GLFW (" + GlfwError() + "); is DISPLAY set?");
  glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_EGL_CONTEXT_API);
  glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
  glfwWindowHint(GLFW_SAMPLES, 0);
  glfwWindowHint(GLFW_DOUBLEBUFFER, GLFW_TRUE);
  impl_->window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (impl_->window == nullptr) {
    const std::string err = GlfwError();
    glfwTerminate();
    throw RunError("viewer: cannot open a " + std::to_string(width) + "x" + std::to_string(height) +
                   " window with an EGL OpenGL context (" + err + ")");
  }
  glfwSetWindowUserPointer(impl_->window, impl_.get());
  glfwSetKeyCallback(impl_->window, &Impl::OnKey);
  glfwSetMouseButtonCallback(impl_->window, &Impl::OnButton);
  glfwSetCursorPosCallback(impl_->window, &Impl::OnCursor);
  glfwSetScrollCallback(impl_->window, &Impl::OnScroll);
  glfwMakeContextCurrent(impl_->window);
  glfwSwapInterval(0);  // the viewer paces itself (Playback); never wait for a vertical blank
}

ViewerWindow::~ViewerWindow() {
  glfwDestroyWindow(impl_->window);
  glfwTerminate();
}

void ViewerWindow::MakeCurrent() {
  // Always: the simulation's renderer makes its own EGL context current behind GLFW's back, so
  // glfwGetCurrentContext() may name this window while another context is current.
  glfwMakeContextCurrent(impl_->window);
}

void ViewerWindow::PollEvents(double timeout_s) {
  if (timeout_s > 0) {
    glfwWaitEventsTimeout(timeout_s);
  } else {
    glfwPollEvents();
  }
}

std::vector<InputEvent> ViewerWindow::TakeEvents() {
  std::vector<InputEvent> out;
  out.swap(impl_->events);
  return out;
}

bool ViewerWindow::CloseRequested() const { return glfwWindowShouldClose(impl_->window) == GLFW_TRUE; }

void ViewerWindow::RequestClose() { glfwSetWindowShouldClose(impl_->window, GLFW_TRUE); }

void ViewerWindow::FramebufferSize(int* width, int* height) const {
  glfwGetFramebufferSize(impl_->window, width, height);
}

void ViewerWindow::SwapBuffers() { glfwSwapBuffers(impl_->window); }

void ViewerWindow::SetTitle(const std::string& title) { glfwSetWindowTitle(impl_->window, title.c_str()); }

cv::Mat ViewerWindow::ReadBackBuffer() const {
  int w = 0, h = 0;
  FramebufferSize(&w, &h);
  cv::Mat rgb(h, w, CV_8UC3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rgb.data);
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  cv::flip(bgr, bgr, 0);  // GL rows go bottom-up
  return bgr;
}

}  // namespace viqu::viewer
