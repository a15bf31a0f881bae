// prep evaluate: the JSON shape, the markdown tables and the errors (the measures themselves are checked in
// tests/world/evaluation_test.cpp).
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli/command.h"
#include "tests/cli/run_subcommand.h"
#include "engine/util/error.h"
#include "tests/support/paths.h"

using namespace prep;

namespace {

std::string run_evaluate(std::vector<std::string> args) {
  args.insert(args.end(), {"--policy-cache", test::tmp_dir() + "/policy-cache"});
  return test::run_subcommand("evaluate", std::move(args));
}

const std::string kKick = test::repo() + "/assets/scenarios/kick.json";

void check_frame_metrics(const nlohmann::json& j) {
  for (const char* k : {"foot_skate_cm_per_frame", "pose_plausibility"}) {
    CAPTURE(k);
    REQUIRE(j.contains(k));
    CHECK(j[k].is_number());
  }
  REQUIRE(j.contains("com_in_support"));
  CHECK((j["com_in_support"].is_number() || j["com_in_support"].is_null()));
  CHECK(j["frames"].get<int>() >= j["synthesized_frames"].get<int>());
  CHECK(j["com_frames"].is_number_integer());
}

}  // namespace

TEST_CASE("prep evaluate --json: one run's object in its documented shape") {
  const nlohmann::json j = nlohmann::json::parse(run_evaluate({"--scenario", kKick, "--method", "ours", "--json"}));
  REQUIRE(j.is_object());
  CHECK(j["scenario"] == "kick");
  CHECK(j["motions"] == "builtin");
  CHECK(j["method"] == "ours");
  CHECK(j["seconds"].get<double>() > 0.0);
  CHECK(j["ticks"].get<int>() == static_cast<int>(std::lround(j["seconds"].get<double>() * 60.0)));
  const nlohmann::json& t = j["total"];
  CHECK(t["reached_goal"].is_boolean());
  CHECK((t["time_to_goal_s"].is_number() || t["time_to_goal_s"].is_null()));
  check_frame_metrics(t);
  CHECK(t["synthesis_us_per_frame"].get<double>() > 0.0);
  REQUIRE(t["launches"].is_array());
  REQUIRE_FALSE(t["launches"].empty());
  for (const auto& l : t["launches"]) {
    CAPTURE(l.dump());
    CHECK(l["action"] == "kick");
    for (const char* k : {"alpha_at_launch", "prep_lead_s", "peak_decel_mps2", "speed_at_launch_mps", "time_s"}) CHECK(l[k].is_number());
    CHECK(l["alpha_at_launch"].get<double>() >= 0.0);
    CHECK(l["alpha_at_launch"].get<double>() <= 1.0);
  }
  REQUIRE(j["characters"].size() == 1);
  const nlohmann::json& c = j["characters"][0];
  CHECK(c["control"] == "user");
  CHECK(c["reached_goal"] == t["reached_goal"]);
  check_frame_metrics(c);
  CHECK(c["launches"].size() == t["launches"].size());
}

TEST_CASE("prep evaluate: several methods give a JSON array, --markdown prints the tables, --plot-dir a plot per scenario") {
  const nlohmann::json a = nlohmann::json::parse(run_evaluate({"--scenario", kKick, "--method", "naive,ours", "--json"}));
  REQUIRE(a.is_array());
  REQUIRE(a.size() == 2);
  CHECK(a[0]["method"] == "naive");
  CHECK(a[1]["method"] == "ours");
  CHECK(a[0]["total"]["com_in_support"].is_null());  // naive never has alpha >= 0.3
  CHECK(a[0]["total"]["launches"][0]["alpha_at_launch"].get<double>() == 0.0);

  const std::string dir = test::tmp_dir() + "/evaluate-plots";
  std::filesystem::create_directories(dir);
  std::filesystem::remove(dir + "/alpha_kick.png");
  const std::string md = run_evaluate({"--scenario", kKick, "--markdown", "--plot-dir", dir});
  CHECK(md.find("| kick | builtin | ours |") != std::string::npos);
  CHECK(md.find("| kick | builtin | linear |") != std::string::npos);
  CHECK(md.find("| kick | builtin | naive |") != std::string::npos);
  CHECK(md.find("| kick (builtin) |") != std::string::npos);  // the acceptance table
  CHECK(std::filesystem::file_size(dir + "/alpha_kick.png") > 1000);
}

TEST_CASE("prep evaluate refuses an unknown method and names a missing scenario file") {
  CHECK_THROWS_WITH_AS(run_evaluate({"--scenario", kKick, "--method", "fancy"}), doctest::Contains("--method"), InputError);
  CHECK_THROWS_WITH_AS(run_evaluate({"--scenario", "/nonexistent/s.json"}), doctest::Contains("/nonexistent/s.json"), InputError);
}

TEST_CASE("prep evaluate --random --json: the courses, the total and a pass/fail per acceptance check") {
  const nlohmann::json j = nlohmann::json::parse(run_evaluate({"--random", "2", "--seed", "4", "--json"}));
  CHECK(j["seed"] == 4);
  CHECK(j["motions"] == "builtin");
  REQUIRE(j["courses"].size() == 2);
  CHECK(j["courses"][0]["name"] == "random-4-0");
  CHECK(j["courses"][1]["name"] == "random-4-1");
  for (const auto& c : j["courses"]) {
    CAPTURE(c.dump());
    CHECK(c["reached_goal"].is_boolean());
    CHECK(c["route_length_m"].get<double>() > 0.0);
    CHECK(c["launches"].is_array());
    CHECK(c["circling"]["seconds"].is_number());
    CHECK(c["weaving"]["most_reversals_in_window"].get<int>() <= c["weaving"]["turn_reversals"].get<int>());
  }
  const nlohmann::json& t = j["total"];
  CHECK(t["courses"] == 2);
  CHECK(t["weaving_courses"].get<int>() <= 2);
  CHECK(t["turn_reversals_per_minute"].get<double>() >= 0.0);
  REQUIRE(t["checks"].is_object());
  bool all = true;
  for (const char* name : {"goal_reached", "alpha_at_launch", "alpha_at_1m", "path_ratio", "no_source_alpha", "circling", "weaving"}) {
    CAPTURE(name);
    REQUIRE(t["checks"].contains(name));
    CHECK(t["checks"][name]["pass"].is_boolean());
    CHECK(t["checks"][name]["measure"].is_string());
    all = all && t["checks"][name]["pass"].get<bool>();
  }
  CHECK(t["checks"].size() == 7);
  CHECK(t["pass"] == all);
}

TEST_CASE("prep evaluate --random: text with the checks, and bad counts, motion sets and combinations refused") {
  const std::string text = run_evaluate({"--random", "1", "--seed", "4"});
  CHECK(text.find("random-4-0") != std::string::npos);
  CHECK(text.find("checks:") != std::string::npos);
  CHECK(text.find("goal_reached: ") != std::string::npos);
  CHECK(text.find("circling: ") != std::string::npos);
  CHECK_THROWS_WITH_AS(run_evaluate({"--random", "0"}), doctest::Contains("--random must be a positive number"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(run_evaluate({"--random", "-2"}), doctest::Contains("--random must be a positive number"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(run_evaluate({"--random", "2", "--motions", "nosuch.json"}), doctest::Contains("nosuch.json"), InputError);
  CHECK_THROWS_AS(run_evaluate({"--random", "2", "--scenario", kKick}), CLI::ExcludesError);
  CHECK_THROWS_AS(run_evaluate({"--seed", "3", "--scenario", kKick}), CLI::RequiresError);
  CHECK_THROWS_WITH_AS(run_evaluate({"--json"}), doctest::Contains("--scenario"), std::invalid_argument);
}
