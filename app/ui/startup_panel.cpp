#include <imgui.h>

#include "app/demo/demo_app.h"
#include "app/ui/panels.h"

namespace prep::ui {

void startup_panel(demo::DemoApp& app) {
  demo::WorldSession& s = app.session();
  const ImVec2 centre(0.5f * static_cast<float>(app.width()), 0.5f * static_cast<float>(app.height()));
  ImGui::SetNextWindowPos(ImVec2(centre.x, centre.y * 0.35f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(420.0f, 0.0f), ImGuiCond_Always);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoMove | kPanelFlags;
  if (ImGui::Begin("Starting", nullptr, flags)) {
    ImGui::Text("%s", s.scenario().name.c_str());
    ImGui::TextWrapped("%s", s.status().c_str());
    if (s.phase() == demo::SessionPhase::Failed) {
      ImGui::TextWrapped("Pick another scenario, or fix the file and open it again.");
    } else if (s.phase() == demo::SessionPhase::Loading) {
      // ImGui 1.86 has no indeterminate bar: dots that grow with time say that it is working.
      const int dots = static_cast<int>(ImGui::GetTime() * 3.0) % 4;
      ImGui::ProgressBar(0.0f, ImVec2(-1.0f, 0.0f), dots == 0 ? "loading" : dots == 1 ? "loading." : dots == 2 ? "loading.." : "loading...");
    } else {
      ImGui::ProgressBar(s.progress(), ImVec2(-1.0f, 0.0f));
      ImGui::TextDisabled("Trained once, then cached (policy cache).");
    }
    app.remember_panel("Starting");
  }
  ImGui::End();
}

}  // namespace prep::ui
