// Where the renderer draws: an off-screen OSMesa context (headless) or a GLFW window. Both load the GL
// pointer table (gl_api.h) from their own get-proc-address when created, so one binary drives either.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include "app/render/image.h"

struct GLFWwindow;

namespace prep::render {

class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual int width() const = 0;   // framebuffer size in pixels
  virtual int height() const = 0;
  virtual bool headless() const = 0;
  // Makes the context current and reloads the GL pointer table from it.
  virtual void make_current() = 0;
  // Ends a frame: OSMesa waits for the drawing to finish; GLFW swaps buffers.
  virtual void end_frame() = 0;
  // The frame just drawn (call before end_frame() on GLFW, which then reads the back buffer).
  virtual Image read_pixels() = 0;
};

// A headless OpenGL 3.3+ core context (llvmpipe) drawing into memory.
class OsMesaContext final : public GlContext {
 public:
  OsMesaContext(int width, int height);  // throws std::runtime_error when OSMesa cannot create it
  ~OsMesaContext() override;
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  int width() const override { return width_; }
  int height() const override { return height_; }
  bool headless() const override { return true; }
  void make_current() override;
  void end_frame() override;
  Image read_pixels() override;  // finishes drawing, then copies the buffer (no glReadPixels needed)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_;
  int height_;
};

// Thrown when no window can be opened (no display); the message says what to do instead.
class NoDisplayError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A window with an OpenGL 3.3 core context.
class GlfwContext final : public GlContext {
 public:
  GlfwContext(int width, int height, const std::string& title, bool vsync);  // throws NoDisplayError
  ~GlfwContext() override;
  GlfwContext(const GlfwContext&) = delete;
  GlfwContext& operator=(const GlfwContext&) = delete;

  int width() const override;
  int height() const override;
  bool headless() const override { return false; }
  void make_current() override;
  void end_frame() override;
  Image read_pixels() override;  // glReadPixels of the back buffer

  GLFWwindow* window() const { return window_; }
  bool should_close() const;

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace prep::render
