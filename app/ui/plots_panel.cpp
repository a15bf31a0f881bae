#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "app/demo/demo_app.h"
#include "app/ui/panels.h"

namespace prep::ui {

namespace {

// One plot of the last samples, in a frame darker than ImGui's default so the panel reads as one block.
void plot(const char* id, const std::vector<float>& values, float lo, float hi, const char* overlay, float height) {
  ImGui::PushStyleColor(ImGuiCol_FrameBg, ImVec4(0.02f, 0.02f, 0.03f, 1.0f));
  static const float none = 0.0f;  // PlotLines wants a pointer even for no samples
  ImGui::PlotLines(id, values.empty() ? &none : values.data(), static_cast<int>(values.size()), 0, overlay, lo, hi,
                   ImVec2(ImGui::GetContentRegionAvail().x, height));
  ImGui::PopStyleColor();
}

}  // namespace

void plots_panel(demo::DemoApp& app) {
  const demo::WorldSession& s = app.session();
  place_panel(app, true, nullptr, kRightWidth);
  if (ImGui::Begin("Plots", nullptr, kPanelFlags)) {
    ImGui::Checkbox("support polygon and COM on the floor", &app.view.show_balance);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("key: B");
    // Its readout is a panel of its own (clearance_panel.cpp): this column has no room for it at 720 pixels.
    ImGui::Checkbox("clearance: body parts too deep in red", &app.view.show_clearance);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("key: O. Capsules of a body deeper than %.0f cm in an object or %.0f cm in another body",
                        100.0f * clearance_metric::kObjectTolerance, 100.0f * clearance_metric::kCharacterTolerance);
    const auto& samples = s.samples();
    std::vector<float> alpha, height, offset;
    alpha.reserve(samples.size());
    height.reserve(samples.size());
    offset.reserve(samples.size());
    float h_lo = 1e9f, h_hi = -1e9f;
    for (const demo::TickSample& t : samples) {
      alpha.push_back(t.alpha);
      height.push_back(t.com_height);
      offset.push_back(t.com_offset);
      h_lo = std::min(h_lo, t.com_height);
      h_hi = std::max(h_hi, t.com_height);
    }
    const float seconds = samples.empty() ? 0.0f : samples.back().time - samples.front().time;
    char text[96];
    std::snprintf(text, sizeof text, "alpha %.2f", alpha.empty() ? 0.0f : alpha.back());
    ImGui::Text("last %.0f s, one sample per tick", seconds);
    plot("##alpha", alpha, 0.0f, 1.0f, text, 56.0f);
    // The COM height: the axis spans what was seen (at least 10 cm), so a lowered hip shows as a dip.
    if (height.empty()) h_lo = 0.0f, h_hi = 1.0f;
    const float mid = 0.5f * (h_lo + h_hi), half = std::max(0.05f, 0.5f * (h_hi - h_lo) + 0.01f);
    std::snprintf(text, sizeof text, "COM height %.3f m", height.empty() ? 0.0f : height.back());
    plot("##com height", height, mid - half, mid + half, text, 48.0f);
    const bool inside = !samples.empty() && samples.back().com_inside;
    std::snprintf(text, sizeof text, "COM to support centre %.3f m%s", offset.empty() ? 0.0f : offset.back(),
                  samples.empty() ? "" : inside ? " (inside)" : " (outside)");
    plot("##com offset", offset, 0.0f, 0.3f, text, 40.0f);
    app.remember_panel("Plots");
  }
  ImGui::End();
}

}  // namespace prep::ui
