#include <GLFW/glfw3.h>  // GLFW_INCLUDE_NONE is defined for every target that links imgui_backends

#include "app/render/gl_api.h"
#include "app/render/gl_context.h"

#include <cstdlib>
#include <string>

namespace prep::render {

using namespace prep::gl;

namespace {
std::string g_glfw_error;
void remember_glfw_error(int code, const char* text) { g_glfw_error = std::to_string(code) + ": " + text; }
gl::ProcAddress glfw_proc(const char* name) { return reinterpret_cast<gl::ProcAddress>(glfwGetProcAddress(name)); }
}  // namespace

GlfwContext::GlfwContext(int width, int height, const std::string& title, bool vsync) {
  glfwSetErrorCallback(remember_glfw_error);
  if (!glfwInit()) {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    std::string why = (!display || !*display) && (!wayland || !*wayland)
                          ? "no display (DISPLAY and WAYLAND_DISPLAY are not set)"
                          : "the display could not be opened (" + g_glfw_error + ")";
    throw NoDisplayError("cannot open a window: " + why +
                         ". Run with --headless, or under a virtual display: "
                         "xvfb-run -a -s \"-screen 0 1280x720x24\" prep-demo");
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw NoDisplayError("cannot create an OpenGL 3.3 core window (" + g_glfw_error +
                         "). Run with --headless to render through OSMesa instead");
  }
  make_current();
  glfwSwapInterval(vsync ? 1 : 0);
}

GlfwContext::~GlfwContext() {
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

int GlfwContext::width() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return w;
}

int GlfwContext::height() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return h;
}

void GlfwContext::make_current() {
  glfwMakeContextCurrent(window_);
  gl::load(&glfw_proc);
}

void GlfwContext::end_frame() { glfwSwapBuffers(window_); }

bool GlfwContext::should_close() const { return glfwWindowShouldClose(window_); }

Image GlfwContext::read_pixels() {
  const int w = width(), h = height();
  std::vector<std::uint8_t> buffer(static_cast<size_t>(w) * h * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, buffer.data());
  return image_from_bottom_up(buffer.data(), w, h);
}

}  // namespace prep::render
