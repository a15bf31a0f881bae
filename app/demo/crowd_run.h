// prep-demo --crowd N: the crowd demo (crowd_app.h) in a window, or headless through OSMesa: a screenshot
// after --seconds of simulation, or a frame-rate benchmark of --bench-frames frames.
#pragma once

#include <memory>
#include <string>

#include "app/render/renderer.h"
#include "engine/world/crowd.h"

namespace prep::demo {

struct CrowdRunOptions {
  std::string scenario;     // one lane
  int lanes = 200;
  float seconds = 10.0f;    // headless: simulated before the screenshot
  int width = 1280, height = 720;
  std::string screenshot;   // headless: PNG of the frame drawn after `seconds`
  int bench_frames = 0;     // headless: > 0 benchmarks this many frames (1/60 s each) instead
  bool panels = true;
  std::string params;       // Params JSON (default: the scenario's)
  std::string cache_dir;    // policy cache ("" = default_policy_cache_dir())
  render::RenderSettings render;
};

// The scenario's assets and policy (trained now when not cached, with progress on stderr), and the crowd.
std::unique_ptr<Crowd> make_crowd(const CrowdRunOptions& options);

// Runs headless and prints what it did (the screenshot written, or the benchmark's figures).
void run_crowd_headless(const CrowdRunOptions& options);

}  // namespace prep::demo
