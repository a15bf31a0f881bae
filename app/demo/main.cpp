// prep-demo: the interactive demo (GLFW window, OpenGL 3.3, Dear ImGui) and its headless mode (OSMesa):
// PNG strips and screenshots of clips, and a frame-rate benchmark.
#include <CLI/CLI.hpp>

#include <iomanip>
#include <iostream>

#include "app/demo/headless.h"
#include "app/demo/motions.h"
#include "app/demo/scenario_run.h"
#include "app/demo/strip.h"
#include "app/demo/windowed.h"
#include "app/render/gl_context.h"
#include "app/render/image.h"
#include "app/render/renderer.h"
#include "engine/params/params.h"

using namespace prep;
using namespace prep::demo;

int main(int argc, char** argv) {
  CLI::App cli{"prep-demo: characters that prepare for what comes next (Shum et al. 2013).\n"
               "Without --headless it opens a window; with --headless it renders through OSMesa."};
  bool headless = false;
  std::string motions_arg = "builtin", bvh, clip_name, strip, screenshot, params_file, script;
  float unit_scale = 0.01f, time = 0.0f;
  int frames = 8, width = 0, height = 0, bench_frames = 0, screenshot_after = 60, quit_after = -1;
  int shadow_map = render::RenderSettings{}.shadow_map_size;
  bool no_panels = false, no_props = false, no_vsync = false;
  cli.add_flag("--headless", headless, "Render off-screen through OSMesa (no display needed)");
  cli.add_option("--motions", motions_arg, "builtin, or a motion-set manifest (JSON)")->capture_default_str();
  cli.add_option("--bvh", bvh, "Play one BVH file instead of a motion set");
  cli.add_option("--unit-scale", unit_scale, "BVH units to metres (0.01 for centimetres)")->capture_default_str();
  cli.add_option("--clip", clip_name, "Clip to show (default: the first)");
  cli.add_option("--params", params_file, "Params JSON (default: built-in defaults)");
  cli.add_option("--strip", strip, "Headless: write a strip of --frames frames of the clip to this PNG");
  cli.add_option("--frames", frames, "Frames in a strip")->capture_default_str()->check(CLI::Range(1, 64));
  cli.add_option("--screenshot", screenshot, "Write one frame (panels included) to this PNG");
  cli.add_option("--time", time, "Headless screenshot: seconds into the clip")->capture_default_str();
  cli.add_option("--width", width, "Image or window width (strip: width of one tile; default 1280, strip 320)");
  cli.add_option("--height", height, "Image or window height (strip: tile height; default 720, strip 480)");
  cli.add_option("--bench-frames", bench_frames, "Headless: draw N frames, print frames/s and ms per stage");
  cli.add_option("--shadow-map", shadow_map, "Shadow map size in texels (0: no shadows)")->capture_default_str();
  cli.add_flag("--no-panels", no_panels, "Do not draw the ImGui panels");
  cli.add_flag("--no-obstacle", no_props, "Do not place the obstacle of the clip's role (bar, beam, hurdle, ball)");
  cli.add_option("--script", script, "Window: scripted key presses FRAME:KEY,... (e.g. 20:e,40:space)");
  cli.add_option("--screenshot-after", screenshot_after, "Window: frame after which --screenshot is taken (-1: on closing, e.g. Escape)")->capture_default_str();
  cli.add_option("--quit-after", quit_after, "Window: close after this many frames");
  cli.add_flag("--no-vsync", no_vsync, "Window: do not wait for the display's refresh");
  std::string scenario, frames_dir, video;
  float seconds = 30.0f;
  bool json = false;
  cli.add_option("--scenario", scenario, "Headless: run this scenario (engine/world) and draw it");
  cli.add_option("--seconds", seconds, "Scenario: simulated seconds")->capture_default_str();
  cli.add_option("--frames-dir", frames_dir, "Scenario: write a PNG per frame (30 frames/s) into this folder");
  cli.add_option("--video", video, "Scenario: write an MP4 through ffmpeg");
  cli.add_flag("--json", json, "Scenario: print the launches (action, alpha_at_launch, time) and the goal as JSON");
  CLI11_PARSE(cli, argc, argv);
  if (headless && !scenario.empty()) {
    try {
      ScenarioRunOptions o;
      o.scenario = scenario;
      o.seconds = seconds;
      o.width = width > 0 ? width : o.width;
      o.height = height > 0 ? height : o.height;
      o.screenshot = screenshot;
      o.frames_dir = frames_dir;
      o.video = video;
      o.params = params_file;
      o.json = json;
      return run_scenario_headless(o);
    } catch (const std::exception& e) {
      std::cerr << "prep-demo: " << e.what() << "\n";
      return 1;
    }
  }

  try {
    const Params params = params_file.empty() ? Params{} : load_params(params_file);
    const DemoMotions motions = load_demo_motions(motions_arg, bvh, unit_scale, params);
    if (motions.clips.empty()) throw std::runtime_error(motions.source + ": no clips");
    int clip = 0;
    if (!clip_name.empty()) {
      clip = motions.find(clip_name);
      if (clip < 0) {
        std::string names;
        for (const DemoClip& c : motions.clips) names += " " + c.clip.name;
        throw std::runtime_error("no clip named \"" + clip_name + "\" in " + motions.source + "; clips:" + names);
      }
    }

    if (!headless) {
      if (!strip.empty() || bench_frames > 0) throw std::runtime_error("--strip and --bench-frames need --headless");
      WindowOptions w;
      w.width = width > 0 ? width : w.width;
      w.height = height > 0 ? height : w.height;
      w.clip = clip;
      w.vsync = !no_vsync;
      w.script = parse_key_script(script);
      w.screenshot = screenshot;
      w.screenshot_after = screenshot_after;
      w.quit_after = quit_after;
      try {
        run_window(motions, w);
      } catch (const render::NoDisplayError& e) {
        std::cerr << "prep-demo: " << e.what() << "\n";
        return 2;
      }
      return 0;
    }

    if (strip.empty() && screenshot.empty() && bench_frames <= 0)
      throw std::runtime_error("--headless needs --strip, --screenshot or --bench-frames");
    if (!strip.empty()) {
      StripOptions s;
      s.frames = frames;
      s.tile_width = width > 0 ? width : s.tile_width;
      s.tile_height = height > 0 ? height : s.tile_height;
      s.props = !no_props;
      render::write_png(render_strip(motions.clips[clip], s), strip);
      std::cout << "prep-demo: wrote " << strip << " (" << motions.clips[clip].clip.name << ", " << frames << " frames, "
                << s.tile_width * frames << "x" << s.tile_height << ")\n";
    }
    HeadlessOptions h;
    h.width = width > 0 ? width : h.width;
    h.height = height > 0 ? height : h.height;
    h.clip = clip;
    h.time = time;
    h.panels = !no_panels;
    h.render.shadow_map_size = shadow_map;
    if (!screenshot.empty()) {
      render::write_png(headless_screenshot(motions, h), screenshot);
      std::cout << "prep-demo: wrote " << screenshot << " (" << motions.clips[clip].clip.name << " at " << time << " s, "
                << h.width << "x" << h.height << ")\n";
    }
    if (bench_frames > 0) {
      const BenchResult r = headless_bench(motions, h, bench_frames);
      std::cout << std::fixed << std::setprecision(1) << "prep-demo: " << h.width << "x" << h.height
                << (h.panels ? " with panels" : " without panels") << ", " << bench_frames << " frames, " << r.triangles
                << " triangles\n  free-running: " << r.fps << " frames/s; CPU time " << r.cpu_ms_per_frame
                << " ms per frame over all threads\n  each stage finished (glFinish): "
                << r.synced_fps << " frames/s; ms per stage:" << std::setprecision(2);
      for (int s = 0; s < kStageCount; ++s) std::cout << "  " << stage_name(s) << " " << r.stage_ms[s];
      std::cout << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "prep-demo: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
