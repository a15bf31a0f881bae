#include "app/demo/stress.h"

#include <cstdio>
#include <filesystem>

#include "app/demo/demo_app.h"
#include "engine/util/error.h"
#include "engine/util/files.h"
#include "engine/world/world.h"

namespace prep::demo {

namespace {

using nlohmann::json;

// A Params file broken the way a hand edit breaks one: a field of the wrong type.
constexpr const char* kBrokenParams = "{\n  \"balance\": {\n    \"w_b\": \"heavy\"\n  }\n}\n";

}  // namespace

StressScript::StressScript(std::uint64_t seed, double seconds, std::string broken_params)
    : rng_(seed), seconds_(seconds), broken_path_(std::move(broken_params)), defaults_(json::parse(params_to_json(Params{}))) {}

StressScript::~StressScript() {
  std::error_code ec;
  if (broken_done_) std::filesystem::remove(broken_path_, ec);
}

void StressScript::before_frame(DemoApp& app, double elapsed) {
  ++report_.frames;
  // Any tunable every kAnyTunableEvery seconds; in between one the world takes live, so that the world
  // runs between the reloads and retrainings the others cause.
  const bool any = elapsed >= next_any_;
  if (any) next_any_ += kAnyTunableEvery;
  change_tunable(app, any);
  if (elapsed >= next_switch_ && !app.scenarios.empty()) {
    next_switch_ += kScenarioEvery;
    app.open_scenario(app.scenarios[static_cast<size_t>(rng_.below(static_cast<int>(app.scenarios.size())))].path);
    ++report_.scenario_switches;
  }
  if (rng_.uniform() < kLaunchChance) {
    ++report_.launches_asked;
    report_.launches_started += app.session().launch(static_cast<TargetAction>(rng_.below(kTargetActionCount))) ? 1 : 0;
  }
  if (!broken_done_ && elapsed >= 0.5 * seconds_) load_broken(app);
}

// One field of the Params, from the defaults, set to a nearby value: a switch flipped, a count one up or
// down, a number scaled by 0.7-1.3.
void StressScript::change_tunable(DemoApp& app, bool any) {
  std::vector<std::pair<std::string, std::string>> fields;
  for (const auto& [section, values] : defaults_.items())
    if (values.is_object())
      for (const auto& [field, value] : values.items())
        if (value.is_number() || value.is_boolean()) fields.emplace_back(section, field);
  const Params defaults;
  for (int attempt = 0; attempt < 50; ++attempt) {
    const auto& [section, field] = fields[static_cast<size_t>(rng_.below(static_cast<int>(fields.size())))];
    json j = defaults_;
    json& v = j[section][field];
    if (v.is_boolean()) {
      v = !v.get<bool>();
    } else if (v.is_number_integer()) {
      v = v.get<std::int64_t>() + (rng_.below(2) == 0 ? -1 : 1);
    } else {
      v = v.get<double>() == 0.0 ? static_cast<double>(rng_.uniform(0.0f, 0.1f)) : v.get<double>() * static_cast<double>(rng_.uniform(0.7f, 1.3f));
    }
    Params p;
    try {
      p = params_from_json(j.dump(), "stress: " + section + "." + field);
    } catch (const InputError&) {
      ++report_.params_refused;
      return;
    }
    const bool live = same_world_assets_params(p, defaults) && policy_params_hash(p) == policy_params_hash(defaults);
    if (!any && !live) continue;
    app.session().set_params(p);
    ++report_.params_changes;
    report_.reloading_changes += live ? 0 : 1;
    return;
  }
}

void StressScript::load_broken(DemoApp& app) {
  broken_done_ = true;
  write_file_atomic(broken_path_, kBrokenParams);
  const std::string before = params_to_json(app.session().params());
  app.load_params_file(broken_path_);
  report_.broken_file = broken_path_;
  report_.broken_message = app.message;
  report_.broken_named = app.message.find(broken_path_) != std::string::npos;
  report_.old_values_kept = params_to_json(app.session().params()) == before;
}

std::string StressScript::summary() const {
  const StressReport& r = report_;
  char text[512];
  std::snprintf(text, sizeof text,
                "stress: %d frames, %d Params changes (%d reloading or retraining, %d refused), %d scenario switches, %d launches asked (%d started); "
                "the broken Params file: \"%s\" (%s the file), old values %s: %s",
                r.frames, r.params_changes, r.reloading_changes, r.params_refused, r.scenario_switches, r.launches_asked, r.launches_started,
                r.broken_message.c_str(), r.broken_named ? "names" : "does not name", r.old_values_kept ? "kept" : "LOST",
                r.ok() ? "ok" : "FAILED");
  return text;
}

}  // namespace prep::demo
