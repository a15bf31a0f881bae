// The speed aims `prep bench` measures against, and whether a run met each: SARSA's steps per second, a
// crowd of 1,000 within a 60 Hz frame, and the stadium's aims on a 2-core machine: a crowd of 20,000 within
// the frame on average and at its worst, and synthesis per character-frame on one core, with and without
// the balance optimizer, for the 22-joint built-in body and the 43-joint daz43 set.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace prep::cli {

struct Aim {
  std::string figure;
  double aim = 0.0;
  bool at_most = true;  // else at least
  bool measured = false;  // false: the run did not measure this figure (a smaller crowd, a set not found)
  double value = 0.0;

  bool met() const { return at_most ? value <= aim : value >= aim; }
  // {"figure", "aim", "at_most", "measured", "met"}; "measured" and "met" are null when not measured.
  nlohmann::json to_json() const;
};

// The aims, each with its figure from `bench`, the JSON object `prep bench --json` prints (its "sarsa",
// "synthesis" and "crowd" entries).
std::vector<Aim> aims_of(const nlohmann::json& bench);

}  // namespace prep::cli
