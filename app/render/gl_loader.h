// Loading prep's GL pointer table (gl_api.h) from a context's get-proc-address. Kept free of GL headers so
// that files which must include GL/gl.h (OSMesa's header does) can still load the table.
#pragma once

#include <string>

namespace prep::gl {

using ProcAddress = void (*)();
using GetProcAddress = ProcAddress (*)(const char* name);

// Fills every pointer from `get_proc` (call with the context current). Throws std::runtime_error naming
// the functions the context does not provide.
void load(GetProcAddress get_proc);

// True once load() succeeded.
bool loaded();

// glFinish through the table.
void finish();

// "OpenGL 4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)" of the current context.
std::string describe_context();

}  // namespace prep::gl
