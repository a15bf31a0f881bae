// prep run --keys: a scenario driven by the player at the steering keys, and its clearance report.
#include <doctest/doctest.h>

#include <algorithm>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli/command.h"
#include "tests/cli/run_subcommand.h"
#include "tests/support/paths.h"

using namespace prep;

namespace {

std::string run_run(std::vector<std::string> args) {
  args.insert(args.end(), {"--policy-cache", test::tmp_dir() + "/policy-cache"});
  return test::run_subcommand("run", std::move(args));
}

const std::string kObstacles = test::repo() + "/assets/scenarios/obstacles.json";

}  // namespace

TEST_CASE("prep run --keys: the run steered by the key player, with the clearance of every frame") {
  const std::string text = run_run({"--scenario", kObstacles, "--keys", "5", "--seconds", "12", "--json"});
  const nlohmann::json j = nlohmann::json::parse(text);
  CHECK(j["keys_seed"] == 5);
  REQUIRE(j.contains("clearance"));
  const nlohmann::json& c = j["clearance"];
  CHECK(c["frames"] == 12 * 60 + 1);  // the first frame and every tick
  CHECK(c["object_penetration_frames"] == 0);
  CHECK(c["character_overlap_frames"] == 0);
  CHECK(c["min_object_m"].get<double>() > -0.01);
  // The same seed, the same run.
  CHECK(run_run({"--scenario", kObstacles, "--keys", "5", "--seconds", "12", "--json"}) == text);
  // Text: the clearance lines after the launches.
  const std::string plain = run_run({"--scenario", kObstacles, "--keys", "5", "--seconds", "12"});
  CHECK(plain.find("clearance over 721 frames: 0 with a body in an object, 0 with two bodies overlapping") != std::string::npos);
  // Without --keys no clearance is reported.
  CHECK(nlohmann::json::parse(run_run({"--scenario", kObstacles, "--seconds", "2", "--json"})).count("clearance") == 0);
  CHECK_THROWS(run_run({"--scenario", kObstacles, "--keys", "-1"}));
}
