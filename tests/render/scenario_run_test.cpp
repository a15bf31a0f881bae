// prep-demo --headless --scenario: the strip of frames (the fallback when ffmpeg is missing), the box
// filter its tiles are shrunk with, and the run that ends when the course is done (--until-goal).
#include "app/demo/scenario_run.h"

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "app/render/palette.h"
#include "tests/support/paths.h"

using namespace prep;
using render::palette::PixelClass;

TEST_CASE("downscale: each pixel is the mean of its factor x factor block") {
  render::Image image(4, 2);
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 2; ++y)
      for (int c = 0; c < 4; ++c) image.pixel(x, y)[c] = static_cast<std::uint8_t>(x < 2 ? 10 * (x + y) : 200);
  const render::Image small = demo::downscale(image, 2);
  REQUIRE(small.width == 2);
  REQUIRE(small.height == 1);
  CHECK(small.pixel(0, 0)[0] == 10);  // (0 + 10 + 10 + 20) / 4
  CHECK(small.pixel(1, 0)[2] == 200);
}

TEST_CASE("a headless scenario run writes a strip of its frames, every tile showing the scene") {
  std::filesystem::create_directories(test::tmp_dir());
  demo::ScenarioRunOptions o;
  o.scenario = test::repo() + "/assets/scenarios/obstacles.json";
  o.seconds = 2.5f;
  o.width = 480;
  o.height = 270;
  o.strip = test::tmp_dir() + "/scenario_strip.png";
  o.cache_dir = test::tmp_dir() + "/policy-cache";
  std::filesystem::remove(o.strip);
  demo::run_scenario_headless(o);
  const render::Image strip = render::read_png(o.strip);
  const int tw = o.width / 3, th = o.height / 3;
  REQUIRE(strip.width == demo::kStripColumns * tw);
  REQUIRE(strip.height == demo::kStripRows * th);
  for (int t = 0; t < demo::kStripTiles; ++t) {
    CAPTURE(t);
    int ground = 0, character = 0;
    const int x0 = (t % demo::kStripColumns) * tw, y0 = (t / demo::kStripColumns) * th;
    for (int y = y0; y < y0 + th; ++y)
      for (int x = x0; x < x0 + tw; ++x) {
        const std::uint8_t* c = strip.pixel(x, y);
        const PixelClass k = render::palette::classify(c[0], c[1], c[2]);
        ground += k == PixelClass::Ground;
        character += k == PixelClass::Character;
      }
    CHECK(ground > tw * th / 4);
    CHECK(character > 20);  // the camera follows the character in the frames that are not drawn too
  }
}

TEST_CASE("the strip's frames spread over the run: a second in, then evenly to its last frame") {
  const std::vector<int> f = demo::strip_frames(761);
  REQUIRE(f.size() == static_cast<size_t>(demo::kStripTiles));
  CHECK(f.front() == demo::kVideoFps);
  CHECK(f.back() == 760);
  for (size_t k = 1; k < f.size(); ++k) CHECK(f[k] - f[k - 1] == doctest::Approx(146.0).epsilon(0.01));
  // A run shorter than the strip: every tile within it, the last its last frame.
  const std::vector<int> g = demo::strip_frames(3);
  for (int k : g) CHECK((k >= 0 && k <= 2));
  CHECK(g.back() == 2);
}

TEST_CASE("--until-goal: the run ends a second after the goal is reached, and the strip spans the course up to it") {
  std::filesystem::create_directories(test::tmp_dir());
  demo::ScenarioRunOptions o;
  o.scenario = test::repo() + "/assets/scenarios/obstacles.json";
  o.seconds = 40.0f;
  o.until_goal = true;
  o.width = 480;
  o.height = 270;
  o.strip = test::tmp_dir() + "/scenario_strip_until_goal.png";
  o.cache_dir = test::tmp_dir() + "/policy-cache";
  const demo::ScenarioRunResult r = demo::run_scenario_headless(o);
  REQUIRE(r.summary.goal_reached);
  // Every obstacle was met on the way (the course is the one a full run plays) ...
  CHECK(r.summary.launches.size() == 3);
  CHECK(r.summary.unused_objects.empty());
  // ... and the run stops kGoalTail after the goal (the course's last target motion ends before it),
  // not at --seconds.
  CHECK(r.seconds == doctest::Approx(r.summary.goal_time + demo::kGoalTail).epsilon(0.1 / 25.0));
  CHECK(r.seconds < o.seconds - 10.0f);
  CHECK(r.frames == static_cast<int>(std::lround(r.seconds * demo::kVideoFps)));
  // The strip: a second in, in order, evenly spread, the last tile the run's last frame, past the goal.
  REQUIRE(r.strip_times.size() == static_cast<size_t>(demo::kStripTiles));
  CHECK(r.strip_times.front() == doctest::Approx(1.0f).epsilon(0.05));
  CHECK(r.strip_times.back() == doctest::Approx(r.seconds));
  CHECK(r.strip_times.back() >= r.summary.goal_time);
  const float gap = (r.strip_times.back() - r.strip_times.front()) / (demo::kStripTiles - 1);
  for (size_t k = 1; k < r.strip_times.size(); ++k) CHECK(r.strip_times[k] - r.strip_times[k - 1] == doctest::Approx(gap).epsilon(0.02));

  // The drawn run is the world's course as a run to --seconds plays it (the world restarts for it and is
  // deterministic): the same launches at the same times, the goal at the same time.
  demo::ScenarioRunOptions full;
  full.scenario = o.scenario;
  full.seconds = 30.0f;
  full.cache_dir = o.cache_dir;
  const demo::ScenarioRunResult f = demo::run_scenario_headless(full);
  CHECK(f.seconds == doctest::Approx(30.0f).epsilon(1e-3));
  CHECK(f.summary.goal_time == doctest::Approx(r.summary.goal_time));
  REQUIRE(f.summary.launches.size() == r.summary.launches.size());
  for (size_t k = 0; k < f.summary.launches.size(); ++k) {
    CHECK(f.summary.launches[k].action == r.summary.launches[k].action);
    CHECK(f.summary.launches[k].time == doctest::Approx(r.summary.launches[k].time));
  }
}
