#include <imgui.h>

#include "app/demo/demo_app.h"
#include "app/ui/panels.h"

namespace prep::ui {

void camera_panel(demo::DemoApp& app) {
  place_panel(app, true, "Timings", kRightWidth);
  if (ImGui::Begin("Camera", nullptr, kPanelFlags)) {
    render::Camera& c = app.view.camera;
    ImGui::Checkbox("follow (C)", &app.view.follow);
    ImGui::SameLine();
    if (ImGui::Button("reset")) app.reset_camera();
    ImGui::SameLine();
    ImGui::Checkbox("panels (H)", &app.view.show_panels);
    ImGui::SliderAngle("yaw", &c.yaw, -180.0f, 180.0f);
    ImGui::SliderFloat("distance", &c.distance, 1.0f, 40.0f, "%.1f m", ImGuiSliderFlags_Logarithmic);
    ImGui::TextDisabled("drag: orbit, right-drag: pan, wheel: zoom");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("keys: Q/E orbit, R/F tilt, Z/X zoom");
    app.remember_panel("Camera");
  }
  ImGui::End();
}

}  // namespace prep::ui
