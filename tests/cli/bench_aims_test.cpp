// prep bench's aims: each found in the run's JSON by its set, balance and crowd size, met or not by its
// bound, and null where the run did not measure it.
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "app/cli/bench_aims.h"

namespace {

const prep::cli::Aim& find(const std::vector<prep::cli::Aim>& aims, const std::string& figure) {
  for (const prep::cli::Aim& a : aims)
    if (a.figure == figure) return a;
  FAIL("no aim named " << figure);
  return aims.front();
}

}  // namespace

TEST_CASE("prep bench's aims: each measured figure taken from its own row and held to its own bound") {
  const nlohmann::json bench = nlohmann::json::parse(R"({
    "sarsa": {"steps_per_second": 17.9e6},
    "synthesis": [
      {"set": "builtin", "balance": true, "us_per_character_frame": 1.49},
      {"set": "builtin", "balance": false, "us_per_character_frame": 0.77},
      {"set": "daz43", "balance": true, "us_per_character_frame": 2.6},
      {"set": "daz43", "balance": false, "us_per_character_frame": 1.2}
    ],
    "crowd": [
      {"characters": 1000, "ms_per_frame": 1.2, "max_ms_per_frame": 2.0},
      {"characters": 20000, "ms_per_frame": 16.0, "max_ms_per_frame": 23.1}
    ]})");
  const std::vector<prep::cli::Aim> aims = prep::cli::aims_of(bench);
  CHECK(aims.size() == 8);

  const auto check = [&](const std::string& figure, double aim, double value, bool met) {
    CAPTURE(figure);
    const prep::cli::Aim& a = find(aims, figure);
    CHECK(a.aim == doctest::Approx(aim));
    CHECK(a.measured);
    CHECK(a.value == doctest::Approx(value));
    CHECK(a.met() == met);
    const nlohmann::json j = a.to_json();
    CHECK(j["met"] == met);
    CHECK(j["measured"].get<double>() == doctest::Approx(value));
  };
  check("SARSA: million steps per second", 10.0, 17.9, true);  // at least
  check("synthesis, builtin, with balance: us per character-frame", 1.5, 1.49, true);
  check("synthesis, builtin, without balance: us per character-frame", 0.76, 0.77, false);
  check("synthesis, daz43, with balance: us per character-frame", 2.5, 2.6, false);
  check("synthesis, daz43, without balance: us per character-frame", 1.34, 1.2, true);
  check("crowd of 1000: mean ms per frame", 16.7, 1.2, true);
  check("crowd of 20000: mean ms per frame", 16.7, 16.0, true);
  check("crowd of 20000: worst ms per frame", 16.7, 23.1, false);
}

TEST_CASE("prep bench's aims: a figure the run did not measure is null, neither met nor missed") {
  const nlohmann::json bench = nlohmann::json::parse(R"({
    "sarsa": {"steps_per_second": 9e6},
    "synthesis": [{"set": "builtin", "balance": true, "us_per_character_frame": 1.4}],
    "crowd": [{"characters": 1000, "ms_per_frame": 17.0, "max_ms_per_frame": 20.0}]})");
  const std::vector<prep::cli::Aim> aims = prep::cli::aims_of(bench);
  CHECK_FALSE(find(aims, "SARSA: million steps per second").met());
  CHECK_FALSE(find(aims, "crowd of 1000: mean ms per frame").met());
  for (const char* figure : {"synthesis, daz43, with balance: us per character-frame", "crowd of 20000: mean ms per frame",
                             "crowd of 20000: worst ms per frame"}) {
    CAPTURE(figure);
    const prep::cli::Aim& a = find(aims, figure);
    CHECK_FALSE(a.measured);
    CHECK(a.to_json()["measured"].is_null());
    CHECK(a.to_json()["met"].is_null());
  }
}
