// A scenario (Sec. 7.2): the characters, the objects they interact with, the goal, and whether target
// motions are launched automatically. Loaded from JSON, strictly: an unknown field, a missing required
// field, a wrong type or an unknown name is an InputError naming the file and the field.
//
// Schema (units: metres on the floor plane, headings in DEGREES about +Y, 0 = facing +Z, 90 = facing +X;
// a floor point is [x, z]):
// {
//   "name": "obstacles",                   // optional, default: the file name without folder and extension
//   "description": "free text",            // optional
//   "auto": true,                          // optional (default false): launch each object's target motion when
//                                          //   the character reaches it, for unattended runs
//   "motions": "builtin",                  // optional: "builtin" (default) or a motion-set manifest path
//                                          //   (relative to the repository root, or absolute)
//   "params": "my_params.json",            // optional: a Params file (relative to the scenario file's folder)
//   "characters": [                        // required, at least one, exactly one "user"
//     {"position": [0, 0], "heading": 0, "control": "user"},
//     {"position": [0, 6], "heading": 180, "control": "opponent", "action": "punch_left"}
//   ],                                     // "heading" optional (default 0); "action" only for opponents (the
//                                          //   action the user meets it with; default "punch_right")
//   "objects": [                           // optional (default none)
//     {"type": "bar", "action": "crawl", "position": [0, 4], "heading": 0, "size": [2.0, 0.8, 0.1]}
//   ],
//   "goal": [0, 12]                        // required: one point [x, z] ...
//   "goal": [[0, 6], [0, 12]]              // ... or waypoints, reached in order
// }
// Object types and the actions they accept: ball -> kick; bar -> crawl; beam -> duck; hurdle -> jump;
// opponent -> punch_left or punch_right (an opponent object is an opponent character standing there).
// "action" is optional and defaults to the type's first action. "heading" (default 0) turns the obstacle: at
// 0 a bar/beam/hurdle spans the X axis and is crossed walking along +Z. "size" = [width (x), height, depth
// (z)]: for a bar or beam the height of its underside, for a hurdle the height of its top, for a ball its
// diameter in all three. Required for every type but opponent (where it is not allowed): an obstacle must
// match the clip that passes it (the built-in clips' obstacles are library::obstacle_of).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace prep {

enum class ObjectType { Ball, Bar, Beam, Hurdle, Opponent };
enum class TargetAction { Kick, Crawl, Duck, Jump, PunchLeft, PunchRight };
enum class Control { User, Opponent };

const char* object_type_name(ObjectType type);    // "ball", ...
const char* target_action_name(TargetAction a);   // "kick", "crawl", "duck", "jump", "punch_left", "punch_right"
const char* control_name(Control c);              // "user", "opponent"
std::optional<ObjectType> parse_object_type(std::string_view name);
std::optional<TargetAction> parse_target_action(std::string_view name);
// The action an object of this type calls for when the file names none, and whether it accepts `action`.
TargetAction default_action(ObjectType type);
bool accepts(ObjectType type, TargetAction action);
// The motion-set role name ("kick", "crawl", ...) of a target action (motion_set.h parse_role reads it).
const char* role_name_of(TargetAction action);

struct ScenarioCharacter {
  glm::vec2 position{0.0f};  // floor (x, z)
  float heading = 0.0f;      // radians
  Control control = Control::User;
  TargetAction action = TargetAction::PunchRight;  // for opponents: what the user meets it with
};

struct ScenarioObject {
  ObjectType type = ObjectType::Ball;
  TargetAction action = TargetAction::Kick;
  glm::vec2 position{0.0f};  // floor (x, z)
  float heading = 0.0f;      // radians
  glm::vec3 size{0.0f};      // width, height, depth (m)
};

struct Scenario {
  std::string name;
  std::string description;
  std::string file;          // where it was loaded from ("" when built in memory)
  bool auto_launch = false;
  std::string motions = "builtin";
  std::string params_file;   // resolved path, "" for the defaults
  std::vector<ScenarioCharacter> characters;
  std::vector<ScenarioObject> objects;
  std::vector<glm::vec2> goal;  // one point or waypoints in order (never empty)

  int user() const;  // index of the user character
};

// Parses scenario JSON text; `source_name` names it in errors and resolves the relative "params" path.
Scenario parse_scenario(const std::string& text, const std::string& source_name);
Scenario load_scenario(const std::string& path);
// The scenario as JSON text that parse_scenario reads back to the same scenario (headings in degrees, so
// within rounding; the "params" path as resolved).
std::string scenario_json(const Scenario& scenario);

}  // namespace prep
