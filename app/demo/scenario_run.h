// prep-demo --headless --scenario FILE: the demo (DemoApp: the world at its fixed step, the renderer, the
// panels) drawn through OSMesa with no display: a screenshot of the last frame, a PNG per frame, a video
// through ffmpeg when it is installed, a PNG strip of frames, a frame-rate benchmark, and the launches
// printed as JSON. The policy is loaded from the cache or trained first (progress on stderr).
//
// --until-goal ends the run once the course is done instead of after --seconds of standing at the goal:
// a run of the world alone (no drawing; the world is deterministic) finds the frame, then the world
// restarts and the drawn run stops there, so the strip's frames and the video span the course.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/demo/motion_folder.h"
#include "app/render/image.h"
#include "app/render/renderer.h"
#include "engine/world/world.h"

namespace prep::demo {

class WorldSession;

struct ScenarioRunOptions {
  std::string scenario;
  float seconds = 30.0f;    // simulated; with until_goal the most
  bool until_goal = false;  // end kGoalTail after the user's goal is reached and no target motion plays
  int width = 1280, height = 720;
  std::string screenshot;   // PNG of the last frame
  std::string frames_dir;   // PNGs frame_00000.png ... at kVideoFps
  std::string video;        // MP4 through ffmpeg (raw frames piped in); without ffmpeg a strip is written instead
  std::string strip;        // PNG: kStripTiles frames spread over the run, in a grid
  std::string params;       // Params JSON (default: the scenario's)
  std::string cache_dir;    // policy cache ("" = default_policy_cache_dir())
  bool json = false;
  bool panels = true;
  bool clearance = false;   // the clearance view on (DemoView::show_clearance)
  int bench_frames = 0;     // > 0: a benchmark of this many frames (1/60 s each) instead of a run
  render::RenderSettings render;
  std::shared_ptr<const MotionFolder> motion_folder;  // the user's folder of takes the scenario was made for
};

constexpr int kVideoFps = 30;
constexpr int kStripColumns = 3, kStripRows = 2;  // a 3x2 grid of frames
constexpr int kStripTiles = kStripColumns * kStripRows;
// s shown after the course is done: the character settles into standing at its goal.
constexpr float kGoalTail = 1.0f;

// What a run did, as it printed it (the tests read it).
struct ScenarioRunResult {
  int frames = 0;                  // frames of 1/kVideoFps run
  float seconds = 0.0f;            // the world's time at the end
  std::vector<float> strip_times;  // the world's time in each strip tile
  int frames_written = 0;          // into the video or the frames folder
  RunSummary summary;
};

// Runs, writes what the options ask for and prints the outcome (text, or JSON with options.json).
ScenarioRunResult run_scenario_headless(const ScenarioRunOptions& options);

// Frames (of 1/kVideoFps) the run lasts: seconds * kVideoFps, or with until_goal fewer when the course is
// done before: up to the first frame by which, for kGoalTail, the user's goal has been reached and no
// character has played a target motion. Advances the session's running world to find it.
int run_frames(WorldSession& session, float seconds, bool until_goal);

// The strip's frames among a run's: kStripTiles spread evenly over it, the first a second in (the
// character has started moving; in a run under kStripTiles seconds a sixth of the way) and the last the
// run's last, in order.
std::vector<int> strip_frames(int frames);

// Whether ffmpeg can be run (on PATH).
bool ffmpeg_available();

// The image shrunk by an integer factor (box filter), for strip tiles.
render::Image downscale(const render::Image& image, int factor);

}  // namespace prep::demo
