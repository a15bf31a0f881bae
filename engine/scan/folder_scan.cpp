// The folder scan: reading the takes, finding units and the reference skeleton, and the clips each take
// holds (scan_report.cpp writes what it found).
#include "engine/scan/folder_scan.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include <glm/gtc/constants.hpp>
#include <glm/geometric.hpp>

#include "engine/control/action_effects.h"
#include "engine/motion/bvh.h"
#include "engine/motion/kinematics.h"
#include "engine/scan/motion_signals.h"
#include "engine/scan/role_guess.h"
#include "engine/scan/target_timing.h"
#include "engine/util/error.h"

namespace prep {
namespace {

namespace fs = std::filesystem;

// A standing figure is 1.4-2.1 m tall; the unit that makes the reference skeleton so (closest to 1.75 m).
struct Unit {
  const char* name;
  float scale;
};
constexpr Unit kUnits[] = {{"metres", 1.0f}, {"centimetres", 0.01f}, {"millimetres", 0.001f}, {"inches", 0.0254f}, {"cmu", 0.05644f}};
constexpr float kShortest = 1.4f, kTallest = 2.1f, kTypical = 1.75f;

constexpr float kEverydayPace = 1.3f;         // m/s
constexpr float kSteerDegPerS = 40.0f;        // a steered turn: a circle of about 2 m at a walk
constexpr float kTurnLoopRate = 15.0f;        // deg/s a recorded turn's loop must turn to be a turn
constexpr float kUsableLoop = 0.3f;           // a turn's loop confidence below this: not loopable
constexpr float kReferenceFrameDeg = 3.0f;    // frame 0 this close to the rest pose: a reference pose
constexpr float kBlendSpeedFloor = 1.5f;      // m/s: the blend out of a reference pose moves faster

struct Take {
  ScannedFile* file = nullptr;
  Clip clip;  // in metres, floor at y = 0
  BodyMap body;
  std::unique_ptr<MotionSignals> signals;
  std::unique_ptr<HeadingFramePoses> poses;
};

std::string signature(const Skeleton& s) {
  std::string out;
  for (const Joint& j : s.joints) out += j.name + "<" + std::to_string(j.parent) + ";";
  return out;
}

// The rest pose's height from the lowest joint or end site to the highest.
float rest_height(const Skeleton& skeleton) {
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  forward_kinematics(skeleton, Pose(skeleton.size()), positions, &rotations);
  float low = positions[0].y, high = positions[0].y;
  for (int j = 0; j < skeleton.size(); ++j) {
    glm::vec3 p = positions[static_cast<size_t>(j)];
    low = std::min(low, p.y);
    high = std::max(high, p.y);
    if (skeleton.joints[static_cast<size_t>(j)].has_end_site) {
      p = end_site_position(skeleton, j, positions, rotations);
      low = std::min(low, p.y);
      high = std::max(high, p.y);
    }
  }
  return high - low;
}

void scale_clip(Clip& clip, float scale) {
  auto skeleton = std::make_shared<Skeleton>(*clip.skeleton);
  for (Joint& j : skeleton->joints) {
    j.offset *= scale;
    j.end_site *= scale;
  }
  clip.skeleton = skeleton;
  for (Pose& p : clip.frames) p.root_position *= scale;
}

float mean_rotation_deg(const Pose& pose) {
  float sum = 0.0f;
  for (const glm::quat& q : pose.rotations) sum += 2.0f * std::acos(std::min(1.0f, std::abs(q.w)));
  return sum / static_cast<float>(std::max<size_t>(1, pose.rotations.size())) * 180.0f / glm::pi<float>();
}

// A converter's reference pose: frame 0 near the rest pose (the joints turned kReferenceFrameDeg on
// average at most), where the take itself is far from it (three times as far, by the median frame).
bool starts_with_reference_pose(const Clip& clip) {
  std::vector<float> means;
  for (const Pose& p : clip.frames) means.push_back(mean_rotation_deg(p));
  return means[0] <= kReferenceFrameDeg && 3.0f * means[0] <= median_of(means, 1, static_cast<int>(means.size()) - 1);
}

// After a reference pose the capture blends in over a few frames, far faster than any motion in it.
int first_usable_frame(const Take& t) {
  const int n = t.clip.frame_count();
  if (n < 8 || !starts_with_reference_pose(t.clip)) return 0;
  std::vector<float> change(static_cast<size_t>(n - 1));
  for (int f = 0; f + 1 < n; ++f) change[static_cast<size_t>(f)] = t.poses->distance_cm(f, f + 1) * t.clip.fps / 100.0f;
  const float usual = median_of(change, 1, n - 2);
  const float limit = std::max(4.0f * usual, kBlendSpeedFloor);
  int first = 1;
  while (first < n / 4 && change[static_cast<size_t>(first)] > limit) ++first;
  return first;
}

// "idle_10_01_f0-440" -> "idle_10_01": a frame-range suffix names a cut, not the take.
std::string without_cut(const std::string& stem) {
  const size_t cut = stem.rfind("_f");
  if (cut == std::string::npos || cut + 2 >= stem.size() || !std::isdigit(static_cast<unsigned char>(stem[cut + 2]))) return stem;
  return stem.substr(0, cut);
}

// "walk_02_01" -> "02_01": from the first digit on ("" when there is none).
std::string take_id(const std::string& stem) {
  const std::string take = without_cut(stem);
  const size_t digit = take.find_first_of("0123456789");
  return digit == std::string::npos ? std::string() : take.substr(digit);
}

// A clip keeps its file's name when the name says its role and the file holds only it; otherwise it is
// called by its role and the take's number ("punch_left_14_01" out of "punch_right_14_01.bvh").
std::string clip_name(Role role, const std::string& stem, bool several) {
  if (!several && role_from_name(stem) == role) return without_cut(stem);
  const std::string id = take_id(stem);
  return std::string(role_name(role)) + "_" + (id.empty() ? without_cut(stem) : id);
}

float loop_speed_of(const MotionSignals& s, int first, int last) {
  const glm::vec3 d = s.root[static_cast<size_t>(last)] - s.root[static_cast<size_t>(first)];
  return glm::length(glm::vec2(d.x, d.z)) / std::max(1e-3f, s.seconds(last - first));
}

float loop_turn_deg_per_s(const MotionSignals& s, int first, int last) {
  return (s.heading[static_cast<size_t>(last)] - s.heading[static_cast<size_t>(first)]) * 180.0f / glm::pi<float>() /
         std::max(1e-3f, s.seconds(last - first));
}

void add_locomotion(const Take& t, const RoleGuess& guess, const std::string& stem, std::vector<ScannedClip>& out) {
  const MotionSignals& s = *t.signals;
  ScannedClip c;
  c.file = t.file->file;
  c.role = guess.role;
  c.first = t.file->first_usable;
  c.last = s.frames - 1;
  c.name = clip_name(guess.role, stem, false);
  c.role_confidence = guess.confidence;
  c.evidence = guess.evidence;
  const int cycle = gait_cycle_frames(s, c.first, c.last);
  const int shortest = cycle > 0 ? static_cast<int>(0.75f * static_cast<float>(cycle)) : s.frames_in(0.6f);
  const int longest = cycle > 0 ? static_cast<int>(2.25f * static_cast<float>(cycle)) : s.frames_in(3.0f);
  LoopRange loop = find_loop(*t.poses, s, c.first, c.last, shortest, longest);
  const bool turn = guess.role == Role::TurnLeft || guess.role == Role::TurnRight;
  if (loop.found() && turn) {
    // A recorded turn loops only where it keeps turning, and joins well.
    const float rate = loop_turn_deg_per_s(s, loop.first, loop.last);
    const bool turning = (guess.role == Role::TurnLeft ? rate : -rate) >= kTurnLoopRate;
    if (!turning || loop.confidence() < kUsableLoop) {
      c.evidence += turning ? "; its best loop joins poorly, so it plays as recorded" : "; it does not keep turning, so it plays as recorded";
      loop = LoopRange{};
    }
  }
  if (loop.found()) {
    c.loop = loop;
    c.timing_confidence = loop.confidence();
    c.speed = loop_speed_of(s, loop.first, loop.last);
    char text[160];
    std::snprintf(text, sizeof text, "; loop %d-%d joins at %.1f cm (an arbitrary loop: %.1f cm)%s", loop.first, loop.last,
                  loop.error_cm, loop.typical_cm, cycle > 0 ? "" : ", no footsteps: searched 0.6-3 s");
    c.evidence += text;
  } else {
    c.speed = loop_speed_of(s, c.first, c.last);
  }
  out.push_back(std::move(c));
}

void add_targets(const Take& t, const RoleGuess& guess, const std::string& stem, std::vector<ScannedClip>& out) {
  const MotionSignals& s = *t.signals;
  const int first = t.file->first_usable, last = s.frames - 1;
  auto base = [&](Role role, bool several) {
    ScannedClip c;
    c.file = t.file->file;
    c.role = role;
    c.first = first;
    c.last = last;
    c.name = clip_name(role, stem, several);
    c.role_confidence = guess.confidence;
    c.evidence = guess.evidence;
    return c;
  };
  if (guess.role == Role::PunchLeft || guess.role == Role::PunchRight) {
    // One clip per strike, each ending where the next strike starts.
    const std::vector<Strike> strikes = hand_strikes(s, first, last);
    std::vector<ScannedClip> punches;
    for (const Strike& k : strikes) {
      ScannedClip c = base(k.limb == kLeft ? Role::PunchLeft : Role::PunchRight, strikes.size() > 1);
      const auto timing = find_target_timing(c.role, s, first, last, &k);
      c.target_frame = timing->target_frame;
      c.timing_confidence = 0.8f;
      c.evidence += "; T_t: " + timing->rule;
      punches.push_back(std::move(c));
    }
    for (size_t i = 0; i + 1 < punches.size(); ++i)
      punches[i].last = std::max(*punches[i].target_frame + 1, *punches[i + 1].target_frame - 1);
    if (!punches.empty()) {
      out.insert(out.end(), punches.begin(), punches.end());
      return;
    }
  }
  ScannedClip c = base(guess.role, false);
  if (const auto timing = find_target_timing(guess.role, s, first, last)) {
    c.target_frame = timing->target_frame;
    c.timing_confidence = 0.8f;
    c.evidence += "; T_t: " + timing->rule;
  } else {
    // Nothing in the motion to time it by: the middle of the take, for the user to correct.
    c.target_frame = (first + last) / 2;
    c.timing_confidence = 0.2f;
    c.evidence += std::string("; T_t: no ") + (guess.role == Role::Jump ? "flight" : "descent") + " found, the middle of the take";
  }
  out.push_back(std::move(c));
}

// The controller's core motions and the steered turns: the best walk first, a turn each way (steered from
// the best walk when the data has no loopable one), the slow walk, then everything else as found.
void choose_core(FolderScan& scan) {
  std::vector<ScannedClip>& clips = scan.clips;
  // The best walk: a loop that joins well at an everyday pace (half a point of confidence per m/s away
  // from 1.3 m/s).
  auto walk_score = [](const ScannedClip& c) { return c.timing_confidence - 0.5f * std::abs(c.speed - kEverydayPace); };
  auto best_walk = clips.end();
  for (auto it = clips.begin(); it != clips.end(); ++it) {
    if (it->role != Role::Walk || !it->loop || it->speed < 0.5f || it->speed > 2.2f) continue;
    if (best_walk == clips.end() || walk_score(*it) > walk_score(*best_walk)) best_walk = it;
  }
  if (best_walk == clips.end())
    for (auto it = clips.begin(); it != clips.end(); ++it)
      if (it->role == Role::Walk && it->loop && (best_walk == clips.end() || it->timing_confidence > best_walk->timing_confidence))
        best_walk = it;
  std::vector<ScannedClip> ordered;
  if (best_walk == clips.end()) {
    scan.lacks.push_back("no loopable walk: the controller has nothing to walk with, so no scenario can run on this set");
    return;
  }
  ScannedClip walk = *best_walk;
  clips.erase(best_walk);
  walk.core = true;
  walk.core_as = "walk";
  ordered.push_back(walk);
  scan.reference = walk.file;

  for (Role turn : {Role::TurnLeft, Role::TurnRight}) {
    auto recorded = std::find_if(clips.begin(), clips.end(), [&](const ScannedClip& c) { return c.role == turn && c.loop; });
    if (recorded != clips.end()) {
      recorded->core = true;
      recorded->core_as = turn == Role::TurnLeft ? "turn left" : "turn right";
      ordered.push_back(*recorded);
      clips.erase(recorded);
      continue;
    }
    ScannedClip steered = walk;
    steered.role = turn;
    steered.name = clip_name(turn, walk.name, true);
    steered.steer_deg_per_s = turn == Role::TurnLeft ? kSteerDegPerS : -kSteerDegPerS;
    steered.core_as = turn == Role::TurnLeft ? "turn left" : "turn right";
    steered.role_confidence = 1.0f;
    steered.evidence = std::string("steered from ") + walk.name + " at " + (turn == Role::TurnLeft ? "+" : "-") +
                       std::to_string(static_cast<int>(kSteerDegPerS)) + " deg/s: the data has no loopable " + role_name(turn);
    ordered.push_back(steered);
    scan.lacks.push_back(std::string("no loopable ") + role_name(turn) + ": steered from " + walk.name + " at " +
                         std::to_string(static_cast<int>(kSteerDegPerS)) + " deg/s");
  }

  auto slow = clips.end();
  for (auto it = clips.begin(); it != clips.end(); ++it)
    if (it->role == Role::Walk && it->loop && it->speed <= kSlowWalkRatio * walk.speed && (slow == clips.end() || it->speed < slow->speed))
      slow = it;
  if (slow != clips.end()) {
    slow->core = true;
    slow->core_as = "slow walk";
    ordered.push_back(*slow);
    clips.erase(slow);
  }
  std::stable_partition(clips.begin(), clips.end(), [](const ScannedClip& c) { return is_locomotion(c.role); });
  ordered.insert(ordered.end(), clips.begin(), clips.end());
  clips = std::move(ordered);
}

void list_lacks(FolderScan& scan) {
  auto has = [&](Role r) { return std::any_of(scan.clips.begin(), scan.clips.end(), [&](const ScannedClip& c) { return c.role == r; }); };
  if (!has(Role::Idle)) scan.lacks.push_back("no idle: characters stand in a held posture made from the walk (upright, its arms as they hang)");
  const struct {
    Role role;
    const char* consequence;
  } targets[] = {{Role::Crawl, "a bar cannot be crawled under"},
                 {Role::Duck, "a beam cannot be ducked under"},
                 {Role::Jump, "a hurdle cannot be jumped"},
                 {Role::Kick, "a ball cannot be kicked"},
                 {Role::PunchLeft, "no left punch in a fight"},
                 {Role::PunchRight, "no right punch in a fight"}};
  for (const auto& t : targets)
    if (!has(t.role)) scan.lacks.push_back(std::string("no ") + role_name(t.role) + ": " + t.consequence + " with this set");
}

}  // namespace

FolderScan scan_motion_folder(const std::string& folder, const Params& params) {
  FolderScan scan;
  scan.folder = folder;
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw InputError(folder, "is not a folder");
  scan.name = fs::path(folder).lexically_normal().filename().string();
  if (scan.name.empty() || scan.name == ".") scan.name = fs::path(folder).lexically_normal().parent_path().filename().string();
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (entry.is_regular_file() && ext == ".bvh") names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  if (names.empty()) throw InputError(folder, "holds no BVH file (*.bvh)");

  // Read every take in file units; a file that does not parse is left out with its message.
  std::vector<Take> takes;
  scan.files.reserve(names.size());
  std::map<std::string, int> skeleton_count;
  for (const std::string& name : names) {
    scan.files.push_back({});
    ScannedFile& f = scan.files.back();
    f.file = name;
    BvhReadOptions options;
    options.unit_scale = 1.0f;
    std::vector<std::string> warnings;
    options.warnings = &warnings;
    try {
      Take t;
      t.clip = read_bvh((fs::path(folder) / name).string(), options);
      f.frames = t.clip.frame_count();
      f.fps = t.clip.fps;
      f.joints = t.clip.skeleton->size();
      if (!warnings.empty()) f.note = warnings.front();
      takes.push_back(std::move(t));
      ++skeleton_count[signature(*takes.back().clip.skeleton)];
    } catch (const InputError& e) {
      f.note = std::string("left out: ") + e.what();
    }
  }
  if (takes.empty()) throw InputError(folder, "no BVH file in it could be read (" + scan.files.front().note + ")");
  for (size_t i = 0, k = 0; i < scan.files.size(); ++i)
    if (scan.files[i].note.rfind("left out", 0) != 0) takes[k++].file = &scan.files[i];

  // The reference skeleton: the most common joint hierarchy; takes on another are left out.
  const std::string common = std::max_element(skeleton_count.begin(), skeleton_count.end(), [](const auto& a, const auto& b) {
                               return a.second < b.second;
                             })->first;
  const Take* first_common = nullptr;
  for (const Take& t : takes)
    if (first_common == nullptr && signature(*t.clip.skeleton) == common) first_common = &t;
  for (Take& t : takes)
    if (signature(*t.clip.skeleton) != common)
      t.file->note = "left out: another skeleton (" + std::to_string(t.file->joints) + " joints) than most files' (" +
                     std::to_string(first_common->file->joints) + ")";

  // Units from the figure's height: the median over the takes (performers differ, and a child or a
  // crouched rest pose may be among them).
  std::vector<float> heights;
  for (const Take& t : takes)
    if (signature(*t.clip.skeleton) == common) heights.push_back(rest_height(*t.clip.skeleton));
  const float height = median_of(heights, 0, static_cast<int>(heights.size()) - 1);
  const Unit* unit = nullptr;
  for (const Unit& u : kUnits) {
    const float h = height * u.scale;
    if (h < kShortest || h > kTallest) continue;
    if (unit == nullptr || std::abs(h - kTypical) < std::abs(height * unit->scale - kTypical)) unit = &u;
  }
  if (unit == nullptr)
    throw InputError((fs::path(folder) / first_common->file->file).string(),
                     "the skeleton is " + std::to_string(height) +
                         " file units tall: no unit (metres, centimetres, millimetres, inches, CMU units) makes that a standing figure of 1.4-2.1 m");
  scan.units = unit->name;
  scan.unit_scale = unit->scale;
  scan.figure_height = height * unit->scale;

  int reference_frames = 0;
  for (Take& t : takes) {
    if (signature(*t.clip.skeleton) != common) continue;
    try {
      t.body = BodyMap::detect(*t.clip.skeleton);
    } catch (const std::invalid_argument& e) {
      throw InputError((fs::path(folder) / t.file->file).string(), std::string("not a recognisable humanoid: ") + e.what());
    }
    scale_clip(t.clip, unit->scale);
    const std::vector<float> floor = estimate_floor_heights(t.clip, t.body);
    for (size_t f = 0; f < t.clip.frames.size(); ++f) t.clip.frames[f].root_position.y -= floor[f];
    t.signals = std::make_unique<MotionSignals>(measure_motion(t.clip, t.body, params.contacts));
    t.poses = std::make_unique<HeadingFramePoses>(t.clip, *t.signals);
    t.file->first_usable = first_usable_frame(t);
    if (t.file->first_usable > 0) ++reference_frames;
    if (t.clip.frame_count() - t.file->first_usable < std::max(4, t.signals->frames_in(0.3f))) {
      t.file->note = "left out: too short to use";
      continue;
    }
    t.file->used = true;

    const std::string stem = fs::path(t.file->file).stem().string();
    const RoleGuess guess = guess_role(stem, *t.signals, t.file->first_usable, t.clip.frame_count() - 1);
    if (is_locomotion(guess.role))
      add_locomotion(t, guess, stem, scan.clips);
    else
      add_targets(t, guess, stem, scan.clips);
  }
  scan.skip_first_frame = reference_frames * 2 > static_cast<int>(takes.size());

  // Names stay unique: a repeat gets its file's position.
  std::map<std::string, int> seen;
  for (ScannedClip& c : scan.clips)
    if (seen[c.name]++ > 0) c.name += "_" + std::to_string(seen[c.name]);

  choose_core(scan);
  list_lacks(scan);
  if (scan.reference.empty()) scan.reference = first_common->file->file;
  return scan;
}

}  // namespace prep
