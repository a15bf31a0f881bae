#include "app/demo/demo_app.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "app/demo/picking.h"
#include "app/render/gl_api.h"
#include "app/ui/panels.h"
#include "engine/util/files.h"
#include "engine/world/floor.h"

namespace prep::demo {

using namespace prep::gl;

namespace {
using floor_plane::forward_of;
using floor_plane::kPi;
}  // namespace

DemoApp::DemoApp(render::GlContext& context, WorldSession& session, GLFWwindow* window, const render::RenderSettings& settings)
    : context_(context), session_(session) {
  context_.make_current();
  renderer_ = std::make_unique<render::Renderer>(settings);
  overlay_ = std::make_unique<render::Overlay>();
  ui_ = std::make_unique<render::ImGuiLayer>(window);
  // Opaque panels: the scene under them is not drawn at all (Renderer::set_covered).
  ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 1.0f;
  gl_description_ = gl::describe_context();
  scenarios = list_scenarios(default_scenarios_dir());
  params_path = "params.json";
  initial_goal_ = session_.goal();
  reset_camera();
}

DemoApp::~DemoApp() {
  context_.make_current();
  if (panel_cache_.framebuffer) glDeleteFramebuffers(1, &panel_cache_.framebuffer);
  if (panel_cache_.texture) glDeleteTextures(1, &panel_cache_.texture);
}

int DemoApp::triangles() const { return renderer_->triangles_last_frame() + overlay_->triangles_last_frame(); }

void DemoApp::reset_camera() {
  glm::vec2 at(0.0f);
  float heading = 0.0f;
  if (const World* w = session_.world()) {
    const WorldCharacter& u = w->characters()[static_cast<size_t>(w->user())];
    at = u.position;
    heading = u.heading;
  } else if (session_.scenario().user() >= 0) {
    const ScenarioCharacter& u = session_.scenario().characters[static_cast<size_t>(session_.scenario().user())];
    at = u.position;
    heading = u.heading;
  }
  // Look toward the source of influence when there is one (the opponent coming, the ball), else along the
  // way to the goal (the course) -- not along the heading of the moment: a character turning on the spot
  // would swing the view away from what it prepares for.
  glm::vec2 toward = session_.goal() - at;
  if (const World* w = session_.world()) {
    const WorldCharacter& u = w->characters()[static_cast<size_t>(w->user())];
    if (u.has_source && glm::length(u.source_object_position - at) > 1.0f) toward = u.source_object_position - at;
  }
  if (glm::length(toward) > 1.0f) heading = std::atan2(toward.x, toward.y);
  const glm::vec2 ahead = look_point();
  view.camera = render::Camera{};
  view.camera.target = glm::vec3(ahead.x, 0.9f, ahead.y);
  // Behind the character and over its left shoulder, high enough to see the course past it.
  view.camera.yaw = heading + kPi - 0.42f;
  view.camera.pitch = 0.36f;
  view.camera.distance = 7.0f;
}

glm::vec2 DemoApp::camera_forward() const {
  glm::vec3 f = view.camera.target - view.camera.eye();
  glm::vec2 g(f.x, f.z);
  const float len = glm::length(g);
  return len > 1e-5f ? g / len : glm::vec2(0.0f, -1.0f);
}

void DemoApp::update_camera(float dt) {
  const World* w = session_.world();
  if (w != camera_world_) {  // a new world: frame it afresh
    camera_world_ = w;
    if (w) reset_camera();
  }
  if (!view.follow || !w) return;
  const glm::vec2 ahead = look_point();
  view.camera.follow(glm::vec3(ahead.x, 0.0f, ahead.y), dt, 0.5f);
}

glm::vec2 DemoApp::look_point() const {
  // The engine's last tick (the drawing lags it by at most a tick: nothing the smoothing would show).
  if (const World* w = session_.world()) {
    const WorldCharacter& u = w->characters()[static_cast<size_t>(w->user())];
    glm::vec2 ahead = kLookAhead * forward_of(u.heading);
    // Part of the way to the source, so that the character and what it prepares for share the view.
    if (u.has_source) {
      const glm::vec2 d = u.source_object_position - u.position;
      const float len = glm::length(d);
      if (len > 1e-3f) ahead = std::min(kSourceShare * len, kMaxLookAhead) * (d / len);
    }
    return u.position + ahead;
  }
  const Scenario& s = session_.scenario();
  if (s.user() < 0) return glm::vec2(0.0f);
  const ScenarioCharacter& u = s.characters[static_cast<size_t>(s.user())];
  return u.position + kLookAhead * forward_of(u.heading);
}

void DemoApp::measure_clearance() {
  const World* w = session_.world();
  clearance_on_ = view.show_clearance && w;
  if (!clearance_on_) return;
  const std::shared_ptr<const Skeleton>& skeleton = w->assets().set->skeleton;
  if (!clearance_ || skeleton != clearance_skeleton_) {  // another motion set since: other volumes
    clearance_ = std::make_unique<ClearanceMeter>(*skeleton);
    clearance_skeleton_ = skeleton;
  }
  clearance_->measure(*w);
  // The world's last tick decides what is flagged; the scene's poses (between the last two ticks) say where
  // it is drawn, so that the red sits on the body as drawn (the renderer places the same volumes). The
  // scene lists the world's characters in their order.
  const std::vector<CharacterClearance>& result = clearance_->result();
  for (size_t i = 0; i < scene_.characters.size() && i < result.size(); ++i) scene_.characters[i].flagged = result[i].penetrating;
}

void DemoApp::skip_frame(float dt) {
  session_.steer(steer_direction());
  session_.advance(dt);
  update_camera(dt);
}

// A panel rectangle (pixels from the top-left) rounded out to whole pixels, in GL's bottom-left origin: what
// is cleared, stored and restored of each panel.
static bool gl_rect(const glm::vec4& r, int width, int height, int& x0, int& y0, int& x1, int& y1) {
  x0 = std::max(0, static_cast<int>(std::floor(r.x)));
  x1 = std::min(width, static_cast<int>(std::ceil(r.x + r.z)));
  const int top = std::max(0, static_cast<int>(std::floor(r.y))), bottom = std::min(height, static_cast<int>(std::ceil(r.y + r.w)));
  y0 = height - bottom;
  y1 = height - top;
  return x1 > x0 && y1 > y0;
}

// Copies the rectangles' pixels from one framebuffer to the other (0: the window's).
static void blit_rects(unsigned int from, unsigned int to, const std::vector<glm::vec4>& rects, int width, int height) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, from);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, to);
  int x0, y0, x1, y1;
  for (const glm::vec4& r : rects)
    if (gl_rect(r, width, height, x0, y0, x1, y1)) glBlitFramebuffer(x0, y0, x1, y1, x0, y0, x1, y1, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void DemoApp::frame(float dt) {
  // The first frames compile shaders and build the font atlas: the averages start after them.
  const bool timed = frames_drawn_ >= kUntimedFrames;
  start_frame_timing(timed);
  ++frames_drawn_;
  const int width = context_.width(), height = context_.height();

  auto t = Clock::now();
  session_.steer(steer_direction());
  const int ticks = session_.advance(dt);
  const World::StageTimes& st = session_.stage_times();
  engine_timings.control.add(st.control_ms);
  engine_timings.motion.add(st.motion_ms);
  engine_timings.synthesis.add(st.synthesis_ms);
  engine_timings.balance.add(st.balance_ms);
  engine_timings.total.add(st.total_ms);
  engine_timings.ticks.add(ticks);
  finish_stage(kUpdate, t, false, timed);

  t = Clock::now();
  scene_ = session_.scene(view.show_balance);
  measure_clearance();
  update_camera(dt);
  renderer_->prepare(scene_);
  finish_stage(kScene, t, true, timed);

  t = Clock::now();
  renderer_->shadow_pass();
  finish_stage(kShadow, t, true, timed);

  // The panels are laid out before the scene is drawn (ImGui's frame logic; nothing is drawn yet), so that
  // this frame's panel rectangles are known to the main pass: the scene is not shaded under them, and their
  // backgrounds are plain clears instead of ImGui's blended, textured quads (most of ImGui's cost on
  // llvmpipe). The panels draw everything else of themselves.
  t = Clock::now();
  panel_rects_.clear();
  const bool starting = session_.phase() != SessionPhase::Running;
  const bool ui = view.show_panels || starting || !view.caption.empty();
  if (ui) {
    ui_->begin_frame(width, height, dt);
    draw_panels();
  }
  std::vector<glm::vec4> covered;
  const ImVec2 scale = ui ? ImGui::GetIO().DisplayFramebufferScale : ImVec2(1.0f, 1.0f);  // display units -> pixels
  for (const auto& [name, r] : panel_rects_) covered.push_back(r * glm::vec4(scale.x, scale.y, scale.x, scale.y));
  double panels_ms = ms_since(t);

  t = Clock::now();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  renderer_->set_covered(covered);
  renderer_->main_pass(view.camera, 0, 0, width, height);
  last_view_projection_ = view.camera.view_projection(static_cast<float>(width) / std::max(height, 1));
  overlay_->draw(scene_, last_view_projection_);
  finish_stage(kMainPass, t, true, timed);

  // Drawing the panels (ImGui's textured, blended glyph quads) is a quarter of a frame on llvmpipe, and
  // idle panels change only in their figures. So while nobody works them (no mouse over them, no key held,
  // no popup open), their pixels from the last drawing are copied back into their rectangles, and they are
  // drawn anew every kPanelRedrawFrames frames (10 times a second at 60 frames/s) or whenever they move,
  // resize or are worked. ImGui's frame logic still runs every frame, so input is never missed.
  t = Clock::now();
  if (ui) {
    if (panels_need_redraw(covered, width, height) || starting || !view.caption.empty()) {
      const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
      glEnable(GL_SCISSOR_TEST);
      glClearColor(bg.x, bg.y, bg.z, 1.0f);
      int x0, y0, x1, y1;
      for (const glm::vec4& r : covered)
        if (gl_rect(r, width, height, x0, y0, x1, y1)) {
          glScissor(x0, y0, x1 - x0, y1 - y0);
          glClear(GL_COLOR_BUFFER_BIT);
        }
      glDisable(GL_SCISSOR_TEST);
      ui_->end_frame();
      store_panels(covered, width, height);
    } else {
      ui_->end_frame_without_drawing();
      restore_panels(width, height);
    }
  }
  if (sync_stages) glFinish();
  panels_ms += ms_since(t);
  if (timed) timings.add(kPanels, panels_ms);
}

bool DemoApp::panels_need_redraw(const std::vector<glm::vec4>& covered, int width, int height) const {
  const PanelCache& c = panel_cache_;
  if (!c.framebuffer || c.width != width || c.height != height || c.rects != covered) return true;
  if (c.frames_since_redraw + 1 >= kPanelRedrawFrames) return true;
  const ImGuiIO& io = ImGui::GetIO();
  bool mouse_down = false;
  for (bool down : io.MouseDown) mouse_down = mouse_down || down;
  // Anything drawn outside the remembered rectangles (a popup, a tooltip) or a widget being worked.
  return io.WantCaptureMouse || io.WantCaptureKeyboard || io.WantTextInput || mouse_down ||
         ImGui::IsPopupOpen(nullptr, ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel);
}

void DemoApp::store_panels(const std::vector<glm::vec4>& covered, int width, int height) {
  PanelCache& c = panel_cache_;
  if (!c.framebuffer || c.width != width || c.height != height) {
    if (!c.framebuffer) {
      glGenFramebuffers(1, &c.framebuffer);
      glGenTextures(1, &c.texture);
    }
    glBindTexture(GL_TEXTURE_2D, c.texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, c.framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, c.texture, 0);
    const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (!complete) {  // no cache: the panels are simply drawn every frame
      glDeleteFramebuffers(1, &c.framebuffer);
      glDeleteTextures(1, &c.texture);
      c = PanelCache{};
      return;
    }
    c.width = width;
    c.height = height;
  }
  blit_rects(0, c.framebuffer, covered, width, height);
  c.rects = covered;
  c.frames_since_redraw = 0;
}

void DemoApp::restore_panels(int width, int height) {
  PanelCache& c = panel_cache_;
  blit_rects(c.framebuffer, 0, c.rects, width, height);
  ++c.frames_since_redraw;
}

bool DemoApp::load_params_file(const std::string& path) {
  try {
    session_.set_params(load_params(path));
    message = "loaded the Params from " + path;
    return true;
  } catch (const std::exception& e) {
    message = e.what();  // names the file and the field
    return false;
  }
}

void DemoApp::remember_panel(const char* name) {
  const ImVec2 p = ImGui::GetWindowPos(), s = ImGui::GetWindowSize();
  panel_rects_[name] = glm::vec4(p.x, p.y, s.x, s.y);
}

void DemoApp::draw_panels() {
  if (!view.caption.empty()) {
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const float size = ImGui::GetFontSize() * view.caption_scale, shadow = std::max(1.0f, view.caption_scale);
    const ImVec2 at(8.0f * view.caption_scale, 6.0f * view.caption_scale);
    draw->AddText(ImGui::GetFont(), size, ImVec2(at.x + shadow, at.y + shadow), IM_COL32(255, 255, 255, 170), view.caption.c_str());
    draw->AddText(ImGui::GetFont(), size, at, IM_COL32(15, 15, 15, 255), view.caption.c_str());
  }
  if (session_.phase() != SessionPhase::Running) ui::startup_panel(*this);
  if (!view.show_panels) return;
  ++panel_frames_;
  ui::scenario_panel(*this);
  ui::preparation_panel(*this);
  ui::plots_panel(*this);
  ui::motion_folder_panel(*this);
  ui::timings_panel(*this);
  ui::camera_panel(*this);
  if (view.show_clearance) ui::clearance_panel(*this);
}

void DemoApp::open_scenario(const std::string& path) {
  try {
    const Scenario next = load_scenario(path);
    std::optional<Params> keep;
    if (next.params_file == session_.scenario().params_file) keep = session_.params();  // the edits stay
    session_.open(path, keep);
    initial_goal_ = session_.goal();
    camera_world_ = nullptr;
    reset_camera();
    message = "opened " + next.name;
  } catch (const std::exception& e) {
    message = e.what();
  }
}

namespace {
// A steering key's direction relative to the camera: (forward, right).
std::optional<glm::vec2> steer_key(int key) {
  switch (key) {
    case GLFW_KEY_W:
    case GLFW_KEY_UP: return glm::vec2(1.0f, 0.0f);
    case GLFW_KEY_S:
    case GLFW_KEY_DOWN: return glm::vec2(-1.0f, 0.0f);
    case GLFW_KEY_D:
    case GLFW_KEY_RIGHT: return glm::vec2(0.0f, 1.0f);
    case GLFW_KEY_A:
    case GLFW_KEY_LEFT: return glm::vec2(0.0f, -1.0f);
    default: return std::nullopt;
  }
}
}  // namespace

void DemoApp::on_key_state(int key, bool down) {
  if (!steer_key(key)) return;
  if (down) steer_keys_.insert(key);
  else steer_keys_.erase(key);
}

glm::vec2 DemoApp::steer_direction() const {
  // (forward, right) of the keys held; a key and its arrow held together count once, opposite keys cancel.
  bool forward = false, back = false, left = false, right = false;
  for (int key : steer_keys_) {
    const glm::vec2 d = *steer_key(key);
    forward = forward || d.x > 0.0f;
    back = back || d.x < 0.0f;
    right = right || d.y > 0.0f;
    left = left || d.y < 0.0f;
  }
  const float along = static_cast<float>(forward) - static_cast<float>(back);
  const float across = static_cast<float>(right) - static_cast<float>(left);
  const glm::vec2 f = camera_forward(), r(-f.y, f.x);
  return along * f + across * r;  // WorldSession::steer normalizes a diagonal
}

void DemoApp::on_key(int key) {
  if (view.camera.key(key)) return;
  switch (key) {
    case GLFW_KEY_1:
    case GLFW_KEY_2:
    case GLFW_KEY_3:
    case GLFW_KEY_4:
    case GLFW_KEY_5:
    case GLFW_KEY_6: {
      const auto action = static_cast<TargetAction>(key - GLFW_KEY_1);
      if (!session_.launch(action)) message = std::string("cannot launch ") + target_action_name(action) + " now";
      break;
    }
    case GLFW_KEY_SPACE:
    case GLFW_KEY_ENTER:
      if (!session_.launch_prepared()) message = "nothing to launch: no source of influence ahead";
      break;
    case GLFW_KEY_T: session_.set_auto(!session_.auto_launch()); break;
    case GLFW_KEY_P: session_.paused = !session_.paused; break;
    case GLFW_KEY_PERIOD: session_.step_once(); break;
    case GLFW_KEY_N:
      session_.restart();
      initial_goal_ = session_.goal();
      break;
    case GLFW_KEY_B: view.show_balance = !view.show_balance; break;
    case GLFW_KEY_O: view.show_clearance = !view.show_clearance; break;
    case GLFW_KEY_H: view.show_panels = !view.show_panels; break;
    case GLFW_KEY_C: view.follow = !view.follow; break;
    case GLFW_KEY_ESCAPE: quit_requested = true; break;
    default: break;
  }
}

void DemoApp::on_drag(float dx, float dy, bool pan) {
  view.camera.drag(dx, dy, pan, context_.height());
  if (pan) view.follow = false;
}

void DemoApp::on_scroll(float steps) { view.camera.scroll(steps); }

void DemoApp::on_click(glm::vec2 pixel, bool right) {
  if (right) {
    if (!session_.launch_prepared()) message = "nothing to launch: no source of influence ahead";
    return;
  }
  const Ray ray = pixel_ray(last_view_projection_, pixel, context_.width(), context_.height());
  if (const World* w = session_.world()) {
    if (const auto k = pick_object(*w, ray)) {
      session_.pick_object(*k);
      const ScenarioObject& o = session_.scenario().objects[static_cast<size_t>(*k)];
      message = std::string("source of influence: ") + object_type_name(o.type) + " (" + target_action_name(o.action) + ")";
      return;
    }
  }
  if (const auto p = ray_floor(ray)) session_.set_goal(*p);
}

std::string DemoApp::closing_report() const {
  const glm::vec2 g = session_.goal();
  char text[320];
  const World* w = session_.world();
  const glm::vec2 user = w ? w->characters()[static_cast<size_t>(w->user())].position : glm::vec2(0.0f);
  std::snprintf(text, sizeof text,
                "scenario %s, %s, t = %.2f s, goal %.2f %.2f -> %.2f %.2f, user at %.2f %.2f, %d launches, auto %s",
                session_.scenario().name.c_str(), phase_name(session_.phase()), w ? w->time() : 0.0f, initial_goal_.x,
                initial_goal_.y, g.x, g.y, user.x, user.y, w ? static_cast<int>(w->launches().size()) : 0,
                session_.auto_launch() ? "on" : "off");
  return text;
}

}  // namespace prep::demo
