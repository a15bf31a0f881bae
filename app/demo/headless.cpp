#include "app/demo/headless.h"

#include <sys/resource.h>

#include <cstdio>

namespace prep::demo {

render::Image headless_screenshot(const DemoMotions& motions, const HeadlessOptions& options) {
  render::OsMesaContext context(options.width, options.height);
  ClipViewerApp app(context, motions, nullptr, options.render);
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
double run(WindowApp& app, render::GlContext& context, int frames, float dt) {
  const auto start = Clock::now();
  for (int i = 0; i < frames; ++i) {
    app.frame(dt);
    const auto t = Clock::now();
    context.end_frame();
    app.timings.add(kFinish, ms_since(t));
  }
  return ms_since(start) / 1000.0;
}
}  // namespace

BenchResult bench_app(WindowApp& app, render::GlContext& context, int frames, float dt) {
  run(app, context, kSettleFrames * 4, dt);  // shader compilation, font atlas, ImGui layout: not measured

  BenchResult result;
  app.sync_stages = false;
  const double cpu_start = process_cpu_ms();
  result.fps = frames / run(app, context, frames, dt);
  result.cpu_ms_per_frame = (process_cpu_ms() - cpu_start) / frames;

  app.sync_stages = true;
  double total[kStageCount] = {};
  const auto start = Clock::now();
  for (int i = 0; i < frames; ++i) {
    app.timings = Timings(1);  // window 1: average_ms == this frame's value
    app.frame(dt);
    const auto t = Clock::now();
    context.end_frame();
    app.timings.add(kFinish, ms_since(t));
    for (int s = 0; s < kStageCount; ++s) total[s] += app.timings.average_ms(s);
  }
  result.synced_fps = frames / (ms_since(start) / 1000.0);
  for (int s = 0; s < kStageCount; ++s) result.stage_ms[s] = total[s] / frames;
  result.triangles = app.triangles();
  app.sync_stages = false;
  return result;
}

BenchResult headless_bench(const DemoMotions& motions, const HeadlessOptions& options, int frames) {
  render::OsMesaContext context(options.width, options.height);
  ClipViewerApp app(context, motions, nullptr, options.render);
  app.player.select(app.motions(), options.clip);
  app.show_panels = options.panels;
  return bench_app(app, context, frames);
}

std::string bench_report(const BenchResult& r, int width, int height, bool panels, int frames) {
  char text[512];
  std::snprintf(text, sizeof text,
                "%dx%d %s, %d frames, %d triangles\n"
                "  free-running: %.1f frames/s; CPU time %.1f ms per frame over all threads\n"
                "  each stage finished (glFinish): %.1f frames/s; ms per stage:",
                width, height, panels ? "with panels" : "without panels", frames, r.triangles, r.fps, r.cpu_ms_per_frame,
                r.synced_fps);
  std::string out = text;
  for (int s = 0; s < kStageCount; ++s) {
    std::snprintf(text, sizeof text, "  %s %.2f", stage_name(s), r.stage_ms[s]);
    out += text;
  }
  return out;
}

}  // namespace prep::demo
