// The headless context. <GL/osmesa.h> pulls in GL/gl.h (whose prototypes would bind to libOSMesa
// directly), so this file includes only gl_loader.h and calls GL through prep::gl::finish().
#include <GL/osmesa.h>

#include "app/render/gl_loader.h"
#include "app/render/gl_context.h"

#include <string>
#include <vector>

namespace prep::render {

struct OsMesaContext::Impl {
  OSMesaContext context = nullptr;
  std::vector<std::uint8_t> buffer;  // RGBA, bottom row first
};

namespace {
gl::ProcAddress osmesa_proc(const char* name) { return reinterpret_cast<gl::ProcAddress>(OSMesaGetProcAddress(name)); }
}  // namespace

OsMesaContext::OsMesaContext(int width, int height) : impl_(std::make_unique<Impl>()), width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    throw std::runtime_error("OSMesa: bad image size " + std::to_string(width) + "x" + std::to_string(height));
  const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA,
                            OSMESA_DEPTH_BITS, 24,
                            OSMESA_STENCIL_BITS, 8,
                            OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION, 3,
                            OSMESA_CONTEXT_MINOR_VERSION, 3,
                            0};
  impl_->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!impl_->context) throw std::runtime_error("OSMesa: cannot create an OpenGL 3.3 core context");
  impl_->buffer.assign(static_cast<size_t>(width) * height * 4, 0);
  make_current();
}

OsMesaContext::~OsMesaContext() {
  if (!impl_->context) return;
  if (OSMesaGetCurrentContext() == impl_->context) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
  OSMesaDestroyContext(impl_->context);
}

// Mesa 22.3's OSMesa keeps the framebuffer objects OSMesaMakeCurrent creates in a list it never frees
// (they are still allocated after OSMesaDestroyContext): LeakSanitizer would report them at exit in
// sanitizer builds. Only allocations made inside libOSMesa are suppressed.
extern "C" const char* __lsan_default_suppressions() { return "leak:libOSMesa.so\n"; }

void OsMesaContext::make_current() {
  if (!OSMesaMakeCurrent(impl_->context, impl_->buffer.data(), GL_UNSIGNED_BYTE, width_, height_))
    throw std::runtime_error("OSMesa: cannot make the context current");
  gl::load(&osmesa_proc);
}

void OsMesaContext::end_frame() { gl::finish(); }

Image OsMesaContext::read_pixels() {
  gl::finish();  // after glFinish the buffer is the image
  return image_from_bottom_up(impl_->buffer.data(), width_, height_);
}

}  // namespace prep::render
