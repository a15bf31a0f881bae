// A headless run's summary: the launches, the goal and the objects left (prep run, prep-demo --json).
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/world/world.h"

namespace prep {

RunSummary summarize(const World& world) {
  RunSummary s;
  s.scenario = world.scenario().name;
  s.seconds = world.time();
  s.launches = world.launches();
  s.goal_reached = world.goal_reached();
  s.goal_time = world.characters()[static_cast<size_t>(world.user())].reached_time;
  for (const WorldObject& o : world.objects()) {
    if (o.used) continue;
    if (o.spec.type == ObjectType::Opponent && world.characters()[static_cast<size_t>(o.character)].defeated) continue;
    char text[96];
    std::snprintf(text, sizeof text, "%s at (%.2f, %.2f)", object_type_name(o.spec.type), o.spec.position.x, o.spec.position.y);
    s.unused_objects.push_back(text);
  }
  return s;
}

std::string summary_json(const RunSummary& summary, const World& world) {
  nlohmann::json j;
  j["scenario"] = summary.scenario;
  j["seconds"] = summary.seconds;
  j["launches"] = nlohmann::json::array();
  for (const LaunchRecord& r : summary.launches) {
    nlohmann::json l;
    l["action"] = target_action_name(r.action);
    l["alpha_at_launch"] = r.alpha_at_launch;
    l["time"] = r.time;
    l["character"] = r.character;
    l["control"] = control_name(world.characters()[static_cast<size_t>(r.character)].control);
    l["automatic"] = r.automatic;
    if (r.level_at_arrival >= 0.0f) l["level_at_arrival"] = r.level_at_arrival;
    if (r.alpha_at_1m >= 0.0f) l["alpha_at_1m"] = r.alpha_at_1m;
    l["miss"] = r.miss;
    if (r.object >= 0) l["object"] = r.object;
    if (r.target_character >= 0) l["target_character"] = r.target_character;
    j["launches"].push_back(l);
  }
  j["goal_reached"] = summary.goal_reached;
  if (summary.goal_reached) j["goal_time"] = summary.goal_time;
  j["objects_without_launch"] = summary.unused_objects;
  return j.dump(2);
}

std::string summary_text(const RunSummary& summary) {
  std::string out = "scenario " + summary.scenario + ", " + std::to_string(summary.seconds) + " s\n";
  char line[224];
  for (const LaunchRecord& r : summary.launches) {
    char at_1m[16] = "-", level[16] = "-";  // -1: the approach began within 1 m / no arrival
    if (r.alpha_at_1m >= 0.0f) std::snprintf(at_1m, sizeof at_1m, "%.2f", r.alpha_at_1m);
    if (r.level_at_arrival >= 0.0f) std::snprintf(level, sizeof level, "%.1f", r.level_at_arrival);
    std::snprintf(line, sizeof line, "  %6.2f s  character %d  %-11s alpha_at_launch %.3f  (1 m before: %s, level on arrival %s, miss %+.2f m)%s\n",
                  r.time, r.character, target_action_name(r.action), r.alpha_at_launch, at_1m, level, r.miss,
                  r.automatic ? "  (auto)" : "");
    out += line;
  }
  if (summary.goal_reached) {
    std::snprintf(line, sizeof line, "goal reached at %.2f s\n", summary.goal_time);
    out += line;
  } else {
    out += "goal not reached\n";
  }
  for (const std::string& o : summary.unused_objects) out += "no launch at " + o + "\n";
  return out;
}

}  // namespace prep
