#include "engine/world/scenario.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "engine/util/error.h"
#include "engine/util/files.h"
#include "engine/world/floor.h"

namespace prep {
namespace {

using nlohmann::json;

using floor_plane::kDegrees;

struct Names {
  ObjectType type;
  const char* name;
};
constexpr Names kObjectNames[] = {{ObjectType::Ball, "ball"},
                                  {ObjectType::Bar, "bar"},
                                  {ObjectType::Beam, "beam"},
                                  {ObjectType::Hurdle, "hurdle"},
                                  {ObjectType::Opponent, "opponent"}};
struct ActionNames {
  TargetAction action;
  const char* name;
};
constexpr ActionNames kActionNames[] = {{TargetAction::Kick, "kick"},           {TargetAction::Crawl, "crawl"},
                                        {TargetAction::Duck, "duck"},           {TargetAction::Jump, "jump"},
                                        {TargetAction::PunchLeft, "punch_left"}, {TargetAction::PunchRight, "punch_right"}};

// A reader that names the field it is at ("objects[2].size") in every error.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    throw InputError(file_, "'" + field + "' " + message);
  }

  void only(const json& object, const std::string& where, std::initializer_list<const char*> known) const {
    if (!object.is_object()) fail(where, "must be an object");
    for (auto it = object.begin(); it != object.end(); ++it) {
      bool ok = false;
      for (const char* k : known) ok = ok || it.key() == k;
      if (!ok) fail(join(where, it.key()), "is not a known field");
    }
  }

  // Every number of a scenario is metres or degrees: beyond a million either way it is a mistake, and one
  // past a float's range (1e39) would become infinity.
  float number(const json& value, const std::string& field) const {
    if (!value.is_number()) fail(field, std::string("must be a number, not ") + value.type_name());
    const double v = value.get<double>();
    if (!std::isfinite(v)) fail(field, "must be finite");
    if (std::abs(v) > 1e6) fail(field, "is " + value.dump() + ": more than a million (metres or degrees) either way");
    return static_cast<float>(v);
  }

  glm::vec2 point(const json& value, const std::string& field) const {
    if (!value.is_array() || value.size() != 2) fail(field, "must be a floor point [x, z]");
    return {number(value[0], field + "[0]"), number(value[1], field + "[1]")};
  }

  std::string text(const json& value, const std::string& field) const {
    if (!value.is_string()) fail(field, std::string("must be a string, not ") + value.type_name());
    return value.get<std::string>();
  }

  static std::string join(const std::string& where, const std::string& key) {
    return where.empty() ? key : where + "." + key;
  }

 private:
  std::string file_;
};

std::string folder_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

std::string stem_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const size_t dot = name.find_last_of('.');
  return dot == std::string::npos ? name : name.substr(0, dot);
}

}  // namespace

const char* object_type_name(ObjectType type) {
  for (const auto& n : kObjectNames)
    if (n.type == type) return n.name;
  return "?";
}

const char* target_action_name(TargetAction a) {
  for (const auto& n : kActionNames)
    if (n.action == a) return n.name;
  return "?";
}

const char* control_name(Control c) { return c == Control::User ? "user" : "opponent"; }

std::optional<ObjectType> parse_object_type(std::string_view name) {
  for (const auto& n : kObjectNames)
    if (name == n.name) return n.type;
  return std::nullopt;
}

std::optional<TargetAction> parse_target_action(std::string_view name) {
  for (const auto& n : kActionNames)
    if (name == n.name) return n.action;
  return std::nullopt;
}

TargetAction default_action(ObjectType type) {
  switch (type) {
    case ObjectType::Ball: return TargetAction::Kick;
    case ObjectType::Bar: return TargetAction::Crawl;
    case ObjectType::Beam: return TargetAction::Duck;
    case ObjectType::Hurdle: return TargetAction::Jump;
    case ObjectType::Opponent: return TargetAction::PunchRight;
  }
  return TargetAction::Kick;
}

bool accepts(ObjectType type, TargetAction action) {
  if (type == ObjectType::Opponent) return action == TargetAction::PunchLeft || action == TargetAction::PunchRight;
  return action == default_action(type);
}

const char* role_name_of(TargetAction action) {
  switch (action) {
    case TargetAction::Kick: return "kick";
    case TargetAction::Crawl: return "crawl";
    case TargetAction::Duck: return "duck";
    case TargetAction::Jump: return "jump";
    case TargetAction::PunchLeft: return "punch_left";
    case TargetAction::PunchRight: return "punch_right";
  }
  return "?";
}

int Scenario::user() const {
  for (size_t i = 0; i < characters.size(); ++i)
    if (characters[i].control == Control::User) return static_cast<int>(i);
  return -1;
}

Scenario parse_scenario(const std::string& text, const std::string& source_name) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {  // parse errors, and numbers out of range (1e999)
    throw InputError(source_name, std::string("not valid JSON: ") + e.what());
  }
  const Reader r(source_name);
  r.only(root, "", {"name", "description", "auto", "motions", "params", "characters", "objects", "goal"});

  Scenario s;
  s.file = source_name;
  s.name = root.contains("name") ? r.text(root["name"], "name") : stem_of(source_name);
  if (root.contains("description")) s.description = r.text(root["description"], "description");
  if (root.contains("auto")) {
    if (!root["auto"].is_boolean()) r.fail("auto", std::string("must be true or false, not ") + root["auto"].type_name());
    s.auto_launch = root["auto"].get<bool>();
  }
  if (root.contains("motions")) {
    s.motions = r.text(root["motions"], "motions");
    if (s.motions.empty()) r.fail("motions", "must be \"builtin\" or a manifest path");
  }
  if (root.contains("params")) {
    const std::string p = r.text(root["params"], "params");
    if (p.empty()) r.fail("params", "must be a file path");
    s.params_file = p.front() == '/' ? p : folder_of(source_name) + p;
  }

  // Characters.
  if (!root.contains("characters")) r.fail("characters", "is missing (at least the user's character)");
  const json& characters = root["characters"];
  if (!characters.is_array() || characters.empty()) r.fail("characters", "must be a non-empty array");
  for (size_t i = 0; i < characters.size(); ++i) {
    const std::string where = "characters[" + std::to_string(i) + "]";
    const json& c = characters[i];
    r.only(c, where, {"position", "heading", "control", "action"});
    ScenarioCharacter ch;
    if (!c.contains("position")) r.fail(where + ".position", "is missing");
    ch.position = r.point(c["position"], where + ".position");
    if (c.contains("heading")) ch.heading = r.number(c["heading"], where + ".heading") * kDegrees;
    if (!c.contains("control")) r.fail(where + ".control", "is missing (\"user\" or \"opponent\")");
    const std::string control = r.text(c["control"], where + ".control");
    if (control == "user") ch.control = Control::User;
    else if (control == "opponent") ch.control = Control::Opponent;
    else r.fail(where + ".control", "must be \"user\" or \"opponent\", not \"" + control + "\"");
    if (c.contains("action")) {
      if (ch.control != Control::Opponent) r.fail(where + ".action", "is only for opponents");
      const std::string a = r.text(c["action"], where + ".action");
      const auto action = parse_target_action(a);
      if (!action || !accepts(ObjectType::Opponent, *action))
        r.fail(where + ".action", "must be \"punch_left\" or \"punch_right\", not \"" + a + "\"");
      ch.action = *action;
    }
    s.characters.push_back(ch);
  }
  int users = 0;
  for (const auto& c : s.characters) users += c.control == Control::User ? 1 : 0;
  if (users != 1) r.fail("characters", "must hold exactly one character with \"control\": \"user\" (found " + std::to_string(users) + ")");

  // Objects.
  if (root.contains("objects")) {
    const json& objects = root["objects"];
    if (!objects.is_array()) r.fail("objects", std::string("must be an array, not ") + objects.type_name());
    for (size_t i = 0; i < objects.size(); ++i) {
      const std::string where = "objects[" + std::to_string(i) + "]";
      const json& o = objects[i];
      r.only(o, where, {"type", "action", "position", "heading", "size"});
      ScenarioObject obj;
      if (!o.contains("type")) r.fail(where + ".type", "is missing (ball, bar, beam, hurdle or opponent)");
      const std::string type = r.text(o["type"], where + ".type");
      const auto t = parse_object_type(type);
      if (!t) r.fail(where + ".type", "\"" + type + "\" is not one of ball, bar, beam, hurdle, opponent");
      obj.type = *t;
      obj.action = default_action(obj.type);
      if (o.contains("action")) {
        const std::string a = r.text(o["action"], where + ".action");
        const auto action = parse_target_action(a);
        if (!action) r.fail(where + ".action", "\"" + a + "\" is not one of kick, crawl, duck, jump, punch_left, punch_right");
        if (!accepts(obj.type, *action)) r.fail(where + ".action", "\"" + a + "\" is not an action for a " + type);
        obj.action = *action;
      }
      if (!o.contains("position")) r.fail(where + ".position", "is missing");
      obj.position = r.point(o["position"], where + ".position");
      if (o.contains("heading")) obj.heading = r.number(o["heading"], where + ".heading") * kDegrees;
      if (obj.type == ObjectType::Opponent) {
        if (o.contains("size")) r.fail(where + ".size", "is not used for an opponent (it is a character)");
      } else {
        if (!o.contains("size")) r.fail(where + ".size", "is missing ([width, height, depth] in metres)");
        const json& size = o["size"];
        if (!size.is_array() || size.size() != 3) r.fail(where + ".size", "must be [width, height, depth]");
        for (int k = 0; k < 3; ++k) {
          obj.size[k] = r.number(size[static_cast<size_t>(k)], where + ".size[" + std::to_string(k) + "]");
          if (!(obj.size[k] > 0.0f)) r.fail(where + ".size[" + std::to_string(k) + "]", "must be positive");
        }
      }
      s.objects.push_back(obj);
    }
  }

  // Goal: one point or a list of waypoints.
  if (!root.contains("goal")) r.fail("goal", "is missing (a point [x, z] or a list of waypoints [[x, z], ...])");
  const json& goal = root["goal"];
  if (goal.is_array() && !goal.empty() && goal[0].is_array()) {
    for (size_t i = 0; i < goal.size(); ++i) s.goal.push_back(r.point(goal[i], "goal[" + std::to_string(i) + "]"));
  } else {
    s.goal.push_back(r.point(goal, "goal"));
  }
  return s;
}

Scenario load_scenario(const std::string& path) { return parse_scenario(read_file(path), path); }

std::string scenario_json(const Scenario& s) {
  auto point = [](glm::vec2 p) { return json::array({p.x, p.y}); };
  json j;
  j["name"] = s.name;
  if (!s.description.empty()) j["description"] = s.description;
  j["auto"] = s.auto_launch;
  j["motions"] = s.motions;
  if (!s.params_file.empty()) j["params"] = s.params_file;
  j["characters"] = json::array();
  for (const ScenarioCharacter& c : s.characters) {
    json cj = {{"position", point(c.position)}, {"heading", c.heading / kDegrees}, {"control", control_name(c.control)}};
    if (c.control == Control::Opponent) cj["action"] = target_action_name(c.action);
    j["characters"].push_back(cj);
  }
  j["objects"] = json::array();
  for (const ScenarioObject& o : s.objects) {
    json oj = {{"type", object_type_name(o.type)}, {"action", target_action_name(o.action)}, {"position", point(o.position)},
               {"heading", o.heading / kDegrees}};
    if (o.type != ObjectType::Opponent) oj["size"] = {o.size.x, o.size.y, o.size.z};
    j["objects"].push_back(oj);
  }
  if (s.goal.size() == 1) {
    j["goal"] = point(s.goal.front());
  } else {
    j["goal"] = json::array();
    for (glm::vec2 g : s.goal) j["goal"].push_back(point(g));
  }
  return j.dump(2) + "\n";
}

}  // namespace prep
