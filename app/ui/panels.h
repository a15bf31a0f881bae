// The demo's ImGui panels (Dear ImGui 1.86: no ImPlot; plots are ImGui::PlotLines). Each panel reads the
// DemoApp's session and view and changes them only through the session's intent calls and set_params, so
// what a panel shows is the engine's state, and what it does is what a key or a click would do.
//
// Layout at 1280x720 (set on first use; the panels can be moved): Scenario and Preparation in a column on
// the left, Plots, Timings and Camera on the right, the middle kept clear for the scene but for the
// clearance view's readout at its bottom while that view is on.
#pragma once

namespace prep::demo {
class DemoApp;
}

namespace prep::ui {

void startup_panel(demo::DemoApp& app);      // centred: what is loading or training, with a progress bar
void scenario_panel(demo::DemoApp& app);     // scenario picker, auto, pause, launches, source and goal
void preparation_panel(demo::DemoApp& app);  // C_i per joint group and joint, w_b/w_s/w_m, thresholds, save/load
void plots_panel(demo::DemoApp& app);        // alpha and the COM over the last seconds, the floor overlay and
                                             // clearance view toggles
void motion_folder_panel(demo::DemoApp& app);  // a folder of the user's takes: what the scan found, what the
                                               // set lacks and what the course lost for it
void clearance_panel(demo::DemoApp& app);    // while the clearance view is on: the user's nearest object
void timings_panel(demo::DemoApp& app);      // engine stages per frame, render stages, frames per second
void camera_panel(demo::DemoApp& app);       // follow, orbit, zoom, keys

// Places the next panel (call before ImGui::Begin) in the left or the right column, `width` wide, right
// below the panel named `below` (drawn earlier this frame; nullptr: at the top). The panels size themselves
// to their content (ImGuiWindowFlags_AlwaysAutoResize), which takes ImGui a few frames, so the places are
// imposed over the first frames only; afterwards a panel stays where the user drags it.
void place_panel(demo::DemoApp& app, bool right_column, const char* below, float width);
// ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoBackground (imgui.h is not included here): the
// DemoApp clears each remembered panel's rectangle to the window colour instead (demo_app.cpp).
constexpr int kPanelFlags = (1 << 6) | (1 << 7);

// Panel geometry shared by the panels (pixels).
constexpr float kMargin = 10.0f;
constexpr float kLeftWidth = 350.0f;
constexpr float kLabelWidth = 120.0f;  // room kept right of sliders for their labels
constexpr float kRightWidth = 300.0f;

}  // namespace prep::ui
