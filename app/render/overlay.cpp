#include "app/render/overlay.h"

#include <cmath>
#include <cstddef>
#include <glm/gtc/type_ptr.hpp>

#include "app/render/palette.h"
#include "app/render/shader.h"

namespace prep::render {

using namespace prep::gl;

namespace {

constexpr float kFullTurn = 2.0f * 3.14159265358979f;  // rad; not kPi: renderer.cpp, in the same unity batch, has one

void triangle(std::vector<OverlayVertex>& out, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec4& colour) {
  out.push_back({a, colour});
  out.push_back({b, colour});
  out.push_back({c, colour});
}

void quad(std::vector<OverlayVertex>& out, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
          const glm::vec4& colour) {
  triangle(out, a, b, c, colour);
  triangle(out, a, c, d, colour);
}

glm::vec3 on_floor(glm::vec2 p, float lift) { return {p.x, lift, p.y}; }

}  // namespace

OverlayGeometry build_overlay(const std::vector<BalanceView>& balance) {
  OverlayGeometry g;
  const glm::vec4 fill(palette::kSupport, 0.35f), outline(palette::kSupport, 0.95f);
  for (const BalanceView& b : balance) {
    const auto& hull = b.support;
    // The hull is convex and counter-clockwise: a fan fills it.
    for (size_t i = 1; i + 1 < hull.size(); ++i)
      triangle(g.depth_tested, on_floor(hull[0], kOverlayLift), on_floor(hull[i], kOverlayLift),
               on_floor(hull[i + 1], kOverlayLift), fill);
    // The outline: a band of kSupportOutline along each edge, on its inner side (the side of the vertices'
    // mean, whatever the winding).
    glm::vec2 centre(0.0f);
    for (const glm::vec2& p : hull) centre += p;
    if (!hull.empty()) centre /= static_cast<float>(hull.size());
    for (size_t i = 0; hull.size() >= 2 && i < hull.size(); ++i) {
      const glm::vec2 a = hull[i], c = hull[(i + 1) % hull.size()];
      const glm::vec2 edge = c - a;
      const float len = std::sqrt(edge.x * edge.x + edge.y * edge.y);
      if (len < 1e-5f) continue;
      glm::vec2 n(-edge.y / len, edge.x / len);
      if ((centre.x - a.x) * n.x + (centre.y - a.y) * n.y < 0.0f) n = -n;
      const float lift = kOverlayLift + 0.001f;
      quad(g.depth_tested, on_floor(a, lift), on_floor(c, lift), on_floor(c + n * kSupportOutline, lift),
           on_floor(a + n * kSupportOutline, lift), outline);
    }
    // The COM on the floor: a disc.
    const glm::vec4 com_colour(b.com_inside ? palette::kComInside : palette::kComOutside, 1.0f);
    const glm::vec2 com_floor(b.com.x, b.com.z);
    const int segments = 20;
    for (int s = 0; s < segments; ++s) {
      const float a0 = kFullTurn * s / segments, a1 = kFullTurn * (s + 1) / segments;
      triangle(g.depth_tested, on_floor(com_floor, kOverlayLift + 0.002f),
               on_floor(com_floor + kComDiscRadius * glm::vec2(std::cos(a0), std::sin(a0)), kOverlayLift + 0.002f),
               on_floor(com_floor + kComDiscRadius * glm::vec2(std::cos(a1), std::sin(a1)), kOverlayLift + 0.002f),
               com_colour);
    }
    // The plumb line: two crossed vertical strips, visible from any side.
    const glm::vec3 top = b.com, bottom(b.com.x, 0.0f, b.com.z);
    const float w = 0.5f * kPlumbWidth;
    quad(g.depth_tested, bottom + glm::vec3(-w, 0, 0), bottom + glm::vec3(w, 0, 0), top + glm::vec3(w, 0, 0),
         top + glm::vec3(-w, 0, 0), com_colour);
    quad(g.depth_tested, bottom + glm::vec3(0, 0, -w), bottom + glm::vec3(0, 0, w), top + glm::vec3(0, 0, w),
         top + glm::vec3(0, 0, -w), com_colour);
    // The COM: an octahedron on top of everything.
    const float d = kComDiamond;
    const glm::vec3 axes[6] = {{d, 0, 0}, {0, 0, d}, {-d, 0, 0}, {0, 0, -d}, {0, d, 0}, {0, -d, 0}};
    for (int k = 0; k < 4; ++k) {
      const glm::vec3 p = top + axes[k], q = top + axes[(k + 1) % 4];
      const glm::vec4 shade(glm::vec3(com_colour) * (k % 2 ? 0.8f : 1.0f), 1.0f);
      triangle(g.on_top, top + axes[4], p, q, shade);
      triangle(g.on_top, top + axes[5], q, p, shade * glm::vec4(0.75f, 0.75f, 0.75f, 1.0f));
    }
  }
  return g;
}

Overlay::Overlay() {
  program_ = build_program("overlay.vert", "overlay.frag");
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  glGenBuffers(1, &vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex), reinterpret_cast<const void*>(offsetof(OverlayVertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex), reinterpret_cast<const void*>(offsetof(OverlayVertex, colour)));
  glBindVertexArray(0);
}

Overlay::~Overlay() {
  glDeleteProgram(program_);
  glDeleteBuffers(1, &vbo_);
  glDeleteVertexArrays(1, &vao_);
}

void Overlay::draw_batch(const std::vector<OverlayVertex>& vertices) {
  if (vertices.empty()) return;
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(OverlayVertex)), vertices.data(), GL_STREAM_DRAW);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices.size()));
  triangles_ += static_cast<int>(vertices.size() / 3);
}

void Overlay::draw(const Scene& scene, const glm::mat4& view_projection) {
  triangles_ = 0;
  if (scene.balance.empty()) return;
  const OverlayGeometry g = build_overlay(scene.balance);
  glUseProgram(program_);
  glUniformMatrix4fv(glGetUniformLocation(program_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_projection));
  glBindVertexArray(vao_);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);  // translucent: leave the scene's depth as it is
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(-1.0f, -8.0f);  // above the floor (and its markers) without z-fighting
  draw_batch(g.depth_tested);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_DEPTH_TEST);
  draw_batch(g.on_top);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace prep::render
