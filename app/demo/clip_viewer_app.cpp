#include "app/demo/clip_viewer_app.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "app/render/gl_api.h"

namespace prep::demo {

using namespace prep::gl;

render::Camera default_camera(const render::Scene& scene) {
  render::Camera camera;
  if (!scene.characters.empty()) {
    const glm::vec3 root = scene.characters[0].joint_positions[0];
    camera.target = glm::vec3(root.x, 0.9f, root.z);
  }
  camera.yaw = 0.9f;
  camera.pitch = 0.28f;
  camera.distance = 4.8f;
  return camera;
}

ClipViewerApp::ClipViewerApp(render::GlContext& context, DemoMotions motions, GLFWwindow* window, const render::RenderSettings& settings)
    : context_(context), motions_(std::move(motions)) {
  context_.make_current();
  renderer_ = std::make_unique<render::Renderer>(settings);
  ui_ = std::make_unique<render::ImGuiLayer>(window);
  gl_description_ = gl::describe_context();
  if (!motions_.clips.empty()) camera = default_camera(clip_scene(motions_.clips[0], 0.0f, false));
}

void ClipViewerApp::frame(float dt) {
  start_frame_timing();
  const int width = context_.width(), height = context_.height();

  auto t = Clock::now();
  player.advance(motions_, dt);
  finish_stage(kUpdate, t, false);

  t = Clock::now();
  scene_ = motions_.clips.empty() ? render::Scene{} : clip_scene(motions_.clips[player.clip], player.time, show_props);
  if (follow && !scene_.characters.empty()) camera.follow(scene_.characters[0].joint_positions[0], dt);
  renderer_->prepare(scene_);
  finish_stage(kScene, t, true);

  t = Clock::now();
  renderer_->shadow_pass();
  finish_stage(kShadow, t, true);

  t = Clock::now();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  renderer_->main_pass(camera, 0, 0, width, height);
  last_view_projection_ = camera.view_projection(static_cast<float>(width) / std::max(height, 1));
  finish_stage(kMainPass, t, true);

  t = Clock::now();
  panel_rects_.clear();
  if (show_panels) {
    ui_->begin_frame(width, height, dt);
    draw_panels();
    ui_->end_frame();
  }
  finish_stage(kPanels, t, true);
}

void ClipViewerApp::remember_panel(const char* name) {
  const ImVec2 p = ImGui::GetWindowPos(), s = ImGui::GetWindowSize();
  panel_rects_[name] = glm::vec4(p.x, p.y, s.x, s.y);
}

void ClipViewerApp::draw_panels() {
  clip_player_panel();
  camera_panel();
  timings_panel();
}

void ClipViewerApp::clip_player_panel() {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(360, 0), ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Clip player")) {
    if (motions_.clips.empty()) {
      ImGui::TextUnformatted("no clips loaded");
    } else {
      const DemoClip& current = motions_.clips[player.clip];
      ImGui::Text("motions: %s", motions_.source.c_str());
      if (ImGui::BeginCombo("clip", current.clip.name.c_str())) {
        for (size_t i = 0; i < motions_.clips.size(); ++i) {
          const DemoClip& c = motions_.clips[i];
          const std::string label = c.clip.name + (c.role ? std::string("  (") + role_name(*c.role) + ")" : "");
          if (ImGui::Selectable(label.c_str(), static_cast<int>(i) == player.clip)) player.select(motions_, static_cast<int>(i));
        }
        ImGui::EndCombo();
      }
      if (ImGui::Button(player.playing ? "Pause" : "Play")) player.playing = !player.playing;
      ImGui::SameLine();
      if (ImGui::Button("<")) on_key(GLFW_KEY_LEFT);
      ImGui::SameLine();
      if (ImGui::Button(">")) on_key(GLFW_KEY_RIGHT);
      ImGui::SameLine();
      ImGui::Checkbox("loop", &player.loop);
      ImGui::SameLine();
      ImGui::Checkbox("obstacle", &show_props);
      ImGui::SliderFloat("speed", &player.speed, 0.0f, 2.0f, "%.2fx");
      const Clip& clip = motions_.clips[player.clip].clip;
      ImGui::SliderFloat("time", &player.time, 0.0f, clip.duration(), "%.2f s");
      ImGui::Text("frame %d / %d at %.0f fps%s", static_cast<int>(std::lround(player.time * clip.fps)),
                  clip.frame_count() - 1, clip.fps,
                  current.target_frame >= 0 ? ("   T_t = frame " + std::to_string(current.target_frame)).c_str() : "");
    }
    remember_panel("Clip player");
  }
  ImGui::End();
}

void ClipViewerApp::camera_panel() {
  ImGui::SetNextWindowPos(ImVec2(10, 200), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(360, 0), ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Camera")) {
    ImGui::Checkbox("follow the character", &follow);
    ImGui::SliderAngle("yaw", &camera.yaw, -180.0f, 180.0f);
    ImGui::SliderAngle("pitch", &camera.pitch, -10.0f, 85.0f);
    ImGui::SliderFloat("distance", &camera.distance, 0.5f, 40.0f, "%.1f m", ImGuiSliderFlags_Logarithmic);
    ImGui::SliderAngle("field of view", &camera.fov_y, 20.0f, 100.0f);
    if (ImGui::Button("Reset")) camera = default_camera(scene_);
    ImGui::SameLine();
    if (ImGui::Button("Side view") && !motions_.clips.empty()) {
      const render::Camera side = strip_camera(motions_.clips[player.clip]);
      camera.yaw = side.yaw;
      camera.pitch = 0.1f;
    }
    ImGui::TextDisabled("drag: orbit  right-drag: pan  wheel: zoom");
    ImGui::TextDisabled("Q/E R/F Z/X orbit, tilt, zoom  C follow");
    remember_panel("Camera");
  }
  ImGui::End();
}

void ClipViewerApp::timings_panel() {
  const float width = 300.0f;
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(context_.width()) - width - 10.0f, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(width, 0), ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Timings")) {
    ImGui::Text("%.1f frames/s  (%.2f ms per frame)", timings.fps(), timings.frame_ms());
    if (ImGui::BeginTable("stages", 2)) {
      for (int s = 0; s < kStageCount; ++s) {
        if (s == kFinish) continue;  // measured outside the frame by the caller, shown below when known
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(stage_name(s));
        ImGui::TableNextColumn();
        ImGui::Text("%6.2f ms", timings.average_ms(s));
      }
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(context_.headless() ? "finish" : "swap");
      ImGui::TableNextColumn();
      ImGui::Text("%6.2f ms", timings.average_ms(kFinish));
      ImGui::EndTable();
    }
    ImGui::Checkbox("time each stage (glFinish)", &sync_stages);
    ImGui::Text("%d triangles", renderer_->triangles_last_frame());
    ImGui::TextWrapped("%s", gl_description_.c_str());
    remember_panel("Timings");
  }
  ImGui::End();
}

void ClipViewerApp::on_key(int key) {
  if (camera.key(key)) return;
  const Clip* clip = motions_.clips.empty() ? nullptr : &motions_.clips[player.clip].clip;
  switch (key) {
    case GLFW_KEY_SPACE: player.playing = !player.playing; break;
    case GLFW_KEY_LEFT:
    case GLFW_KEY_RIGHT:
      if (clip) {
        player.playing = false;
        const float frame = std::round(player.time * clip->fps) + (key == GLFW_KEY_RIGHT ? 1.0f : -1.0f);
        player.time = std::clamp(frame / clip->fps, 0.0f, clip->duration());
      }
      break;
    case GLFW_KEY_UP: player.select(motions_, player.clip - 1); break;
    case GLFW_KEY_DOWN: player.select(motions_, player.clip + 1); break;
    case GLFW_KEY_C: follow = !follow; break;
    case GLFW_KEY_P: show_panels = !show_panels; break;
    case GLFW_KEY_ESCAPE: quit_requested = true; break;
    default: break;
  }
}

void ClipViewerApp::on_drag(float dx, float dy, bool pan) {
  camera.drag(dx, dy, pan, context_.height());
  if (pan) follow = false;
}

void ClipViewerApp::on_scroll(float steps) { camera.scroll(steps); }

std::string ClipViewerApp::closing_report() const {
  if (motions_.clips.empty()) return "no clips";
  const DemoClip& clip = motions_.clips[player.clip];
  return "camera yaw " + std::to_string(std::lround(camera.yaw * 180.0f / 3.14159265f)) + " deg, clip " + clip.clip.name +
         (player.playing ? " playing" : " paused") + " at " + std::to_string(player.time) + " s";
}

}  // namespace prep::demo
