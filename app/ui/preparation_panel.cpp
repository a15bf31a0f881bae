#include <imgui.h>

#include <cstring>
#include <string>

#include "app/demo/demo_app.h"
#include "app/ui/panels.h"

namespace prep::ui {

namespace {

// A marker after a control whose value the trained policy depends on (policy_params_hash).
void retrains_note() {
  ImGui::SameLine();
  ImGui::TextDisabled("*");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The controller's policy depends on this value: a new one is trained in the background\n"
                      "(or loaded from the cache) and swapped in when ready; the old one plays meanwhile.");
}

// Eq. 1 curves: the groups, then per-joint overrides of C_i.
bool blend_controls(Params& p, const WorldAssets* assets) {
  bool changed = false;
  ImGui::TextUnformatted("Eq. 1  w_i = c_i sqrt(1 - (1 - alpha)^C_i)");
  changed |= ImGui::SliderFloat("C_i upper", &p.blend.C_upper, 0.1f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  changed |= ImGui::SliderFloat("C_i lower", &p.blend.C_lower, 0.1f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  retrains_note();
  int method = p.blend.method == "linear" ? 1 : 0;
  const char* methods[] = {"ours: per-joint curves", "linear: one weight alpha"};
  if (ImGui::Combo("blend", &method, methods, 2)) {
    p.blend.method = method == 1 ? "linear" : "ours";
    changed = true;
  }
  retrains_note();
  if (!assets || !assets->set) return changed;
  const Skeleton& skeleton = *assets->set->skeleton;
  const BodyMap& body = assets->set->body;
  const std::string header = "C_i per joint (" + std::to_string(p.blend.C_override.size()) + " overridden)";
  if (ImGui::TreeNode("joints", "%s", header.c_str())) {
    // A scrolled list: the skeleton has dozens of joints, the panel must still fit the screen.
    ImGui::BeginChild("joint list", ImVec2(0.0f, 8.0f * ImGui::GetFrameHeightWithSpacing()), true);
    for (int j = 0; j < skeleton.size(); ++j) {
      const std::string& name = skeleton.joints[static_cast<size_t>(j)].name;
      const bool upper = j < static_cast<int>(body.upper_body.size()) && body.upper_body[static_cast<size_t>(j)];
      auto it = p.blend.C_override.find(name);
      bool on = it != p.blend.C_override.end();
      ImGui::PushID(j);
      if (ImGui::Checkbox("##on", &on)) {
        if (on) p.blend.C_override[name] = upper ? p.blend.C_upper : p.blend.C_lower;
        else p.blend.C_override.erase(name);
        changed = true;
      }
      ImGui::SameLine();
      if (on) {
        ImGui::SetNextItemWidth(140.0f);
        changed |= ImGui::SliderFloat(name.c_str(), &p.blend.C_override[name], 0.1f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
      } else {
        ImGui::Text("%s  (%s: %.2f)", name.c_str(), upper ? "upper" : "lower", upper ? p.blend.C_upper : p.blend.C_lower);
      }
      ImGui::PopID();
    }
    ImGui::EndChild();
    ImGui::TreePop();
  }
  return changed;
}

bool balance_controls(Params& p) {
  bool changed = false;
  ImGui::TextUnformatted("Eq. 10  E = w_b E_b + w_s E_s + w_m E_m");
  changed |= ImGui::Checkbox("balance", &p.balance.enabled);
  ImGui::SameLine();
  changed |= ImGui::Checkbox("foot IK", &p.ik.enabled);
  changed |= ImGui::SliderFloat("w_b", &p.balance.w_b, 0.0f, 10.0f, "%.2f");
  changed |= ImGui::SliderFloat("w_s", &p.balance.w_s, 0.0f, 10.0f, "%.2f");
  changed |= ImGui::SliderFloat("w_m", &p.balance.w_m, 0.0f, 5.0f, "%.2f");
  changed |= ImGui::SliderFloat("alpha threshold", &p.balance.alpha_threshold, 0.0f, 1.0f, "%.2f");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("No balance optimization below this level of preparation");
  changed |= ImGui::SliderInt("max steps", &p.balance.max_steps, 0, 40);
  changed |= ImGui::SliderFloat("goal radius", &p.reward.goal_radius, 0.1f, 2.0f, "%.2f m");
  retrains_note();
  changed |= ImGui::SliderFloat("source radius", &p.reward.source_radius, 0.1f, 2.0f, "%.2f m");
  retrains_note();
  return changed;
}

void tip(const char* text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

// The run-time rules (RuntimeParams), folded away by default: the filter over alpha and when a target
// motion launches, then each rule beyond the paper, which off gives the paper's behaviour. The world reads
// them from its next tick.
bool runtime_controls(Params& p) {
  if (!ImGui::TreeNode("run-time rules")) return false;
  RuntimeParams& r = p.runtime;
  // Typed values (ctrl+click) too stay in range: an alpha of 0 to launch at would be refused.
  constexpr ImGuiSliderFlags kClamp = ImGuiSliderFlags_AlwaysClamp;
  bool changed = false;
  changed |= ImGui::SliderFloat("alpha sigma", &r.alpha_sigma_s, 0.0f, 1.0f, "%.2f s", kClamp);
  tip("Width of the Gaussian filter over the chosen alpha (Sec. 6): a step rises to 68% after sigma");
  changed |= ImGui::SliderFloat("launch alpha", &r.launch_alpha, 0.05f, 1.0f, "%.2f", kClamp);
  tip("At its launch point a character launches its target motion once the played alpha reaches this");
  ImGui::TextDisabled("beyond the paper (off: the paper's behaviour)");
  changed |= ImGui::SliderFloat("preparation range", &r.preparation_range, 0.5f, 15.0f, "%.1f m", kClamp);
  tip("A source calls for preparation when its launch point lies at most this far ahead");
  changed |= ImGui::Checkbox("relax with no source in range", &r.relax_without_source);
  tip("With no source in range alpha 0 is played, whatever level the controller chose");
  bool keep = r.kept_alpha >= 0.0f;
  if (ImGui::Checkbox("keep preparation between targets", &keep)) {
    r.kept_alpha = keep ? RuntimeParams{}.kept_alpha : -1.0f;
    changed = true;
  }
  tip("Back from a target motion with the next source in range, the controller resumes at this level, not 0");
  if (keep) changed |= ImGui::SliderFloat("kept alpha", &r.kept_alpha, 0.0f, 1.0f, "%.2f", kClamp);
  changed |= ImGui::SliderFloat("tight turn", &r.tight_turn_deg_per_s, 0.0f, 360.0f, "%.0f deg/s", kClamp);
  tip("A goal inside the walking turns' circle or behind: the heading turns toward it at up to this rate (0: off)");
  changed |= ImGui::SliderFloat("waypoint radius", &r.waypoint_pass_radius, 0.0f, 3.0f, "%.2f m", kClamp);
  tip("A waypoint that is not the last counts as passed when the character goes by it this close (0: goal radius only)");
  struct Switch {
    const char* label;
    bool* on;
    const char* tip;
  };
  const Switch switches[] = {
      {"anticipate a closing source", &r.anticipate_closing,
       "An opponent walking up is shown to the controller where a still one would leave the same time to prepare"},
      {"end a turn at the goal's bearing", &r.end_turn_at_goal_bearing,
       "A turn toward the goal ends, and the controller decides again, once the goal's bearing crosses over"},
      {"keep the source ahead", &r.keep_source_ahead,
       "Turns that would swing a source ahead and the goal further off the facing are passed over"},
      {"choose the level again a bin nearer", &r.level_per_source_bin,
       "Between decisions the level is chosen again, for the motion playing, when the source comes a distance bin nearer"},
      {"make for a ball in range", &r.make_for_ball_source,
       "Unattended, the user walks to a ball that is its source and nearer than where it is going, and kicks it"},
      {"keep bodies out of obstacles", &r.keep_clear,
       "A body in an obstacle it is not crossing is set back out; a kicked ball bounces off what it meets"},
  };
  for (const Switch& w : switches) {
    changed |= ImGui::Checkbox(w.label, w.on);
    tip(w.tip);
  }
  ImGui::TreePop();
  return changed;
}

void file_controls(demo::DemoApp& app) {
  char path[512];
  std::strncpy(path, app.params_path.c_str(), sizeof path - 1);
  path[sizeof path - 1] = '\0';
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x - 100.0f);
  if (ImGui::InputText("##params file", path, sizeof path)) app.params_path = path;
  ImGui::SameLine();
  if (ImGui::Button("Save")) {
    try {
      save_params(app.session().params(), app.params_path);  // atomic (temporary file + rename)
      app.message = "saved the Params to " + app.params_path;
    } catch (const std::exception& e) {
      app.message = e.what();
    }
  }
  ImGui::SameLine();
  if (ImGui::Button("Load")) app.load_params_file(app.params_path);
}

}  // namespace

void preparation_panel(demo::DemoApp& app) {
  demo::WorldSession& s = app.session();
  place_panel(app, false, "Scenario", kLeftWidth);
  if (ImGui::Begin("Preparation", nullptr, kPanelFlags)) {
    ImGui::PushItemWidth(-kLabelWidth);
    Params p = s.params();
    bool changed = blend_controls(p, s.assets());
    ImGui::Separator();
    changed |= balance_controls(p);
    ImGui::Separator();
    changed |= runtime_controls(p);
    if (changed) s.set_params(p);  // at once: World::set_params rebuilds the synthesizer
    if (s.retraining() || s.policy_stale()) ImGui::ProgressBar(s.progress(), ImVec2(-1.0f, 0.0f), "retraining the policy");
    ImGui::TextDisabled("* the controller's policy depends on it: retrained");
    ImGui::Separator();
    file_controls(app);
    ImGui::PopItemWidth();
    app.remember_panel("Preparation");
  }
  ImGui::End();
}

}  // namespace prep::ui
