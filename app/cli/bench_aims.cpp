#include "app/cli/bench_aims.h"

namespace prep::cli {
namespace {

constexpr double kFrameMs = 16.7;  // a frame at 60 Hz
constexpr double kSarsaMillionStepsPerSecond = 10.0;

struct SynthesisAim {
  const char* set;
  double with_balance_us, without_balance_us;
};
// Without balance: twice ozz-animation 0.16's blend and local-to-model, measured on a 2-core machine like
// this one (0.38 us at 22 joints, 0.67 us at 43). With balance: what a 60 Hz frame of 20,000 characters on
// two cores leaves the full synthesis.
constexpr SynthesisAim kSynthesisAims[] = {{"builtin", 1.5, 0.76}, {"daz43", 2.5, 1.34}};

}  // namespace

nlohmann::json Aim::to_json() const {
  return {{"figure", figure},
          {"aim", aim},
          {"at_most", at_most},
          {"measured", measured ? nlohmann::json(value) : nlohmann::json(nullptr)},
          {"met", measured ? nlohmann::json(met()) : nlohmann::json(nullptr)}};
}

std::vector<Aim> aims_of(const nlohmann::json& bench) {
  std::vector<Aim> aims;
  Aim sarsa{"SARSA: million steps per second", kSarsaMillionStepsPerSecond, false};
  if (bench.contains("sarsa")) sarsa.measured = true, sarsa.value = bench["sarsa"]["steps_per_second"].get<double>() / 1e6;
  aims.push_back(sarsa);

  const nlohmann::json none = nlohmann::json::array();
  const nlohmann::json& synthesis = bench.contains("synthesis") ? bench["synthesis"] : none;
  for (const SynthesisAim& a : kSynthesisAims) {
    for (bool balance : {true, false}) {
      Aim aim{std::string("synthesis, ") + a.set + (balance ? ", with" : ", without") + " balance: us per character-frame",
              balance ? a.with_balance_us : a.without_balance_us};
      for (const auto& s : synthesis) {
        if (s["set"] == a.set && s["balance"] == balance) aim.measured = true, aim.value = s["us_per_character_frame"].get<double>();
      }
      aims.push_back(aim);
    }
  }

  const nlohmann::json& crowd = bench.contains("crowd") ? bench["crowd"] : none;
  const auto crowd_aim = [&](int characters, const char* what, const char* key) {
    Aim aim{"crowd of " + std::to_string(characters) + ": " + what + " ms per frame", kFrameMs};
    for (const auto& c : crowd) {
      if (c["characters"] == characters) aim.measured = true, aim.value = c[key].get<double>();
    }
    aims.push_back(aim);
  };
  crowd_aim(1000, "mean", "ms_per_frame");
  crowd_aim(20000, "mean", "ms_per_frame");
  crowd_aim(20000, "worst", "max_ms_per_frame");
  return aims;
}

}  // namespace prep::cli
