// prep-demo --headless --scenario FILE: the engine's world (engine/world) run at its fixed step, drawn
// through OSMesa with the demo's renderer (no panels yet), with screenshots, frame folders, a video
// through ffmpeg when installed, and the launches printed as JSON.
#pragma once

#include <string>

#include "app/render/scene.h"
#include "engine/world/world.h"

namespace prep::demo {

// The renderer's scene for the world's read-only scene (the world stays GL-free; this is the only bridge).
render::Scene to_render_scene(const WorldScene& world);

struct ScenarioRunOptions {
  std::string scenario;
  float seconds = 30.0f;
  int width = 1280, height = 720;
  std::string screenshot;   // PNG of the last frame
  std::string frames_dir;   // PNGs frame_00000.png ... at 30 frames/s
  std::string video;        // MP4 through ffmpeg (from frames written to a temporary folder)
  std::string params;       // Params JSON (default: the scenario's)
  bool json = false;
};

// Returns the process exit code (0: ran; the goal reached or not is in the output).
int run_scenario_headless(const ScenarioRunOptions& options);

}  // namespace prep::demo
