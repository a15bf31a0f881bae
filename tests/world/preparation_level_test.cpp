// The level of preparation chosen again as the source comes a distance bin nearer
// (RuntimeParams::level_per_source_bin), on built-in courses where it was chosen too far out.
#include <doctest/doctest.h>

#include "engine/world/world.h"
#include "tests/world/builtin_assets.h"
#include "tests/world/builtin_courses.h"

using namespace prep;

TEST_CASE("the level chosen again a distance bin nearer: approaches that prepared late are prepared a metre before") {
  // Four built-in courses of seed 1 whose launch was below alpha 0.5 a metre before it while a gait cycle's
  // action outlasted the source's distance bins (two ducks, two punches): the level chosen two bins out
  // was kept to within a metre. With the level chosen again on each nearer bin they are prepared.
  Params off = test::builtin_assets()->params;
  off.runtime.level_per_source_bin = false;
  int late_without = 0;
  for (int k : {89, 101, 132, 177}) {
    CAPTURE(k);
    const Scenario s = test::builtin_random_course(1, k);
    World with(s, test::builtin_assets()), without(s, test::builtin_assets());
    without.set_params(off);
    const auto first_measured = [](World& world) {
      for (int tick = 0; tick < 60 * 40; ++tick) {
        world.step();
        for (const LaunchRecord& r : world.launches())
          if (r.character == world.user() && r.alpha_at_1m >= 0.0f) return r.alpha_at_1m;
      }
      return -1.0f;
    };
    const float a_with = first_measured(with), a_without = first_measured(without);
    CHECK(a_with >= 0.5f);
    if (a_without >= 0.0f && a_without < 0.5f) ++late_without;
  }
  CHECK(late_without >= 3);
}
