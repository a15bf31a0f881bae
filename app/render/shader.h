// GLSL programs built from the shaders in <repo>/shaders, embedded into the binary at build time.
#pragma once

#include <map>
#include <string>

#include "app/render/gl_api.h"

namespace prep::render {

// File name (e.g. "lit.frag") -> text, as in shaders/ when the binary was built.
const std::map<std::string, std::string>& embedded_shader_sources();

// The text of a shader with every line `#include "NAME"` replaced by that file's text.
// Throws std::runtime_error naming the shader when NAME is unknown.
std::string shader_source(const std::string& name);

// Compiles and links a program; throws std::runtime_error with the driver's log, naming the file.
GLuint build_program(const std::string& vertex_name, const std::string& fragment_name);

}  // namespace prep::render
