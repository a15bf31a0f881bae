#include "app/render/shader.h"

#include <sstream>
#include <stdexcept>
#include <vector>

namespace prep::render {

using namespace prep::gl;

std::string shader_source(const std::string& name) {
  const auto& sources = embedded_shader_sources();
  const auto it = sources.find(name);
  if (it == sources.end()) throw std::runtime_error("shaders/" + name + ": no such shader");
  std::istringstream in(it->second);
  std::string line, out;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const std::string directive = "#include \"";
    if (line.compare(0, directive.size(), directive) == 0) {
      const size_t end = line.find('"', directive.size());
      if (end == std::string::npos) throw std::runtime_error("shaders/" + name + ":" + std::to_string(line_number) + ": bad #include");
      out += shader_source(line.substr(directive.size(), end - directive.size()));
      out += "#line " + std::to_string(line_number + 1) + "\n";
    } else {
      out += line + "\n";
    }
  }
  return out;
}

namespace {
GLuint compile(GLenum stage, const std::string& name) {
  const std::string text = shader_source(name);
  const GLuint shader = glCreateShader(stage);
  const char* ptr = text.c_str();
  glShaderSource(shader, 1, &ptr, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<size_t>(length) + 1, '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    glDeleteShader(shader);
    throw std::runtime_error("shaders/" + name + ": does not compile:\n" + log.data());
  }
  return shader;
}
}  // namespace

GLuint build_program(const std::string& vertex_name, const std::string& fragment_name) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex_name);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, fragment_name);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDetachShader(program, vs);
  glDetachShader(program, fs);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<size_t>(length) + 1, '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    glDeleteProgram(program);
    throw std::runtime_error("shaders/" + vertex_name + " + " + fragment_name + ": do not link:\n" + log.data());
  }
  return program;
}

}  // namespace prep::render
