// The soak: a short one runs clean and does what it says (courses, goals, Params changes); each check
// catches the state it is for.
#include "engine/world/soak.h"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "tests/support/paths.h"
#include "tests/world/builtin_assets.h"

using namespace prep;

TEST_CASE("a short soak: courses regenerated, goals moved, Params changed live and for a retraining, no violation") {
  SoakOptions o;
  o.hours = 840.0 / 3600.0;  // past the first change that retrains, at 10 minutes, and the quiet end after it
  o.characters = 6;
  o.seed = 3;
  o.cache_dir = test::tmp_dir() + "/policy-cache";
  int periods = 0;
  const SoakReport r = run_soak(o, [&](const SoakPeriod&) { ++periods; });
  REQUIRE(r.hours.size() == 1);
  CHECK(periods == 1);
  const SoakPeriod& p = r.hours[0];
  for (const std::string& v : p.first_violations) MESSAGE(v);
  CHECK(p.simulated_s == doctest::Approx(840.0).epsilon(0.001));
  CHECK(r.characters >= 6);
  CHECK(p.character_ticks >= static_cast<std::int64_t>(6 * 840 * 60));
  CHECK(p.courses >= 6);           // every world has been regenerated at least once
  CHECK(p.goals_moved > 50);
  CHECK(p.params_changes >= 60);   // one every 10 s, and the retraining one
  CHECK(p.retrains >= 1);
  CHECK(p.violations.total() == 0);
  CHECK(r.ok());
  // Under AddressSanitizer glibc's mallinfo2 sees nothing (ASan has its own allocator): 0 both times.
  CHECK(r.heap_first_minute_mb >= 0.0);
  CHECK(r.heap_end_mb <= r.heap_first_minute_mb + 1.0);
  const auto j = soak_json(r);
  CHECK(j["ok"] == true);
  CHECK(j["hours"][0]["violations"]["total"] == 0);
}

TEST_CASE("soak checks: a NaN, alpha out of range, the root out of its range, a foot in the floor") {
  const WorldAssets& assets = *test::builtin_assets();
  World world(load_scenario(test::repo() + "/assets/scenarios/kick.json"), test::builtin_assets());
  world.run(1.0f);
  const glm::vec2 range = root_height_range(*assets.set);
  CHECK(range.x < range.y);
  const WorldCharacter good = world.characters()[0];
  SoakViolations v;
  CHECK(check_character(good, *assets.set, range, v).empty());
  CHECK(v.total() == 0);

  WorldCharacter c = good;
  c.pose.rotations[3].x = std::numeric_limits<float>::quiet_NaN();
  CHECK(check_character(c, *assets.set, range, v).find("NaN") != std::string::npos);
  CHECK(v.bad_pose == 1);
  c = good;
  c.alpha = 1.2f;
  CHECK(check_character(c, *assets.set, range, v).find("alpha") != std::string::npos);
  CHECK(v.alpha_range == 1);
  c = good;
  c.pose.root_position.y = range.y + 0.5f;
  CHECK(check_character(c, *assets.set, range, v).find("root height") != std::string::npos);
  CHECK(v.root_height == 1);
  c = good;
  c.pose.root_position.y -= 0.1f;  // the whole body 10 cm down: its feet in the floor
  CHECK(check_character(c, *assets.set, range, v).find("below the floor") != std::string::npos);
  CHECK(v.foot_below == 1);
  CHECK(v.total() == 4);
}
