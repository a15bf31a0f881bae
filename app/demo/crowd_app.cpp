#include "app/demo/crowd_app.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/demo/world_scene.h"
#include "app/render/gl_api.h"
#include "app/render/palette.h"
#include "engine/motion/kinematics.h"

namespace prep::demo {

using namespace prep::gl;

render::Camera crowd_camera(const Crowd& crowd) {
  render::Camera c;
  const glm::vec2 low = crowd.low(), high = crowd.high();
  // The lanes run toward +z: stand beyond their far ends, a little to the side, and look back along them.
  c.target = {0.35f * low.x + 0.65f * high.x, 0.9f, high.y - 0.25f * (high.y - low.y)};
  c.yaw = 0.45f;
  c.pitch = 0.32f;
  c.distance = 16.0f;
  c.far_plane = 400.0f;
  return c;
}

CrowdApp::CrowdApp(render::GlContext& context, Crowd& crowd, GLFWwindow* window, const render::RenderSettings& settings)
    : context_(context), crowd_(crowd) {
  context_.make_current();
  renderer_ = std::make_unique<render::Renderer>(settings);
  ui_ = std::make_unique<render::ImGuiLayer>(window);
  camera = crowd_camera(crowd_);
}

CrowdApp::~CrowdApp() = default;

int CrowdApp::advance(float dt) {
  if (paused) return 0;
  const float tick = crowd_.lane(0).params().runtime.fixed_dt;
  pending_ = std::min(pending_ + dt, kMaxTicksPerFrame * tick);
  int ticks = 0;
  const auto start = Clock::now();
  for (; pending_ >= tick - 1e-6f; pending_ -= tick, ++ticks) crowd_.step();
  if (ticks > 0) engine_ms_.add(ms_since(start) / ticks);
  return ticks;
}

void CrowdApp::skip_frame(float dt) { advance(dt); }

void CrowdApp::build_scene() {
  size_t count = 0;
  for (int i = 0; i < crowd_.lanes(); ++i) count += crowd_.lane(i).characters().size();
  scene_.characters.resize(count);
  scene_.objects.clear();
  by_distance_.clear();
  const glm::vec3 eye = camera.eye();
  const glm::mat4 view_projection = camera.view_projection(static_cast<float>(context_.width()) / std::max(context_.height(), 1));
  // In view: the pelvis projects inside the image, or a little beyond its edges (a body is wider than its root).
  const auto in_view = [&](const glm::vec3& p) {
    const glm::vec4 clip = view_projection * glm::vec4(p, 1.0f);
    return clip.w > 0.0f && std::abs(clip.x) <= 1.2f * clip.w && std::abs(clip.y) <= 1.2f * clip.w;
  };
  size_t k = 0;
  for (int i = 0; i < crowd_.lanes(); ++i) {
    const World& w = crowd_.lane(i);
    const std::shared_ptr<const Skeleton>& skeleton = w.assets().set->skeleton;
    for (size_t c = 0; c < w.characters().size(); ++c, ++k) {
      const WorldCharacter& wc = w.characters()[c];
      render::SceneCharacter& rc = scene_.characters[k];
      rc.skeleton = skeleton;
      forward_kinematics(*skeleton, wc.pose, rc.joint_positions, &rc.joint_rotations);
      rc.colour = static_cast<int>(c) == w.user() ? render::palette::kCharacter : render::palette::kOtherCharacter;
      rc.light = true;
      if (in_view(wc.pose.root_position)) by_distance_.emplace_back(glm::length(wc.pose.root_position - eye), k);
    }
    for (const WorldObject& o : w.objects()) {
      const auto type = render_type(o.spec.type);
      if (!type) continue;
      render::SceneObject ro;
      ro.type = *type;
      ro.position = o.position;
      ro.heading = o.spec.heading;
      ro.size = o.spec.size;
      ro.light = glm::length(o.position - eye) > kDetailedDistance;
      scene_.objects.push_back(ro);
    }
  }
  const size_t detailed = std::min<size_t>(kDetailedBodies, by_distance_.size());
  std::partial_sort(by_distance_.begin(), by_distance_.begin() + static_cast<long>(detailed), by_distance_.end());
  for (size_t d = 0; d < detailed; ++d) scene_.characters[by_distance_[d].second].light = false;
  scene_.focus = camera.target;
}

void CrowdApp::frame(float dt) {
  start_frame_timing();
  const int width = context_.width(), height = context_.height();

  auto t = Clock::now();
  advance(dt);
  finish_stage(kUpdate, t, false);

  t = Clock::now();
  build_scene();
  renderer_->prepare(scene_);
  finish_stage(kScene, t, true);

  t = Clock::now();
  renderer_->shadow_pass();
  finish_stage(kShadow, t, true);

  t = Clock::now();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  renderer_->main_pass(camera, 0, 0, width, height);
  finish_stage(kMainPass, t, true);

  t = Clock::now();
  if (show_panel) {
    ui_->begin_frame(width, height, dt);
    draw_panel();
    ui_->end_frame();
  }
  finish_stage(kPanels, t, true);
}

void CrowdApp::draw_panel() {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Crowd", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("%d characters, each preparing for its hurdle and its ball", crowd_.lanes());
    ImGui::Text("engine: %.2f ms per tick (both cores)", engine_ms_.value());
    ImGui::Text("%.0f frames/s, %d triangles", timings.fps(), renderer_->triangles_last_frame());
    ImGui::Text("%.0f s simulated, %d lanes started over", crowd_.time(), crowd_.restarts());
    ImGui::Checkbox("paused (P)", &paused);
  }
  ImGui::End();
}

void CrowdApp::on_key(int key) {
  if (camera.key(key)) return;
  const float metres = 0.05f * camera.distance;
  const glm::vec2 forward(-std::sin(camera.yaw), -std::cos(camera.yaw));  // the view's direction on the floor
  const glm::vec2 right(-forward.y, forward.x);
  auto move = [&](glm::vec2 d) { camera.target += glm::vec3(d.x, 0.0f, d.y) * metres; };
  switch (key) {
    case GLFW_KEY_W: case GLFW_KEY_UP: move(forward); break;
    case GLFW_KEY_S: case GLFW_KEY_DOWN: move(-forward); break;
    case GLFW_KEY_D: case GLFW_KEY_RIGHT: move(right); break;
    case GLFW_KEY_A: case GLFW_KEY_LEFT: move(-right); break;
    case GLFW_KEY_P: paused = !paused; break;
    case GLFW_KEY_H: show_panel = !show_panel; break;
    case GLFW_KEY_ESCAPE: quit_requested = true; break;
    default: break;
  }
}

void CrowdApp::on_drag(float dx, float dy, bool pan) { camera.drag(dx, dy, pan, context_.height()); }

void CrowdApp::on_scroll(float steps) { camera.scroll(steps); }

std::string CrowdApp::closing_report() const {
  char text[160];
  std::snprintf(text, sizeof text, "crowd of %d, %.1f s simulated, %d lanes started over, camera at (%.1f, %.1f)",
                crowd_.lanes(), crowd_.time(), crowd_.restarts(), camera.target.x, camera.target.z);
  return text;
}

int CrowdApp::triangles() const { return renderer_->triangles_last_frame(); }

}  // namespace prep::demo
