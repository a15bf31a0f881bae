// Motion sets (Sec. 4): loading a manifest of BVH clips onto one reference skeleton.
#include "engine/motion/motion_set.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <glm/trigonometric.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "engine/motion/bvh.h"
#include "engine/motion/held_stand.h"
#include "engine/motion/kinematics.h"
#include "engine/motion/steer.h"
#include "engine/util/error.h"
#include "engine/util/files.h"

namespace prep {
namespace {

constexpr std::array<const char*, kRoleCount> kRoleNames = {"idle",  "walk",  "turn_left", "turn_right",
                                                            "step_left", "step_right", "crawl", "duck",
                                                            "jump",  "punch_left", "punch_right", "kick"};

using nlohmann::json;
namespace fs = std::filesystem;

// The floor rule "auto" (motion_set.h): window length and percentile.
constexpr float kFloorWindowSeconds = 1.0f;
constexpr float kFloorPercentile = 0.10f;

struct FloorRule {
  bool automatic = true;  // estimate from the feet (motion_set.h)
  float height = 0.0f;    // metres, when not automatic
};

struct FieldPath {
  std::string text;
  FieldPath operator/(const std::string& field) const { return {text.empty() ? field : text + "." + field}; }
};

class ManifestReader {
 public:
  explicit ManifestReader(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const FieldPath& field, const std::string& message) const {
    throw InputError(path_, field.text.empty() ? message : field.text + ": " + message);
  }

  json parse(const std::string& text) const {
    try {
      return json::parse(text);
    } catch (const json::parse_error& e) {
      // Turn the byte offset into a line number.
      const size_t at = std::min(static_cast<size_t>(e.byte), text.size());
      const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
      std::string what = e.what();
      const size_t colon = what.find("parse error");
      throw InputError(path_, line, "invalid JSON: " + (colon == std::string::npos ? what : what.substr(colon)));
    } catch (const json::exception& e) {  // a number past a double's range (1e400)
      throw InputError(path_, std::string("invalid JSON: ") + e.what());
    }
  }

  void only_fields(const json& object, const FieldPath& where, std::initializer_list<const char*> allowed) const {
    if (!object.is_object()) fail(where, "must be an object");
    for (const auto& [key, value] : object.items()) {
      (void)value;
      bool known = false;
      for (const char* a : allowed) known = known || key == a;
      if (!known) {
        std::string list;
        for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
        fail(where / key, "unknown field (expected one of: " + list + ")");
      }
    }
  }

  std::string string_field(const json& object, const FieldPath& where, const char* key, bool required,
                           const std::string& fallback = {}) const {
    const auto it = object.find(key);
    if (it == object.end()) {
      if (required) fail(where / key, "missing (a string is required)");
      return fallback;
    }
    if (!it->is_string()) fail(where / key, "must be a string");
    return it->get<std::string>();
  }

  // A file or folder name: a string with no control character (a NUL ends a path where the system reads it,
  // so the name could never be the file meant).
  std::string path_field(const json& object, const FieldPath& where, const char* key) const {
    const std::string path = string_field(object, where, key, true);
    for (const char ch : path)
      if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) fail(where / key, "a file name with a control character in it");
    return path;
  }

  std::optional<int> int_field(const json& object, const FieldPath& where, const char* key) const {
    const auto it = object.find(key);
    if (it == object.end()) return std::nullopt;
    if (!it->is_number_integer()) fail(where / key, "must be an integer frame number");
    const auto v = it->get<std::int64_t>();
    if (v < 0 || v > 100000000) fail(where / key, "frame number out of range: " + std::to_string(v));
    return static_cast<int>(v);
  }

  std::optional<std::array<int, 2>> range_field(const json& object, const FieldPath& where, const char* key) const {
    const auto it = object.find(key);
    if (it == object.end()) return std::nullopt;
    const FieldPath field = where / key;
    if (!it->is_array() || it->size() != 2 || !(*it)[0].is_number_integer() || !(*it)[1].is_number_integer())
      fail(field, "must be [first, last], two integer frame numbers");
    const auto a = (*it)[0].get<std::int64_t>(), b = (*it)[1].get<std::int64_t>();
    if (a < 0 || b > 100000000) fail(field, "frame numbers out of range");
    if (a >= b) fail(field, "first (" + std::to_string(a) + ") must be before last (" + std::to_string(b) + ")");
    return std::array<int, 2>{static_cast<int>(a), static_cast<int>(b)};
  }

  // "floor": "auto" | number; nullopt when absent.
  std::optional<FloorRule> floor_field(const json& object, const FieldPath& where) const {
    const auto it = object.find("floor");
    if (it == object.end()) return std::nullopt;
    if (it->is_string() && it->get<std::string>() == "auto") return FloorRule{true, 0.0f};
    if (it->is_number() && std::isfinite(it->get<double>())) return FloorRule{false, it->get<float>()};
    fail(where / "floor", "must be \"auto\" or a height in metres");
  }

  float unit_scale(const json& root) const {
    const bool has_scale = root.contains("unit_scale"), has_units = root.contains("units");
    if (has_scale && has_units) fail({"units"}, "give either \"units\" or \"unit_scale\", not both");
    if (has_scale) {
      const json& v = root["unit_scale"];
      if (!v.is_number() || !(v.get<double>() > 0) || !std::isfinite(v.get<double>()))
        fail({"unit_scale"}, "must be a positive number (file units -> metres)");
      return v.get<float>();
    }
    if (has_units) {
      if (!root["units"].is_string()) fail({"units"}, "must be a string");
      const std::string u = root["units"].get<std::string>();
      static const std::map<std::string, float> known = {
          {"metres", 1.0f},       {"meters", 1.0f},      {"m", 1.0f},          {"centimetres", 0.01f},
          {"centimeters", 0.01f}, {"cm", 0.01f},         {"millimetres", 0.001f}, {"millimeters", 0.001f},
          {"mm", 0.001f},         {"inches", 0.0254f},   {"in", 0.0254f},      {"cmu", 0.05644f}};
      const auto it = known.find(u);
      if (it == known.end()) fail({"units"}, "unknown unit '" + u + "' (metres, centimetres, millimetres, inches or cmu)");
      return it->second;
    }
    return 0.01f;  // centimetres, the common BVH unit
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

bool same_rest_shape(const Skeleton& a, const Skeleton& b) {
  for (size_t j = 0; j < a.joints.size(); ++j) {
    if (glm::length(a.joints[j].offset - b.joints[j].offset) > 1e-6f) return false;
    if (a.joints[j].has_end_site != b.joints[j].has_end_site) return false;
    if (glm::length(a.joints[j].end_site - b.joints[j].end_site) > 1e-6f) return false;
  }
  return true;
}

// Thigh + shin, averaged over both legs.
float leg_length(const Skeleton& skeleton, const BodyMap& body) {
  float sum = 0.0f;
  for (const LegChain& leg : body.legs)
    sum += glm::length(skeleton.joints[static_cast<size_t>(leg.knee)].offset) +
           glm::length(skeleton.joints[static_cast<size_t>(leg.ankle)].offset);
  return 0.5f * sum;
}

// Per frame, the lowest of the heel and toe-tip heights of both feet.
std::vector<float> lowest_foot_heights(const Clip& clip, const BodyMap& body) {
  std::vector<float> out;
  out.reserve(clip.frames.size());
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  for (const Pose& pose : clip.frames) {
    forward_kinematics(*clip.skeleton, pose, positions, &rotations);
    const FootPoints feet = foot_points(*clip.skeleton, body, positions, rotations);
    out.push_back(std::min({feet.heel[0].y, feet.heel[1].y, feet.toe[0].y, feet.toe[1].y}));
  }
  return out;
}

}  // namespace

// The floor rule "auto" (see motion_set.h): per-frame floor heights.
std::vector<float> estimate_floor_heights(const Clip& clip, const BodyMap& body) {
  const std::vector<float> lowest = lowest_foot_heights(clip, body);
  const int frames = static_cast<int>(lowest.size());
  const int window = std::max(1, static_cast<int>(std::lround(kFloorWindowSeconds * clip.fps)));
  // Window boundaries; a last window shorter than half a window joins the one before it.
  std::vector<int> starts;
  for (int s = 0; s < frames; s += window) starts.push_back(s);
  if (starts.size() > 1 && frames - starts.back() < window / 2) starts.pop_back();
  std::vector<float> centres, values;
  std::vector<float> scratch;
  for (size_t w = 0; w < starts.size(); ++w) {
    const int first = starts[w];
    const int last = w + 1 < starts.size() ? starts[w + 1] - 1 : frames - 1;
    scratch.assign(lowest.begin() + first, lowest.begin() + last + 1);
    const size_t at = static_cast<size_t>(kFloorPercentile * static_cast<float>(scratch.size() - 1));
    std::nth_element(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(at), scratch.end());
    centres.push_back(0.5f * static_cast<float>(first + last));
    values.push_back(scratch[at]);
  }
  std::vector<float> floor(static_cast<size_t>(frames));
  if (centres.size() == 1) {
    std::fill(floor.begin(), floor.end(), values.front());
    return floor;
  }
  // Piecewise linear through the window values, the first and last segments extended to the clip's ends
  // (a drifting floor keeps drifting there).
  for (int f = 0; f < frames; ++f) {
    const float x = static_cast<float>(f);
    size_t k = 0;
    while (k + 2 < centres.size() && centres[k + 1] < x) ++k;
    const float t = (x - centres[k]) / (centres[k + 1] - centres[k]);
    floor[static_cast<size_t>(f)] = values[k] + (values[k + 1] - values[k]) * t;
  }
  return floor;
}

namespace {

fs::path resolve_folder(const ManifestReader& reader, const std::string& folder, const std::string& first_file) {
  const fs::path given(folder);
  if (given.is_absolute()) return given;
  // Relative to the repository root (the manifests in assets/ name ../shared/...), else to the manifest's
  // own folder (a manifest written beside its clips).
  const fs::path candidates[] = {fs::path(source_dir()) / given, fs::path(reader.path()).parent_path() / given};
  for (const fs::path& c : candidates)
    if (fs::is_regular_file(c / first_file)) return c.lexically_normal();
  reader.fail({"folder"}, "'" + folder + "' holds no '" + first_file + "' (looked in " + candidates[0].string() + " and " +
                              candidates[1].string() + ")");
}

}  // namespace

const char* role_name(Role role) {
  const int i = static_cast<int>(role);
  return i >= 0 && i < kRoleCount ? kRoleNames[static_cast<size_t>(i)] : "unknown";
}

std::optional<Role> parse_role(std::string_view name) {
  for (int i = 0; i < kRoleCount; ++i)
    if (name == kRoleNames[static_cast<size_t>(i)]) return static_cast<Role>(i);
  return std::nullopt;
}

bool is_locomotion(Role role) {
  switch (role) {
    case Role::Idle: case Role::Walk: case Role::TurnLeft: case Role::TurnRight: case Role::StepLeft: case Role::StepRight:
      return true;
    default:
      return false;
  }
}

int MotionSet::find(std::string_view clip_name) const {
  for (size_t i = 0; i < clips.size(); ++i)
    if (clips[i].clip.name == clip_name) return static_cast<int>(i);
  return -1;
}

int find_cyclic_clip(const MotionSet& set, Role role) {
  for (size_t i = 0; i < set.clips.size(); ++i) {
    if (set.clips[i].role == role && set.clips[i].cyclic) return static_cast<int>(i);
  }
  return -1;
}

void finalize_motion_set(MotionSet& set, const Params& params) {
  if (!set.skeleton) throw std::invalid_argument("motion set '" + set.name + "' has no skeleton");
  set.body = BodyMap::detect(*set.skeleton);
  set.mass = MassModel::build(*set.skeleton, set.body);
  // Characters stop on an idle clip: a set without one gets a stand held from its walk (held_stand.h).
  const int walk = find_cyclic_clip(set, Role::Walk);
  if (find_cyclic_clip(set, Role::Idle) < 0 && walk >= 0)
    set.clips.push_back(held_stand_from_walk(set.clips[static_cast<size_t>(walk)], set.body));
  for (MotionClip& c : set.clips) c.contacts = detect_contacts(c.clip, set.body, params.contacts);
}

MotionSet load_motion_set(const std::string& manifest_path, const Params& params) {
  return parse_motion_set(read_file(manifest_path), manifest_path, params);
}

MotionSet parse_motion_set(const std::string& text, const std::string& manifest_path, const Params& params) {
  const ManifestReader reader(manifest_path);
  const json root = reader.parse(text);
  reader.only_fields(root, {}, {"name", "folder", "unit_scale", "units", "skip_first_frame", "reference", "floor",
                                "description", "clips"});
  MotionSet set;
  set.manifest_path = manifest_path;
  set.name = reader.string_field(root, {}, "name", false, fs::path(manifest_path).stem().string());
  reader.string_field(root, {}, "description", false);
  const std::string folder_name = reader.path_field(root, {}, "folder");
  const float unit_scale = reader.unit_scale(root);
  bool skip_default = false;
  if (root.contains("skip_first_frame")) {
    if (!root["skip_first_frame"].is_boolean()) reader.fail({"skip_first_frame"}, "must be true or false");
    skip_default = root["skip_first_frame"].get<bool>();
  }
  const FloorRule floor_default = reader.floor_field(root, {}).value_or(FloorRule{});

  if (!root.contains("clips")) reader.fail({"clips"}, "missing (an array of clips is required)");
  const json& clips = root["clips"];
  if (!clips.is_array() || clips.empty()) reader.fail({"clips"}, "must be a non-empty array");

  // First pass: the fields of every clip, checked before any BVH is read.
  struct Entry {
    FieldPath where;
    std::string name, file;
    Role role;
    std::optional<std::array<int, 2>> frames, loop;
    std::optional<int> t_t;
    std::optional<float> steer_deg_per_s;
    FloorRule floor;
    bool skip = false;
  };
  std::vector<Entry> entries;
  std::set<std::string> names;
  for (size_t i = 0; i < clips.size(); ++i) {
    const json& c = clips[i];
    Entry e;
    e.where = {"clips[" + std::to_string(i) + "]"};
    reader.only_fields(c, e.where, {"name", "file", "role", "frames", "loop", "t_t", "steer_deg_per_s", "floor", "skip_first_frame", "notes"});
    e.file = reader.path_field(c, e.where, "file");
    e.name = reader.string_field(c, e.where, "name", false, fs::path(e.file).stem().string());
    e.where = {e.where.text + " (" + e.name + ")"};
    reader.string_field(c, e.where, "notes", false);
    if (!names.insert(e.name).second) reader.fail(e.where / "name", "the name '" + e.name + "' repeats");
    const std::string role = reader.string_field(c, e.where, "role", true);
    const auto parsed = parse_role(role);
    if (!parsed) {
      std::string list;
      for (const char* r : kRoleNames) list += std::string(list.empty() ? "" : ", ") + r;
      reader.fail(e.where / "role", "unknown role '" + role + "' (expected one of: " + list + ")");
    }
    e.role = *parsed;
    e.frames = reader.range_field(c, e.where, "frames");
    e.loop = reader.range_field(c, e.where, "loop");
    e.t_t = reader.int_field(c, e.where, "t_t");
    if (c.contains("steer_deg_per_s")) {
      const json& v = c["steer_deg_per_s"];
      if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() == 0.0 || std::abs(v.get<double>()) > 180.0)
        reader.fail(e.where / "steer_deg_per_s", "must be a rate of turn in degrees per second, non-zero, at most 180 either way (positive: to the left)");
      e.steer_deg_per_s = v.get<float>();
    }
    e.floor = reader.floor_field(c, e.where).value_or(floor_default);
    e.skip = skip_default;
    if (c.contains("skip_first_frame")) {
      if (!c["skip_first_frame"].is_boolean()) reader.fail(e.where / "skip_first_frame", "must be true or false");
      e.skip = c["skip_first_frame"].get<bool>();
    }
    if (is_locomotion(e.role)) {
      if (e.t_t) reader.fail(e.where / "t_t", "only target motions (crawl, duck, jump, punches, kick) have a T_t; this clip is '" + role + "'");
      if (e.steer_deg_per_s && ((e.role == Role::TurnLeft && *e.steer_deg_per_s < 0.0f) ||
                                (e.role == Role::TurnRight && *e.steer_deg_per_s > 0.0f)))
        reader.fail(e.where / "steer_deg_per_s", "turns the " + std::string(*e.steer_deg_per_s > 0.0f ? "left" : "right") +
                                                     " way (positive is to the left), but the clip is '" + role + "'");
    } else {
      if (e.steer_deg_per_s) reader.fail(e.where / "steer_deg_per_s", "only locomotion clips are steered; this clip is '" + role + "'");
      if (!e.t_t) reader.fail(e.where / "t_t", "missing: a target motion ('" + role + "') needs the first frame of its target movement");
      if (e.loop) reader.fail(e.where / "loop", "only locomotion clips loop; this clip is '" + role + "'");
    }
    entries.push_back(std::move(e));
  }

  const fs::path folder = resolve_folder(reader, folder_name, entries.front().file);
  std::string reference_file = entries.front().file;
  if (root.contains("reference")) {
    reference_file = reader.path_field(root, {}, "reference");
    const bool listed = std::any_of(entries.begin(), entries.end(), [&](const Entry& e) { return e.file == reference_file; });
    if (!listed) reader.fail({"reference"}, "'" + reference_file + "' is not the file of any clip");
  }

  // Each file is read once (a file may hold two clips, e.g. a jab and a cross).
  std::map<std::string, Clip> files;
  BvhReadOptions options;
  options.unit_scale = unit_scale;
  options.warnings = &set.warnings;
  auto load = [&](const std::string& file) -> const Clip& {
    auto it = files.find(file);
    if (it == files.end()) it = files.emplace(file, read_bvh((folder / file).string(), options)).first;
    return it->second;
  };

  const Clip& reference = load(reference_file);
  set.skeleton = reference.skeleton;
  try {
    set.body = BodyMap::detect(*set.skeleton);
  } catch (const std::invalid_argument& e) {
    reader.fail({"reference"}, std::string("the skeleton of '") + reference_file + "' is not a recognisable humanoid: " + e.what());
  }
  const Skeleton& ref = *set.skeleton;
  const float ref_leg = leg_length(ref, set.body);

  for (const Entry& e : entries) {
    const Clip& source = load(e.file);
    const int count = source.frame_count();
    const int first_allowed = e.skip ? 1 : 0;
    if (count <= first_allowed + 1)
      reader.fail(e.where / "file", "'" + e.file + "' has " + std::to_string(count) + " frames: too few to use");
    const std::array<int, 2> range = e.frames.value_or(std::array<int, 2>{first_allowed, count - 1});
    if (range[0] < first_allowed)
      reader.fail(e.where / "frames", "starts at frame " + std::to_string(range[0]) + ", but frame 0 is the reference pose (skip_first_frame)");
    if (range[1] >= count)
      reader.fail(e.where / "frames", "ends at frame " + std::to_string(range[1]) + ", but '" + e.file + "' has frames 0-" + std::to_string(count - 1));
    auto inside = [&](int f) { return f >= range[0] && f <= range[1]; };

    MotionClip mc;
    mc.role = e.role;
    mc.source_file = (folder / e.file).string();
    Clip& clip = mc.clip;
    clip.name = e.name;
    clip.fps = source.fps;
    clip.skeleton = set.skeleton;

    // Joint correspondence by name; other performers' clips are retargeted onto the reference skeleton.
    const Skeleton& src = *source.skeleton;
    std::vector<int> from(static_cast<size_t>(ref.size()));
    if (src.size() != ref.size())
      reader.fail(e.where / "file", "'" + e.file + "' has " + std::to_string(src.size()) + " joints, the reference '" +
                                        reference_file + "' has " + std::to_string(ref.size()));
    for (int j = 0; j < ref.size(); ++j) {
      const Joint& rj = ref.joints[static_cast<size_t>(j)];
      const int s = src.find(rj.name);
      if (s < 0) reader.fail(e.where / "file", "'" + e.file + "' has no joint '" + rj.name + "' (the reference skeleton has)");
      const int sp = src.joints[static_cast<size_t>(s)].parent;
      const std::string src_parent = sp < 0 ? "" : src.joints[static_cast<size_t>(sp)].name;
      const std::string ref_parent = rj.parent < 0 ? "" : ref.joints[static_cast<size_t>(rj.parent)].name;
      if (src_parent != ref_parent)
        reader.fail(e.where / "file", "joint '" + rj.name + "' hangs from '" + src_parent + "' in '" + e.file + "' but from '" +
                                          ref_parent + "' in the reference");
      from[static_cast<size_t>(j)] = s;
    }
    float root_scale = 1.0f;
    if (!same_rest_shape(src, ref)) {
      try {
        const float leg = leg_length(src, BodyMap::detect(src));
        if (!(leg > 0.0f)) throw std::invalid_argument("zero leg length");
        root_scale = ref_leg / leg;
      } catch (const std::invalid_argument& err) {
        reader.fail(e.where / "file", std::string("cannot measure the legs of '") + e.file + "': " + err.what());
      }
    }
    clip.frames.reserve(static_cast<size_t>(range[1] - range[0] + 1));
    for (int f = range[0]; f <= range[1]; ++f) {
      const Pose& sp = source.frames[static_cast<size_t>(f)];
      Pose p(ref.size());
      p.root_position = sp.root_position * root_scale;
      for (int j = 0; j < ref.size(); ++j) p.rotations[static_cast<size_t>(j)] = sp.rotations[static_cast<size_t>(from[static_cast<size_t>(j)])];
      clip.frames.push_back(std::move(p));
    }

    // Floor: y = 0 under the feet.
    if (!e.floor.automatic) {
      for (Pose& p : clip.frames) p.root_position.y -= e.floor.height;
    } else {
      const std::vector<float> floor = estimate_floor_heights(clip, set.body);
      for (size_t f = 0; f < clip.frames.size(); ++f) clip.frames[f].root_position.y -= floor[f];
    }
    if (e.steer_deg_per_s) {
      mc.steer_rad_per_s = glm::radians(*e.steer_deg_per_s);
      steer_clip(clip, set.body, detect_contacts(clip, set.body, params.contacts), mc.steer_rad_per_s);
    }

    if (e.loop) {
      if (!inside((*e.loop)[0]) || !inside((*e.loop)[1]))
        reader.fail(e.where / "loop", "[" + std::to_string((*e.loop)[0]) + ", " + std::to_string((*e.loop)[1]) +
                                          "] is outside the clip's frames [" + std::to_string(range[0]) + ", " + std::to_string(range[1]) + "]");
      mc.cyclic = true;
      mc.loop_first = (*e.loop)[0] - range[0];
      mc.loop_last = (*e.loop)[1] - range[0];
    }
    if (e.t_t) {
      if (!inside(*e.t_t))
        reader.fail(e.where / "t_t", std::to_string(*e.t_t) + " is outside the clip's frames [" + std::to_string(range[0]) + ", " +
                                         std::to_string(range[1]) + "]");
      mc.target_frame = *e.t_t - range[0];
    }
    set.clips.push_back(std::move(mc));
  }

  try {
    finalize_motion_set(set, params);
  } catch (const std::invalid_argument& e) {
    throw InputError(manifest_path, e.what());
  }
  return set;
}

}  // namespace prep
