// prep-demo --headless --scenario FILE: the demo (DemoApp: the world at its fixed step, the renderer, the
// panels) drawn through OSMesa with no display: a screenshot of the last frame, a PNG per frame, a video
// through ffmpeg when it is installed, a PNG strip of frames, a frame-rate benchmark, and the launches
// printed as JSON. The policy is loaded from the cache or trained first (progress on stderr).
#pragma once

#include <string>

#include "app/render/image.h"
#include "app/render/renderer.h"

namespace prep::demo {

struct ScenarioRunOptions {
  std::string scenario;
  float seconds = 30.0f;
  int width = 1280, height = 720;
  std::string screenshot;   // PNG of the last frame
  std::string frames_dir;   // PNGs frame_00000.png ... at kVideoFps
  std::string video;        // MP4 through ffmpeg (raw frames piped in); without ffmpeg a strip is written instead
  std::string strip;        // PNG: kStripTiles frames spread over the run, in a grid
  std::string params;       // Params JSON (default: the scenario's)
  std::string cache_dir;    // policy cache ("" = default_policy_cache_dir())
  bool json = false;
  bool panels = true;
  int bench_frames = 0;     // > 0: a benchmark of this many frames (1/60 s each) instead of a run
  render::RenderSettings render;
};

constexpr int kVideoFps = 30;
constexpr int kStripColumns = 3, kStripRows = 2;  // a 3x2 grid of frames
constexpr int kStripTiles = kStripColumns * kStripRows;

// Returns the process exit code (0: ran; whether the goal was reached is in the output).
int run_scenario_headless(const ScenarioRunOptions& options);

// Whether ffmpeg can be run (on PATH).
bool ffmpeg_available();

// The image shrunk by an integer factor (box filter), for strip tiles.
render::Image downscale(const render::Image& image, int factor);

}  // namespace prep::demo
