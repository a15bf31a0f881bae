// Headless runs (OSMesa): a clip viewer screenshot, and benchmarks of any WindowApp (the scenario demo or
// the clip viewer) with frames per second and milliseconds per stage.
#pragma once

#include <string>

#include "app/demo/clip_viewer_app.h"
#include "app/demo/window_app.h"
#include "app/render/gl_context.h"

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

// Draws the clip viewer paused at options.time and returns the image (panels included unless disabled).
render::Image headless_screenshot(const DemoMotions& motions, const HeadlessOptions& options);

struct BenchResult {
  double fps = 0.0;                       // free-running frames per second
  double cpu_ms_per_frame = 0.0;          // process CPU time (all threads: ours and llvmpipe's) per free-running frame
  double stage_ms[kStageCount] = {};      // mean ms per stage, each stage ended by glFinish
  double synced_fps = 0.0;                // frames per second of that synchronised run
  int triangles = 0;
};

// Runs `frames` frames of `dt` twice: free-running for the frame rate, then with every stage synchronised
// for the per-stage milliseconds (after a few unmeasured frames: shader compilation, font atlas, layout).
BenchResult bench_app(WindowApp& app, render::GlContext& context, int frames, float dt = 1.0f / 60.0f);

// The clip viewer playing options.clip.
BenchResult headless_bench(const DemoMotions& motions, const HeadlessOptions& options, int frames);

// "1280x720 with panels, 600 frames, N triangles\n  free-running: ..." as prep-demo prints it.
std::string bench_report(const BenchResult& r, int width, int height, bool panels, int frames);

}  // namespace prep::demo
