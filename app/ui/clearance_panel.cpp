#include <imgui.h>

#include <algorithm>
#include <string>

#include "app/demo/demo_app.h"
#include "app/ui/panels.h"

namespace prep::ui {

namespace {

// Text wrapped at spaces, but not after a comma: ImGui's wrapping also breaks after a full stop or a
// comma, which splits a position such as "(0.00, 3.50)".
void wrapped_at_spaces(const std::string& text) {
  const float width = ImGui::GetContentRegionAvail().x;
  std::string line;
  size_t at = 0;
  while (at < text.size()) {
    size_t space = text.find(' ', at);
    while (space != std::string::npos && space > 0 && text[space - 1] == ',') space = text.find(' ', space + 1);
    const std::string word = text.substr(at, space == std::string::npos ? std::string::npos : space - at);
    const std::string longer = line.empty() ? word : line + " " + word;
    if (!line.empty() && ImGui::CalcTextSize(longer.c_str()).x > width) {
      ImGui::TextUnformatted(line.c_str());
      line = word;
    } else {
      line = longer;
    }
    at = space == std::string::npos ? text.size() : space + 1;
  }
  if (!line.empty()) ImGui::TextUnformatted(line.c_str());
}

}  // namespace

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
      wrapped_at_spaces(meter->describe(*world, user, n));
    } else {
      ImGui::TextDisabled("measured once the world runs");
    }
    app.remember_panel("Clearance");
  }
  ImGui::End();
}

}  // namespace prep::ui
