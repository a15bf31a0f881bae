#include <imgui.h>

#include "app/demo/demo_app.h"
#include "app/ui/panels.h"

namespace prep::ui {

static_assert(kPanelFlags == (ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoBackground), "panels.h spells the flags out");

void place_panel(demo::DemoApp& app, bool right_column, const char* below, float width) {
  const float x = right_column ? static_cast<float>(app.width()) - width - kMargin : kMargin;
  float y = kMargin;
  if (below) {
    const auto it = app.panel_rects().find(below);
    if (it != app.panel_rects().end()) y = it->second.y + it->second.w + kMargin;
  }
  // Auto-sized windows settle over two or three frames: keep them in place until then.
  const ImGuiCond when = app.panel_frames() < 4 ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
  ImGui::SetNextWindowPos(ImVec2(x, y), when);
  ImGui::SetNextWindowSizeConstraints(ImVec2(width, 0.0f), ImVec2(width, static_cast<float>(app.height()) - y - kMargin));
}

}  // namespace prep::ui
