#include <imgui.h>

#include <cmath>
#include <string>

#include "app/demo/demo_app.h"
#include "app/render/palette.h"
#include "app/ui/panels.h"

namespace prep::ui {

namespace {

// The source of influence's highlight colour (palette::kSource) for the prepared action's button.
ImVec4 source_colour(float alpha) {
  const glm::vec3& c = render::palette::kSource;
  return ImVec4(c.r, c.g, c.b, alpha);
}

void picker(demo::DemoApp& app) {
  demo::WorldSession& s = app.session();
  const std::string current = s.scenario().name.empty() ? "(none)" : s.scenario().name;
  if (ImGui::BeginCombo("scenario", current.c_str())) {
    for (const demo::ScenarioEntry& e : app.scenarios) {
      const bool selected = e.path == s.scenario_path();
      if (ImGui::Selectable(e.name.c_str(), selected) && !selected) app.open_scenario(e.path);
      if (ImGui::IsItemHovered() && !e.description.empty()) ImGui::SetTooltip("%s", e.description.c_str());
    }
    ImGui::EndCombo();
  }
}

void run_controls(demo::WorldSession& s) {
  bool auto_on = s.auto_launch();
  if (ImGui::Checkbox("auto (T)", &auto_on)) s.set_auto(auto_on);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Launch the target motion when the character reaches the obstacle or target");
  ImGui::SameLine();
  ImGui::Checkbox("pause (P)", &s.paused);
  ImGui::SameLine();
  if (ImGui::Button("step")) s.step_once();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("One engine tick (key: .)");
  ImGui::SameLine();
  if (ImGui::Button("restart")) s.restart();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The scenario from its start (key: N)");
  ImGui::SliderFloat("speed", &s.time_scale, 0.1f, 2.0f, "%.2fx");
}

void launch_buttons(demo::WorldSession& s, demo::DemoApp& app) {
  const World* w = s.world();
  const auto prepared = s.prepared_action();
  ImGui::TextUnformatted("Launch: keys 1-6; Space, right-click: prepared");
  for (int k = 0; k < kTargetActionCount; ++k) {
    const auto action = static_cast<TargetAction>(k);
    const bool available = w && w->assets().target(action).clip >= 0;
    const bool is_prepared = prepared && *prepared == action;
    if (k % 3) ImGui::SameLine();
    if (is_prepared) {
      ImGui::PushStyleColor(ImGuiCol_Button, source_colour(0.70f));
      ImGui::PushStyleColor(ImGuiCol_ButtonHovered, source_colour(0.85f));
      ImGui::PushStyleColor(ImGuiCol_ButtonActive, source_colour(1.0f));
    }
    ImGui::BeginDisabled(!available);
    const std::string label = std::to_string(k + 1) + " " + target_action_name(action);
    if (ImGui::Button(label.c_str(), ImVec2(106.0f, 0.0f)) && !s.launch(action))
      app.message = std::string("cannot launch ") + target_action_name(action) + " now (already in a target motion)";
    ImGui::EndDisabled();
    if (is_prepared) ImGui::PopStyleColor(3);
  }
}

void readout(const demo::WorldSession& s) {
  const World* w = s.world();
  const glm::vec2 g = s.goal();
  if (!w) {
    ImGui::Text("goal (%.1f, %.1f)", g.x, g.y);
    return;
  }
  const WorldCharacter& u = w->characters()[static_cast<size_t>(w->user())];
  ImGui::Text("alpha %.2f  (controller's level %.1f)", u.alpha, u.chosen_alpha);
  if (u.in_target) {
    ImGui::Text("playing the target motion: %s", target_action_name(u.playing));
  } else if (u.has_source) {
    const float d = glm::length(u.source_object_position - u.position);
    std::string what = "opponent";
    if (u.source_object >= 0) what = object_type_name(w->objects()[static_cast<size_t>(u.source_object)].spec.type);
    ImGui::Text("source: %s, %.1f m (prepares to %s)%s", what.c_str(), d, target_action_name(u.prepared_for),
                w->picked_source() >= 0 ? ", picked" : "");
  } else {
    ImGui::TextUnformatted("source: none ahead");
  }
  if (u.reached_goal && u.goal.empty())
    ImGui::Text("goal (%.1f, %.1f) reached at %.1f s", g.x, g.y, u.reached_time);
  else
    ImGui::Text("goal (%.1f, %.1f), %.1f m away", g.x, g.y, glm::length(g - u.position));
  const auto& launches = w->launches();
  int mine = 0;
  const LaunchRecord* last = nullptr;
  for (const LaunchRecord& r : launches)
    if (r.character == w->user()) ++mine, last = &r;
  if (last)
    ImGui::Text("%d launches; last: %s at %.1f s, alpha %.2f", mine, target_action_name(last->action), last->time,
                last->alpha_at_launch);
  else
    ImGui::TextUnformatted("no launches yet");
}

}  // namespace

void scenario_panel(demo::DemoApp& app) {
  demo::WorldSession& s = app.session();
  place_panel(app, false, nullptr, kLeftWidth);
  if (ImGui::Begin("Scenario", nullptr, kPanelFlags)) {
    ImGui::PushItemWidth(-kLabelWidth + 50.0f);
    picker(app);
    if (s.phase() != demo::SessionPhase::Running) {
      ImGui::TextWrapped("%s", s.status().c_str());
      ImGui::ProgressBar(s.progress(), ImVec2(-1.0f, 0.0f));
    } else if (s.retraining() || s.policy_stale()) {
      ImGui::TextWrapped("%s", s.status().c_str());
      ImGui::ProgressBar(s.progress(), ImVec2(-1.0f, 0.0f));
    }
    run_controls(s);
    ImGui::Separator();
    launch_buttons(s, app);
    ImGui::Separator();
    readout(s);
    ImGui::TextDisabled("click: floor = goal, object = source; WASD steer");
    if (!app.message.empty()) ImGui::TextWrapped("%s", app.message.c_str());
    if (!s.notice().empty()) ImGui::TextWrapped("%s", s.notice().c_str());
    ImGui::PopItemWidth();
    app.remember_panel("Scenario");
  }
  ImGui::End();
}

}  // namespace prep::ui
