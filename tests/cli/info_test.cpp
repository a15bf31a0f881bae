#include <doctest/doctest.h>

#include <algorithm>
#include <iostream>
#include <sstream>

#include "app/cli/command.h"
#include "tests/cli/run_subcommand.h"
#include "app/cli/info.h"
#include "engine/motion/motion_set.h"
#include "engine/util/error.h"
#include "tests/support/paths.h"

// The registry main.cpp defines for the real tool.
namespace prep::cli {
std::vector<Command>& commands() {
  static std::vector<Command> all;
  return all;
}
}  // namespace prep::cli

using namespace prep;

namespace {
std::string run(const std::string& name, std::vector<std::string> args) { return test::run_subcommand(name, std::move(args)); }

cli::RegisterInfoSection test_section({"test_section", 1000,
                                       [](const MotionSet& set, const Params&) { return nlohmann::json{{"clips", set.clips.size()}}; },
                                       nullptr});
}  // namespace

TEST_CASE("prep info --json describes a manifest in its documented shape, with registered sections appended") {
  const std::string manifest = test::repo() + "/assets/manifests/cmu31.json";
  const nlohmann::json d = nlohmann::json::parse(run("info", {"--json", "--motions", manifest}));
  CHECK(d["skeleton"]["joints"] == 31);
  REQUIRE(d["clips"].is_array());
  CHECK(d["clips"].size() == 10);  // the manifest's nine, and the stand held from the walk (it has no idle)
  for (const auto& c : d["clips"]) {
    CAPTURE(c.dump());
    CHECK(parse_role(c["role"].get<std::string>()).has_value());
    CHECK(c["frames"].get<int>() > 0);
    CHECK(c["fps"].get<double>() == doctest::Approx(30.0).epsilon(1e-4));
    CHECK(c["seconds"].get<double>() == doctest::Approx(c["frames"].get<double>() / c["fps"].get<double>()));
    for (const char* side : {"left", "right"}) {
      CHECK(c["contact"][side].get<double>() >= 0.0);
      CHECK(c["contact"][side].get<double>() <= 1.0);
    }
    CHECK(c["com_in_support"].get<double>() >= 0.0);
    CHECK(c["com_in_support"].get<double>() <= 1.0);
  }
  // The walk has both feet down often, the running jump is mostly in the air or on one foot.
  const auto& walk = d["clips"][0];
  CHECK(walk["name"] == "walk_69_01");
  CHECK(walk["role"] == "walk");
  CHECK(walk["frames"] == 70);
  CHECK(walk["contact"]["left"].get<double>() > 0.4);
  CHECK(walk["contact"]["right"].get<double>() > 0.4);
  CHECK(d["test_section"]["clips"] == 10);
}

TEST_CASE("prep info prints a table with every clip and explains the balance column") {
  const std::string text = run("info", {"--motions", test::repo() + "/assets/manifests/cmu31.json"});
  CHECK(text.find("skeleton: 31 joints") != std::string::npos);
  for (const char* name : {"walk_69_01", "turn_left_69_27", "crawl_111_03", "duck_127_29", "jump_127_25", "punch_right_14_01", "punch_left_14_01"})
    CHECK(text.find(name) != std::string::npos);
  CHECK(text.find("frames in flight are left out") != std::string::npos);
  CHECK(text.find("test_section:") != std::string::npos);
}

TEST_CASE("prep info names a manifest that is not there") {
  CHECK_THROWS_WITH_AS(run("info", {"--motions", "/nonexistent/set.json"}), doctest::Contains("/nonexistent/set.json"), InputError);
}
