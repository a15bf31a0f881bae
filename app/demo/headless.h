// Headless runs of the demo (OSMesa): one screenshot, or a benchmark of N frames.
#pragma once

#include <string>

#include "app/demo/demo_app.h"

namespace prep::demo {

struct HeadlessOptions {
  int width = 1280;
  int height = 720;
  int clip = 0;
  float time = 0.0f;     // s into the clip for a screenshot
  bool panels = true;
  render::RenderSettings render;
};

// Frames drawn before a screenshot is read: ImGui lays out new auto-sized windows over the first frames.
constexpr int kSettleFrames = 3;

// Draws the demo paused at options.time and returns the image (panels included unless disabled).
render::Image headless_screenshot(const DemoMotions& motions, const HeadlessOptions& options);

struct BenchResult {
  double fps = 0.0;                       // free-running frames per second
  double cpu_ms_per_frame = 0.0;          // process CPU time (all threads: ours and llvmpipe's) per free-running frame
  double stage_ms[kStageCount] = {};      // mean ms per stage, each stage ended by glFinish
  double synced_fps = 0.0;                // frames per second of that synchronised run
  int triangles = 0;
};

// Plays the clip for `frames` frames (1/60 s each) twice: free-running for the frame rate, then with
// every stage synchronised for the per-stage milliseconds.
BenchResult headless_bench(const DemoMotions& motions, const HeadlessOptions& options, int frames);

}  // namespace prep::demo
