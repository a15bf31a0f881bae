#include "app/render/gl_api.h"

#include <stdexcept>

namespace prep::gl {

#define PREP_GL_DEFINE_POINTER(type, name) type name = nullptr;
PREP_GL_FUNCTIONS(PREP_GL_DEFINE_POINTER)
#undef PREP_GL_DEFINE_POINTER

namespace {
bool g_loaded = false;
}

void load(GetProcAddress get_proc) {
  std::string missing;
#define PREP_GL_LOAD_POINTER(type, name)                   \
  name = reinterpret_cast<type>(get_proc(#name));          \
  if (!name) missing += (missing.empty() ? "" : ", ") + std::string(#name);
  PREP_GL_FUNCTIONS(PREP_GL_LOAD_POINTER)
#undef PREP_GL_LOAD_POINTER
  g_loaded = missing.empty();
  if (!g_loaded) throw std::runtime_error("the OpenGL context does not provide: " + missing);
}

bool loaded() { return g_loaded; }

void finish() { glFinish(); }

std::string describe_context() {
  auto text = [](GLenum what) {
    const GLubyte* s = glGetString(what);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return "OpenGL " + text(GL_VERSION) + ", " + text(GL_RENDERER);
}

}  // namespace prep::gl
