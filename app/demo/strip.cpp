#include "app/demo/strip.h"

#include <imgui.h>

#include <cstdio>
#include <stdexcept>

#include "app/demo/clip_view.h"
#include "app/render/gl_api.h"
#include "app/render/gl_context.h"
#include "app/render/imgui_layer.h"
#include "app/render/renderer.h"

namespace prep::demo {

using namespace prep::gl;

render::Image render_strip(const DemoClip& clip, const StripOptions& options) {
  if (options.frames < 1) throw std::invalid_argument("strip: --frames must be at least 1");
  if (clip.clip.frames.empty()) throw std::invalid_argument("strip: clip " + clip.clip.name + " has no frames");
  const int width = options.tile_width * options.frames, height = options.tile_height;
  render::OsMesaContext context(width, height);
  render::RenderSettings settings;
  settings.shadow_map_size = 2048;  // stills: sharper shadows, speed does not matter
  render::Renderer renderer(settings);
  const render::Camera side = strip_camera(clip);
  std::vector<float> times(static_cast<size_t>(options.frames));
  for (int i = 0; i < options.frames; ++i)
    times[i] = options.frames == 1 ? 0.0f : clip.clip.duration() * static_cast<float>(i) / (options.frames - 1);

  for (int i = 0; i < options.frames; ++i) {
    const render::Scene scene = clip_scene(clip, times[i], options.props);
    render::Camera camera = side;
    const glm::vec3 root = scene.characters[0].joint_positions[0];
    camera.target.x = root.x;
    camera.target.z = root.z;
    renderer.draw(scene, camera, i * options.tile_width, 0, options.tile_width, height);
  }
  // Tile borders: 2-pixel dark lines.
  glEnable(GL_SCISSOR_TEST);
  glClearColor(0.15f, 0.15f, 0.15f, 1.0f);
  for (int i = 1; i < options.frames; ++i) {
    glScissor(i * options.tile_width - 1, 0, 2, height);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  glDisable(GL_SCISSOR_TEST);

  if (options.labels) {
    render::ImGuiLayer ui(nullptr);
    ui.begin_frame(width, height, 1.0f / 60.0f);
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    for (int i = 0; i < options.frames; ++i) {
      char label[160];
      const int frame = static_cast<int>(times[i] * clip.clip.fps + 0.5f);
      std::snprintf(label, sizeof label, "%s%st=%.2f s (frame %d)", i == 0 ? clip.clip.name.c_str() : "",
                    i == 0 ? "\n" : "", times[i], frame);  // the clip's name on its own line: tiles are narrow
      const ImVec2 at(static_cast<float>(i * options.tile_width + 6), 6.0f);
      draw->AddText(ImVec2(at.x + 1, at.y + 1), IM_COL32(255, 255, 255, 160), label);
      draw->AddText(at, IM_COL32(20, 20, 20, 255), label);
    }
    ui.end_frame();
  }
  return context.read_pixels();
}

}  // namespace prep::demo
