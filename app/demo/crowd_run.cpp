#include "app/demo/crowd_run.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "app/demo/crowd_app.h"
#include "app/demo/headless.h"
#include "app/render/gl_api.h"
#include "app/render/image.h"
#include "app/render/gl_context.h"
#include "engine/params/params.h"
#include "engine/world/policy_cache.h"

namespace prep::demo {

std::unique_ptr<Crowd> make_crowd(const CrowdRunOptions& options) {
  const Scenario lane = load_scenario(options.scenario);
  const Params params = options.params.empty() ? load_scenario_params(lane) : load_params(options.params);
  const std::string cache = options.cache_dir.empty() ? default_policy_cache_dir() : options.cache_dir;
  bool trained = false;
  std::cerr << "prep-demo: crowd of " << options.lanes << " lanes of " << lane.name << ": loading" << std::endl;
  const auto assets = prepare_world_assets(lane, params, cache, &trained);
  if (trained) std::cerr << "prep-demo: the controller's policy was trained and cached in " << cache << std::endl;
  CrowdOptions o;
  o.lanes = options.lanes;
  return std::make_unique<Crowd>(lane, assets, o);
}

void run_crowd_headless(const CrowdRunOptions& options) {
  std::unique_ptr<Crowd> crowd = make_crowd(options);
  render::OsMesaContext context(options.width, options.height);
  CrowdApp app(context, *crowd, nullptr, options.render);
  app.show_panel = options.panels;
  const float dt = 1.0f / 60.0f;
  if (options.bench_frames > 0) {
    const BenchResult r = bench_app(app, context, options.bench_frames, dt);
    std::cout << "prep-demo: crowd of " << crowd->lanes() << " (" << options.scenario << "), "
              << bench_report(r, options.width, options.height, options.panels, options.bench_frames) << "\n"
              << "  engine: " << app.engine_ms_per_tick() << " ms per tick for " << crowd->lanes() << " characters"
              << std::endl;
    return;
  }
  // The last half second is drawn, so that the panel's frames/s is that of drawn frames: after the settle
  // frames (shader compilation) the timings start over.
  constexpr int kDrawnFrames = 30;
  const int frames = static_cast<int>(options.seconds / dt);
  const int skipped = std::max(0, frames - kSettleFrames - kDrawnFrames);
  for (int f = 0; f < skipped; ++f) app.skip_frame(dt);
  for (int f = 0; f < kSettleFrames; ++f) app.frame(dt);
  app.timings = Timings();
  for (int f = 0; f < kDrawnFrames; ++f) app.frame(dt);
  if (options.screenshot.empty()) throw std::runtime_error("a headless crowd needs --screenshot or --bench-frames");
  render::write_png(context.read_pixels(), options.screenshot);
  std::cout << "prep-demo: wrote " << options.screenshot << " (crowd of " << crowd->lanes() << " after "
            << crowd->time() << " s; " << app.triangles() << " triangles)" << std::endl;
}

}  // namespace prep::demo
