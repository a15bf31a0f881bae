#include "app/demo/headless.h"

#include <sys/resource.h>

namespace prep::demo {

render::Image headless_screenshot(const DemoMotions& motions, const HeadlessOptions& options) {
  render::OsMesaContext context(options.width, options.height);
  DemoApp app(context, motions, nullptr, options.render);
  app.player.select(app.motions(), options.clip);
  app.player.time = options.time;
  app.player.playing = false;
  app.show_panels = options.panels;
  app.follow = false;
  app.camera = default_camera(clip_scene(app.motions().clips[app.player.clip], options.time, false));
  for (int i = 0; i < kSettleFrames; ++i) app.frame(1.0f / 60.0f);
  return context.read_pixels();
}

namespace {
double process_cpu_ms() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return (usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) * 1e3 + (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-3;
}

// Runs `frames` frames; returns wall-clock seconds.
double run(DemoApp& app, render::GlContext& context, int frames) {
  const auto start = Clock::now();
  for (int i = 0; i < frames; ++i) {
    app.frame(1.0f / 60.0f);
    const auto t = Clock::now();
    context.end_frame();
    app.timings.add(kFinish, ms_since(t));
  }
  return ms_since(start) / 1000.0;
}
}  // namespace

BenchResult headless_bench(const DemoMotions& motions, const HeadlessOptions& options, int frames) {
  render::OsMesaContext context(options.width, options.height);
  DemoApp app(context, motions, nullptr, options.render);
  app.player.select(app.motions(), options.clip);
  app.show_panels = options.panels;
  run(app, context, kSettleFrames * 4);  // shader compilation, font atlas, ImGui layout: not measured

  BenchResult result;
  app.sync_stages = false;
  const double cpu_start = process_cpu_ms();
  result.fps = frames / run(app, context, frames);
  result.cpu_ms_per_frame = (process_cpu_ms() - cpu_start) / frames;

  app.sync_stages = true;
  double total[kStageCount] = {};
  const auto start = Clock::now();
  for (int i = 0; i < frames; ++i) {
    app.timings = Timings(1);  // window 1: average_ms == this frame's value
    app.frame(1.0f / 60.0f);
    const auto t = Clock::now();
    context.end_frame();
    app.timings.add(kFinish, ms_since(t));
    for (int s = 0; s < kStageCount; ++s) total[s] += app.timings.average_ms(s);
  }
  result.synced_fps = frames / (ms_since(start) / 1000.0);
  for (int s = 0; s < kStageCount; ++s) result.stage_ms[s] = total[s] / frames;
  result.triangles = app.renderer().triangles_last_frame();
  return result;
}

}  // namespace prep::demo
