// prep-demo: the interactive demo (GLFW window, OpenGL 3.3, Dear ImGui) on a scenario of Sec. 7.2 (by
// default the obstacle course), its headless mode (OSMesa: screenshots, frames, video, a strip, the
// launches as JSON, a frame-rate benchmark), and the clip viewer (--viewer, --clip or --bvh).
#include <CLI/CLI.hpp>

#include <filesystem>
#include <iomanip>
#include <iostream>

#include "app/demo/crowd_run.h"
#include "app/demo/headless.h"
#include "app/demo/motion_folder.h"
#include "app/demo/motions.h"
#include "app/demo/scenario_run.h"
#include "app/demo/strip.h"
#include "app/demo/windowed.h"
#include "app/demo/world_session.h"
#include "app/render/gl_context.h"
#include "app/render/image.h"
#include "app/render/renderer.h"
#include "engine/params/params.h"
#include "engine/world/policy_cache.h"

using namespace prep;
using namespace prep::demo;

namespace {

int clip_viewer(bool headless, const std::string& motions_arg, const std::string& bvh, float unit_scale,
                const std::string& clip_name, const std::string& params_file, int width, int height,
                const WindowOptions& w, const std::string& strip, int frames, const std::string& screenshot, float time, bool no_panels,
                bool no_props, int bench_frames, const render::RenderSettings& render) {
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
    WindowOptions o = w;
    o.clip = clip;
    run_clip_viewer_window(motions, o);
    return 0;
  }
  if (strip.empty() && screenshot.empty() && bench_frames <= 0)
    throw std::runtime_error("the clip viewer headless needs --strip, --screenshot or --bench-frames");
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
  h.width = w.width;
  h.height = w.height;
  h.clip = clip;
  h.time = time;
  h.panels = !no_panels;
  h.render = render;
  if (!screenshot.empty()) {
    render::write_png(headless_screenshot(motions, h), screenshot);
    std::cout << "prep-demo: wrote " << screenshot << " (" << motions.clips[clip].clip.name << " at " << time << " s, "
              << h.width << "x" << h.height << ")\n";
  }
  if (bench_frames > 0)
    std::cout << "prep-demo: clip " << motions.clips[clip].clip.name << ", "
              << bench_report(headless_bench(motions, h, bench_frames), h.width, h.height, h.panels, bench_frames) << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"prep-demo: characters that prepare for what comes next (Shum et al. 2013).\n"
               "Opens a window on a scenario (default: the obstacle course); --headless renders through OSMesa.\n"
               "In the window: WASD/arrows held steer the character, 1-6 or Space or a right-click launch target motions,\n"
               "a left click sets the goal (floor) or the source of influence (an object), T toggles auto,\n"
               "O the clearance view (body parts too deep in an object or another body in red)."};
  bool headless = false, viewer = false;
  std::string scenario, motions_arg = "builtin", bvh, clip_name, strip, screenshot, params_file, script, frames_dir, video;
  float unit_scale = 0.01f, time = 0.0f, seconds = 30.0f;
  int frames = 8, width = 0, height = 0, bench_frames = 0, screenshot_after = 60, quit_after = -1;
  int shadow_map = render::RenderSettings{}.shadow_map_size;
  bool no_panels = false, no_props = false, no_vsync = false, json = false, capsules = false, until_goal = false;
  bool clearance = false;
  int crowd = 0;
  cli.add_flag("--headless", headless, "Render off-screen through OSMesa (no display needed)");
  cli.add_option("--crowd", crowd,
                 "A crowd: N lanes of the scenario (default assets/scenarios/stadium.json) side by side, every character "
                 "preparing; headless: --screenshot after --seconds, or --bench-frames")
      ->check(CLI::Range(1, 100000));
  cli.add_option("--scenario", scenario, "Scenario JSON (default: assets/scenarios/obstacles.json)");
  // The last --seconds counts: scripts/demo.sh gives one ahead of the user's arguments.
  cli.add_option("--seconds", seconds, "Headless scenario: simulated seconds (with --until-goal the most)")
      ->capture_default_str()
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  cli.add_flag("--until-goal", until_goal,
               "Headless scenario: end a second after the user's goal is reached and no target motion plays");
  cli.add_option("--params", params_file, "Params JSON (default: the scenario's, or the built-in defaults)");
  cli.add_option("--screenshot", screenshot, "Write one frame (panels included) to this PNG: headless the last one");
  cli.add_option("--frames-dir", frames_dir, "Headless scenario: a PNG per frame (30 frames/s) into this folder");
  cli.add_option("--video", video, "Headless scenario: an MP4 through ffmpeg (without ffmpeg: a PNG strip)");
  cli.add_option("--strip", strip, "Headless: a PNG strip (scenario: 6 frames of the run; clip: --frames frames)");
  cli.add_flag("--json", json, "Headless scenario: print the launches (action, alpha_at_launch, time) and the goal as JSON");
  cli.add_option("--width", width, "Image or window width (default 1280; clip strip: width of one tile, 320)");
  cli.add_option("--height", height, "Image or window height (default 720; clip strip: tile height, 480)");
  cli.add_option("--bench-frames", bench_frames, "Headless: draw N frames, print frames/s and ms per stage");
  cli.add_option("--shadow-map", shadow_map, "Shadow map size in texels (0: no shadows)")->capture_default_str();
  cli.add_flag("--capsules", capsules, "Draw the characters as capsules per bone instead of the skinned body");
  cli.add_flag("--no-panels", no_panels, "Do not draw the ImGui panels");
  cli.add_flag("--clearance", clearance,
               "Scenario: start with the clearance view on (body parts deeper than the tolerance in an object or "
               "another body drawn in red; key O)");
  cli.add_option("--script", script,
                 "Window: scripted keys FRAME:KEY (a press) or FROM-TO:KEY (held), comma-separated (e.g. 20:e,40-100:w)");
  cli.add_option("--screenshot-after", screenshot_after, "Window: frame after which --screenshot is taken (-1: on closing, e.g. Escape)")->capture_default_str();
  cli.add_option("--quit-after", quit_after, "Window: close after this many frames");
  cli.add_flag("--no-vsync", no_vsync, "Window: do not wait for the display's refresh");
  double stress_seconds = 0.0;
  std::uint64_t stress_seed = 1;
  cli.add_option("--stress", stress_seconds,
                 "Window: a stress run of this many seconds (a random tunable changed every frame, scenarios switched, "
                 "random launches, a broken Params file loaded half-way), then close; exit 1 if it failed");
  cli.add_option("--stress-seed", stress_seed, "Window: the stress run's seed")->capture_default_str();
  cli.add_flag("--viewer", viewer, "The clip viewer instead of a scenario (also chosen by --clip, --bvh, --motions)");
  cli.add_option("--motions", motions_arg,
                 "A folder of BVH takes: scanned into a motion set (as prep manifest does), then the obstacle course "
                 "(or --scenario) with what the set can do; or, for the clip viewer, builtin or a motion-set manifest (JSON)")
      ->capture_default_str();
  cli.add_option("--bvh", bvh, "Clip viewer: play one BVH file");
  cli.add_option("--unit-scale", unit_scale, "Clip viewer: BVH units to metres (0.01 for centimetres)")->capture_default_str();
  cli.add_option("--clip", clip_name, "Clip viewer: the clip to show (default: the first)");
  cli.add_option("--frames", frames, "Clip viewer: frames in a strip")->capture_default_str()->check(CLI::Range(1, 64));
  cli.add_option("--time", time, "Clip viewer, headless screenshot: seconds into the clip")->capture_default_str();
  cli.add_flag("--no-obstacle", no_props, "Clip viewer: do not place the obstacle of the clip's role");
  CLI11_PARSE(cli, argc, argv);

  render::RenderSettings render;
  render.shadow_map_size = shadow_map;
  render.skinned_bodies = !capsules;
  WindowOptions w;
  w.width = width > 0 ? width : w.width;
  w.height = height > 0 ? height : w.height;
  w.vsync = !no_vsync;
  w.screenshot = screenshot;
  w.screenshot_after = screenshot_after;
  w.quit_after = quit_after;
  w.clearance = clearance;
  w.stress_seconds = stress_seconds;
  w.stress_seed = stress_seed;
  try {
    w.script = parse_key_script(script);
    // A folder of takes: its set plays the course; anything else named by --motions opens the clip viewer.
    std::shared_ptr<const MotionFolder> folder;
    if (std::filesystem::is_directory(motions_arg)) {
      if (viewer || !bvh.empty() || !clip_name.empty()) throw std::runtime_error("--motions DIR plays a course: not with --viewer, --clip or --bvh");
      const std::string course = scenario.empty() ? default_scenario_path() : scenario;
      std::cerr << "prep-demo: scanning " << motions_arg << std::endl;
      folder = open_motion_folder(motions_arg, course, default_policy_cache_dir());
      std::cerr << "prep-demo: " << folder->manifest << ": " << folder->scan.clips.size() << " clips; " << folder->scenario << std::endl;
      for (const std::string& c : folder->changes) std::cerr << "prep-demo: course: " << c << "\n";
      scenario = folder->scenario;
    }
    viewer = viewer || !bvh.empty() || !clip_name.empty() || (motions_arg != "builtin" && !folder);
    if (viewer) {
      if (!scenario.empty()) throw std::runtime_error("--scenario and the clip viewer (--viewer, --clip, --bvh, --motions) exclude each other");
      if (clearance) throw std::runtime_error("--clearance measures a scenario's world: the clip viewer has none");
      return clip_viewer(headless, motions_arg, bvh, unit_scale, clip_name, params_file, width, height, w, strip, frames, screenshot, time,
                         no_panels, no_props, bench_frames, render);
    }
    if (crowd > 0) {
      if (folder || viewer) throw std::runtime_error("--crowd plays a scenario's lanes: not with --motions DIR or the clip viewer");
      CrowdRunOptions c;
      c.scenario = scenario.empty() ? default_crowd_scenario_path() : scenario;
      c.lanes = crowd;
      c.seconds = seconds;
      c.width = w.width;
      c.height = w.height;
      c.screenshot = screenshot;
      c.bench_frames = bench_frames;
      c.panels = !no_panels;
      c.params = params_file;
      c.render = render;
      if (headless) {
        run_crowd_headless(c);
        return 0;
      }
      try {
        run_crowd_window(c, w);
      } catch (const render::NoDisplayError& e) {
        std::cerr << "prep-demo: " << e.what() << "\n";
        return 2;
      }
      return 0;
    }
    if (scenario.empty()) scenario = default_scenario_path();
    if (headless) {
      ScenarioRunOptions o;
      o.scenario = scenario;
      o.seconds = seconds;
      o.until_goal = until_goal;
      o.width = w.width;
      o.height = w.height;
      o.screenshot = screenshot;
      o.frames_dir = frames_dir;
      o.video = video;
      o.strip = strip;
      o.params = params_file;
      o.json = json;
      o.panels = !no_panels;
      o.clearance = clearance;
      o.bench_frames = bench_frames;
      o.render = render;
      o.motion_folder = folder;
      run_scenario_headless(o);  // whether the goal was reached is in what it prints
      return 0;
    }
    if (!frames_dir.empty() || !video.empty() || !strip.empty() || json || bench_frames > 0 || until_goal)
      throw std::runtime_error("--frames-dir, --video, --strip, --json, --until-goal and --bench-frames need --headless");
    try {
      run_demo_window(scenario, params_file.empty() ? std::nullopt : std::optional<Params>(load_params(params_file)), w, folder);
    } catch (const render::NoDisplayError& e) {
      std::cerr << "prep-demo: " << e.what() << "\n";
      return 2;
    }
  } catch (const std::exception& e) {
    std::cerr << "prep-demo: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
