#include <imgui.h>

#include "app/demo/demo_app.h"
#include "app/demo/motion_folder.h"
#include "app/ui/panels.h"

namespace prep::ui {

namespace {

void row(const char* name, double ms) {
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextUnformatted(name);
  ImGui::TableNextColumn();
  ImGui::Text("%6.2f ms", ms);
}

}  // namespace

void timings_panel(demo::DemoApp& app) {
  place_panel(app, true, app.motion_folder ? "Motion capture" : "Plots", kRightWidth);
  if (ImGui::Begin("Timings", nullptr, kPanelFlags)) {
    const demo::Timings& t = app.timings;
    const demo::EngineTimings& e = app.engine_timings;
    ImGui::Text("%.1f frames/s  (%.2f ms per frame)", t.fps(), t.frame_ms());
    ImGui::Text("engine: %.2f ticks/frame, step %.1f ms", e.ticks.value(), 1000.0 * app.session().params().runtime.fixed_dt);
    if (ImGui::BeginTable("stages", 2)) {
      // The engine's share per frame (World::StageTimes, all characters, all of the frame's ticks).
      row("controller", e.control.value());
      row("motion graph", e.motion.value());
      row("synthesis", e.synthesis.value());
      row("balance, goals", e.balance.value());
      row("engine total", e.total.value());
      for (int s = demo::kScene; s < demo::kStageCount; ++s) {
        if (s == demo::kFinish) continue;
        row(demo::stage_name(s), t.average_ms(s));
      }
      row(app.headless() ? "finish" : "swap", t.average_ms(demo::kFinish));
      ImGui::EndTable();
    }
    ImGui::Checkbox("time each GL stage (glFinish)", &app.sync_stages);
    ImGui::Text("%d triangles", app.triangles());
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", app.gl_description().c_str());
    app.remember_panel("Timings");
  }
  ImGui::End();
}

}  // namespace prep::ui
