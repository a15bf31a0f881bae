// Per-instance data of the instanced draws (matches the shaders' attributes).
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace prep::render {

struct CapsuleInstance {
  glm::vec4 a_radius;  // end A, radius
  glm::vec4 b_glow;    // end B, source glow 0..1
  glm::vec3 colour;
};
struct BoxInstance {
  glm::mat4 model;  // the unit cube centred at the origin placed: translation, rotation, scale
  glm::vec4 colour_glow;
};
struct MarkerInstance {
  glm::vec4 centre_outer;
  glm::vec4 colour_inner;
};

}  // namespace prep::render
