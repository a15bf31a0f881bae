#include <imgui.h>

#include <algorithm>

#include "app/demo/demo_app.h"
#include "app/ui/panels.h"

namespace prep::ui {

void clearance_panel(demo::DemoApp& app) {
  // At the bottom between the columns, below where the followed character stands; its bottom edge is
  // placed every frame (not only at first, as the columns are), so that a description wrapping to one line
  // more grows the panel upward rather than off the screen.
  const float left = kMargin + kLeftWidth + kMargin, right = static_cast<float>(app.width()) - kRightWidth - 2.0f * kMargin;
  const float width = std::max(right - left, 200.0f);
  ImGui::SetNextWindowPos(ImVec2(0.5f * (left + right), static_cast<float>(app.height()) - kMargin), ImGuiCond_Always,
                          ImVec2(0.5f, 1.0f));
  ImGui::SetNextWindowSizeConstraints(ImVec2(width, 0.0f), ImVec2(width, 0.5f * static_cast<float>(app.height())));
  if (ImGui::Begin("Clearance", nullptr, kPanelFlags | ImGuiWindowFlags_NoMove)) {
    const ClearanceMeter* meter = app.clearance();
    const World* world = app.session().world();
    if (meter && world) {
      const int user = world->user();
      const Nearest& n = meter->result()[static_cast<size_t>(user)].object;
      int red = 0;
      for (const CharacterClearance& c : meter->result()) red += static_cast<int>(c.penetrating.size());
      if (n.capsule >= 0)
        ImGui::Text("user to the nearest object: %.1f cm        capsules in red: %d", 100.0f * n.distance, red);
      else
        ImGui::Text("user: no object within reach        capsules in red: %d", red);
      ImGui::TextWrapped("%s", meter->describe(*world, user, n).c_str());
    } else {
      ImGui::TextDisabled("measured once the world runs");
    }
    app.remember_panel("Clearance");
  }
  ImGui::End();
}

}  // namespace prep::ui
