#include <imgui.h>

#include <cstdio>
#include <string>

#include "app/demo/demo_app.h"
#include "app/demo/motion_folder.h"
#include "app/ui/panels.h"

namespace prep::ui {

void motion_folder_panel(demo::DemoApp& app) {
  const demo::MotionFolder* folder = app.motion_folder.get();
  if (folder == nullptr) return;
  const FolderScan& scan = folder->scan;
  place_panel(app, true, "Plots", kRightWidth);
  ImGui::SetNextWindowSizeConstraints(ImVec2(kRightWidth, 0.0f), ImVec2(kRightWidth, 0.6f * static_cast<float>(app.height())));
  if (ImGui::Begin("Motion capture", nullptr, kPanelFlags)) {
    int used = 0;
    for (const ScannedFile& f : scan.files) used += f.used ? 1 : 0;
    ImGui::Text("%s: %d of %zu takes, %s", scan.name.c_str(), used, scan.files.size(), scan.units.c_str());
    // Wrapped at the column's width: the panel sizes itself to its content, so it has no edge of its own.
    const float wrap = ImGui::GetCursorPosX() + kRightWidth - 2.0f * ImGui::GetStyle().WindowPadding.x;
    ImGui::PushTextWrapPos(wrap);
    std::string core;
    for (const ScannedClip& c : scan.clips)
      if (!c.core_as.empty()) core += (core.empty() ? "" : ", ") + c.core_as + " " + c.name;
    ImGui::TextDisabled("controller: %s", core.empty() ? "no loopable walk" : core.c_str());
    // ImGui's BulletText does not wrap: a bullet, then wrapped text beside it.
    auto bullet = [](const std::string& text) {
      ImGui::Bullet();
      ImGui::TextUnformatted(text.c_str());
    };
    for (const std::string& l : scan.lacks) bullet(l);
    for (const std::string& c : folder->changes) bullet("course: " + c);
    ImGui::PopTextWrapPos();
    // The clips, folded: each one's evidence in its tooltip.
    char header[48];
    std::snprintf(header, sizeof header, "clips (%zu)###clips", scan.clips.size());
    if (ImGui::CollapsingHeader(header) && ImGui::BeginTable("scanned clips", 3, ImGuiTableFlags_SizingFixedFit)) {
      for (const ScannedClip& c : scan.clips) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(c.name.c_str());
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", c.evidence.c_str());
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(role_name(c.role));
        ImGui::TableNextColumn();
        if (c.steer_deg_per_s != 0.0f)
          ImGui::Text("%+.0f deg/s", c.steer_deg_per_s);
        else if (c.loop)
          ImGui::Text("loop %d-%d", c.loop->first, c.loop->last);
        else if (c.target_frame)
          ImGui::Text("T_t %d", *c.target_frame);
      }
      ImGui::EndTable();
    }
    app.remember_panel("Motion capture");
  }
  ImGui::End();
}

}  // namespace prep::ui
