#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include <glm/gtc/constants.hpp>
#include <glm/trigonometric.hpp>

#include "engine/motion/bvh.h"
#include "engine/motion/kinematics.h"
#include "engine/motion/motion_set.h"
#include "engine/util/error.h"
#include "tests/support/paths.h"

using namespace prep;
namespace fs = std::filesystem;

namespace {

const MotionSet& manifest_set(const std::string& name) {
  static std::map<std::string, MotionSet> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, load_motion_set(test::repo() + "/assets/manifests/" + name + ".json", Params{})).first;
  return it->second;
}

std::set<std::string> bvh_files_in(const std::string& folder) {
  std::set<std::string> out;
  for (const auto& f : fs::directory_iterator(folder))
    if (f.path().extension() == ".bvh") out.insert(f.path().filename().string());
  return out;
}

// Joint positions in the root's heading frame (yaw and horizontal position removed): what a loop join
// must match.
std::vector<glm::vec3> local_positions(const Clip& clip, int frame) {
  std::vector<glm::vec3> p;
  forward_kinematics(*clip.skeleton, clip.frames[static_cast<size_t>(frame)], p);
  const glm::quat unyaw = glm::angleAxis(-heading_of(clip.frames[static_cast<size_t>(frame)].rotations[0]), glm::vec3(0, 1, 0));
  const glm::vec3 origin(p[0].x, 0.0f, p[0].z);
  for (glm::vec3& v : p) v = unyaw * (v - origin);
  return p;
}

double pose_distance(const Clip& clip, int a, int b) {
  const auto pa = local_positions(clip, a), pb = local_positions(clip, b);
  double sum = 0;
  for (size_t j = 0; j < pa.size(); ++j) sum += glm::dot(pa[j] - pb[j], pa[j] - pb[j]);
  return std::sqrt(sum / static_cast<double>(pa.size()));
}

// A scratch manifest for the error tests, in the build's temporary folder.
std::string write_manifest(const std::string& name, const std::string& text) {
  fs::create_directories(test::tmp_dir());
  const std::string path = test::tmp_dir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::string cmu31_manifest(const std::string& clips, const std::string& extra = "") {
  return "{\"name\": \"t\", \"folder\": \"" + test::mocap() + "/cmu31\", \"units\": \"cmu\"" + extra +
         ", \"clips\": [" + clips + "]}";
}

}  // namespace

TEST_CASE("role names round-trip and split into locomotion and target motions") {
  for (int i = 0; i < kRoleCount; ++i) {
    const Role r = static_cast<Role>(i);
    REQUIRE(parse_role(role_name(r)).has_value());
    CHECK(*parse_role(role_name(r)) == r);
  }
  CHECK_FALSE(parse_role("run").has_value());
  CHECK(is_locomotion(Role::TurnRight));
  CHECK_FALSE(is_locomotion(Role::Kick));
}

TEST_CASE("both CMU manifests load and list every clip of their folder with its role") {
  // Roles ../shared/mocap/README.md lists for the two folders.
  const std::map<std::string, std::string> role_by_prefix = {{"idle", "idle"},   {"walk", "walk"},  {"run", "walk"},
                                                             {"turn_left", "turn_left"}, {"crawl", "crawl"},
                                                             {"duck", "duck"},   {"jump", "jump"},  {"punch", "punch_right"},
                                                             {"kick", "kick"}};
  std::set<std::string> roles;
  for (const std::string name : {"daz43", "cmu31"}) {
    CAPTURE(name);
    const MotionSet& set = manifest_set(name);
    CHECK(set.skeleton->size() == (name == "daz43" ? 43 : 31));
    std::set<std::string> listed;
    for (const MotionClip& c : set.clips) {
      CAPTURE(c.clip.name);
      if (!c.derived_from.empty()) {  // cmu31 has no idle: the stand held from its walk (held_stand.h)
        CHECK(c.role == Role::Idle);
        CHECK(set.find(c.derived_from) >= 0);
        continue;
      }
      const std::string file = fs::path(c.source_file).filename().string();
      listed.insert(file);
      roles.insert(role_name(c.role));
      CHECK(c.clip.skeleton == set.skeleton);
      CHECK(c.clip.frame_count() > 10);
      CHECK(c.contacts.size() == c.clip.frames.size());
      // The role matches what the file is (the file names say it), except the deliberate extra entries:
      // a walk steered into a turn (turning the way its role says), the veer's truncated turn, the jab.
      if (c.steer_rad_per_s != 0.0f) {
        CHECK(fs::path(c.source_file).filename().string().rfind("walk", 0) == 0);
        CHECK(c.role == (c.steer_rad_per_s > 0.0f ? Role::TurnLeft : Role::TurnRight));
        CHECK(c.cyclic);
      } else if (c.clip.name != "turn_right_05_01" && c.clip.name != "punch_left_14_01") {
        bool matched = false;
        for (const auto& [prefix, role] : role_by_prefix)
          if (file.rfind(prefix, 0) == 0) {
            CHECK(std::string(role_name(c.role)) == role);
            matched = true;
          }
        CHECK(matched);
      }
      if (is_locomotion(c.role)) {
        CHECK(c.target_frame == -1);
      } else {
        CHECK(c.target_frame >= 0);
        CHECK(c.target_frame < c.clip.frame_count());
        CHECK_FALSE(c.cyclic);
      }
      if (c.cyclic) {
        CHECK(c.loop_first >= 0);
        CHECK(c.loop_last > c.loop_first);
        CHECK(c.loop_last < c.clip.frame_count());
      }
    }
    CHECK(listed == bvh_files_in(test::mocap() + "/" + name));
  }
  for (const char* r : {"idle", "walk", "turn_left", "turn_right", "crawl", "duck", "jump", "punch_left", "punch_right", "kick"})
    CHECK(roles.count(r) == 1);
}

TEST_CASE("manifest frame ranges, T_t and loops count the file's frames") {
  const MotionSet& daz = manifest_set("daz43");
  // jump_forward_13_11: frames [28, 399], t_t 118 (skip_first_frame).
  const MotionClip& jump = daz.clips[static_cast<size_t>(daz.find("jump_forward_13_11"))];
  CHECK(jump.clip.frame_count() == 399 - 28 + 1);
  CHECK(jump.target_frame == 118 - 28);
  BvhReadOptions options;
  options.unit_scale = 0.01f;
  const Clip file = read_bvh(test::mocap() + "/daz43/jump_forward_13_11.bvh", options);
  for (size_t j = 0; j < file.frames[28].rotations.size(); ++j)
    CHECK(std::abs(glm::dot(jump.clip.frames[0].rotations[j], file.frames[28].rotations[j])) == doctest::Approx(1.0f));
  // Horizontal root position untouched (same skeleton, no retargeting); height moved by the floor only.
  CHECK(jump.clip.frames[0].root_position.x == file.frames[28].root_position.x);
  CHECK(jump.clip.frames[0].root_position.z == file.frames[28].root_position.z);
  const MotionClip& walk = daz.clips[static_cast<size_t>(daz.find("walk_02_01"))];
  // The walk uses the file's frames 6-343 (frames 1-5 blend in from the reference pose).
  CHECK(walk.clip.frame_count() == 343 - 6 + 1);
  CHECK(walk.cyclic);
  CHECK(walk.loop_first == 120 - 6);
  CHECK(walk.loop_last == 250 - 6);
  // Two clips from one file: the punch take holds a left jab and a right cross.
  const MotionSet& cmu = manifest_set("cmu31");
  const MotionClip& right = cmu.clips[static_cast<size_t>(cmu.find("punch_right_14_01"))];
  const MotionClip& left = cmu.clips[static_cast<size_t>(cmu.find("punch_left_14_01"))];
  CHECK(right.source_file == left.source_file);
  CHECK(right.role == Role::PunchRight);
  CHECK(left.role == Role::PunchLeft);
  CHECK(right.target_frame == 20);
  CHECK(left.target_frame == 9);
  CHECK(left.clip.frame_count() == 20);
}

TEST_CASE("every loop range of the manifests is a close pose match") {
  for (const std::string name : {"daz43", "cmu31"}) {
    const MotionSet& set = manifest_set(name);
    for (const MotionClip& c : set.clips) {
      if (!c.cyclic || !c.derived_from.empty()) continue;  // a held stand joins itself exactly
      CAPTURE(c.clip.name);
      // Playing loop_last then loop_first: the jump in pose there, against how different the poses half a
      // loop apart are (for a gait cycle: the legs swapped). An arbitrary loop range joins at about that.
      const double join = pose_distance(c.clip, c.loop_last, c.loop_first);
      const int half = (c.loop_last - c.loop_first + 1) / 2;
      std::vector<double> apart;
      for (int f = c.loop_first; f + half <= c.loop_last; ++f) apart.push_back(pose_distance(c.clip, f, f + half));
      std::sort(apart.begin(), apart.end());
      const double half_loop = apart[apart.size() / 2];
      CHECK(join < 0.045);  // metres RMS over the joints
      if (c.role == Role::Walk) CHECK(join < 0.25 * half_loop);
      if (c.role == Role::Idle) CHECK(join < 0.02);
    }
  }
}

TEST_CASE("clips of other performers play on the reference skeleton: rotations kept, root scaled by leg length") {
  const MotionSet& cmu = manifest_set("cmu31");
  const Skeleton& ref = *cmu.skeleton;
  auto leg = [](const Skeleton& s) {
    float sum = 0;
    for (const char* j : {"LeftKnee", "LeftAnkle", "RightKnee", "RightAnkle"}) sum += glm::length(s.joints[static_cast<size_t>(s.find(j))].offset);
    return sum / 2;
  };
  float largest_change = 0;
  for (const MotionClip& c : cmu.clips) {
    CAPTURE(c.clip.name);
    if (!c.derived_from.empty()) continue;  // made from the walk, not read from a file
    BvhReadOptions options;
    options.unit_scale = 0.05644f;
    const Clip file = read_bvh(c.source_file, options);
    const Skeleton& own = *file.skeleton;
    const float ratio = leg(ref) / leg(own);
    largest_change = std::max(largest_change, std::abs(ratio - 1.0f));
    for (int f : {0, c.clip.frame_count() / 2, c.clip.frame_count() - 1}) {
      const Pose& p = c.clip.frames[static_cast<size_t>(f)];
      const Pose& q = file.frames[static_cast<size_t>(f)];  // every cmu31 range starts at the file's frame 0
      // A steered clip's root turns on purpose (steer_clip; its own test): every other joint is as recorded.
      const bool steered = c.steer_rad_per_s != 0.0f;
      for (int j = steered ? 1 : 0; j < ref.size(); ++j) {
        const int k = own.find(ref.joints[static_cast<size_t>(j)].name);
        CHECK(std::abs(glm::dot(p.rotations[static_cast<size_t>(j)], q.rotations[static_cast<size_t>(k)])) == doctest::Approx(1.0f));
      }
      if (steered) continue;
      CHECK(p.root_position.x == doctest::Approx(q.root_position.x * ratio));
      CHECK(p.root_position.z == doctest::Approx(q.root_position.z * ratio));
    }
  }
  // Subject 111 (the crawl) has legs about 11% shorter than subject 69 (the reference walk).
  CHECK(largest_change > 0.1f);
}

TEST_CASE("the automatic floor puts the feet on y = 0 in every clip") {
  for (const std::string name : {"daz43", "cmu31"}) {
    const MotionSet& set = manifest_set(name);
    for (const MotionClip& c : set.clips) {
      CAPTURE(c.clip.name);
      // Per frame the lowest heel/toe point; its 10th percentile over the clip is at the floor (the rule
      // is applied per 1-second window, so over the whole clip it holds within a couple of cm).
      std::vector<float> lowest;
      std::vector<glm::vec3> p;
      std::vector<glm::quat> r;
      for (const Pose& pose : c.clip.frames) {
        forward_kinematics(*set.skeleton, pose, p, &r);
        const FootPoints feet = foot_points(*set.skeleton, set.body, p, r);
        lowest.push_back(std::min({feet.heel[0].y, feet.heel[1].y, feet.toe[0].y, feet.toe[1].y}));
      }
      std::sort(lowest.begin(), lowest.end());
      CHECK(std::abs(lowest[lowest.size() / 10]) < 0.02f);
      CHECK(lowest.front() > -0.05f);
    }
  }
}

TEST_CASE("a number as floor moves the clip down by exactly that") {
  const std::string clip = "{\"file\": \"walk_69_01.bvh\", \"role\": \"walk\"";
  const MotionSet zero = load_motion_set(write_manifest("floor0.json", cmu31_manifest(clip + ", \"floor\": 0}")), Params{});
  const MotionSet raised = load_motion_set(write_manifest("floor1.json", cmu31_manifest(clip + ", \"floor\": 0.25}")), Params{});
  CHECK(zero.clips[0].clip.name == "walk_69_01");
  for (int f : {0, 35, 69})
    CHECK(raised.clips[0].clip.frames[static_cast<size_t>(f)].root_position.y ==
          doctest::Approx(zero.clips[0].clip.frames[static_cast<size_t>(f)].root_position.y - 0.25f));
}

TEST_CASE("bad manifests give errors naming the manifest and the field") {
  const std::string walk = "{\"file\": \"walk_69_01.bvh\", \"role\": \"walk\"}";
  auto load = [](const std::string& file, const std::string& text) { return load_motion_set(write_manifest(file, text), Params{}); };
  CHECK_THROWS_WITH_AS(load("bad_json.json", "{\n\"name\": \"x\",\n\"clips\": [\n}"), doctest::Contains("bad_json.json:4: invalid JSON"),
                       InputError);
  // A number past a double's range is nlohmann's out_of_range, not a parse_error: it once escaped as such
  // (found by the manifest fuzz target; the input is in its corpus).
  CHECK_THROWS_WITH_AS(load_motion_set(test::repo() + "/tests/fuzz/corpus/manifest/number_overflow.json", Params{}),
                       doctest::Contains("number_overflow.json: invalid JSON: [json.exception.out_of_range.406] number overflow"),
                       InputError);
  // A NUL in a field name ("\u0000clips") ended the message there (found by the manifest fuzz target).
  CHECK_THROWS_WITH_AS(load_motion_set(test::repo() + "/tests/fuzz/corpus/manifest/nul_in_field_name.json", Params{}),
                       doctest::Contains("nul_in_field_name.json: \\x00clips: unknown field (expected one of: name, folder"),
                       InputError);
  // A NUL in a clip's file name ("humanoid_t\u0000all.bvh") cut the BVH loader's message at the NUL, so that it
  // named no file (found by the manifest fuzz target): a file or folder name with a control character is
  // refused where the manifest gives it.
  CHECK_THROWS_WITH_AS(load_motion_set(test::repo() + "/tests/fuzz/corpus/manifest/nul_in_file_name.json", Params{}),
                       doctest::Contains("nul_in_file_name.json: clips[1].file: a file name with a control character in it"),
                       InputError);
  CHECK_THROWS_WITH_AS(load("unknown_field.json", cmu31_manifest(walk, ", \"speed\": 2")),
                       doctest::Contains("unknown_field.json: speed: unknown field"), InputError);
  CHECK_THROWS_WITH_AS(load("no_folder.json", "{\"clips\": [" + walk + "]}"), doctest::Contains("no_folder.json: folder: missing"),
                       InputError);
  CHECK_THROWS_WITH_AS(load("wrong_folder.json", "{\"folder\": \"nowhere\", \"clips\": [" + walk + "]}"),
                       doctest::Contains("wrong_folder.json: folder: 'nowhere' holds no 'walk_69_01.bvh'"), InputError);
  CHECK_THROWS_WITH_AS(load("no_clips.json", cmu31_manifest("")), doctest::Contains("no_clips.json: clips: must be a non-empty array"),
                       InputError);
  CHECK_THROWS_WITH_AS(load("units.json", cmu31_manifest(walk, ", \"unit_scale\": 0.05")),
                       doctest::Contains("units.json: units: give either"), InputError);
  CHECK_THROWS_WITH_AS(load("role.json", cmu31_manifest("{\"file\": \"walk_69_01.bvh\", \"role\": \"stroll\"}")),
                       doctest::Contains("role.json: clips[0] (walk_69_01).role: unknown role 'stroll'"), InputError);
  CHECK_THROWS_WITH_AS(load("no_tt.json", cmu31_manifest("{\"file\": \"duck_127_29.bvh\", \"role\": \"duck\"}")),
                       doctest::Contains("no_tt.json: clips[0] (duck_127_29).t_t: missing"), InputError);
  CHECK_THROWS_WITH_AS(load("tt_walk.json", cmu31_manifest("{\"file\": \"walk_69_01.bvh\", \"role\": \"walk\", \"t_t\": 3}")),
                       doctest::Contains("tt_walk.json: clips[0] (walk_69_01).t_t: only target motions"), InputError);
  CHECK_THROWS_WITH_AS(load("tt_out.json", cmu31_manifest("{\"file\": \"duck_127_29.bvh\", \"role\": \"duck\", \"frames\": [5, 40], \"t_t\": 2}")),
                       doctest::Contains("tt_out.json: clips[0] (duck_127_29).t_t: 2 is outside the clip's frames [5, 40]"), InputError);
  CHECK_THROWS_WITH_AS(load("frames.json", cmu31_manifest("{\"file\": \"walk_69_01.bvh\", \"role\": \"walk\", \"frames\": [0, 70]}")),
                       doctest::Contains("frames.json: clips[0] (walk_69_01).frames: ends at frame 70"), InputError);
  CHECK_THROWS_WITH_AS(load("frames2.json", cmu31_manifest("{\"file\": \"walk_69_01.bvh\", \"role\": \"walk\", \"frames\": [9, 3]}")),
                       doctest::Contains("frames2.json: clips[0] (walk_69_01).frames: first (9) must be before last (3)"), InputError);
  CHECK_THROWS_WITH_AS(load("loop.json", cmu31_manifest("{\"file\": \"walk_69_01.bvh\", \"role\": \"walk\", \"frames\": [10, 60], \"loop\": [5, 40]}")),
                       doctest::Contains("loop.json: clips[0] (walk_69_01).loop: [5, 40] is outside"), InputError);
  CHECK_THROWS_WITH_AS(load("loop_target.json", cmu31_manifest("{\"file\": \"duck_127_29.bvh\", \"role\": \"duck\", \"t_t\": 10, \"loop\": [1, 9]}")),
                       doctest::Contains("loop_target.json: clips[0] (duck_127_29).loop: only locomotion clips loop"), InputError);
  CHECK_THROWS_WITH_AS(load("dup.json", cmu31_manifest(walk + ", " + walk)), doctest::Contains("dup.json: clips[1] (walk_69_01).name: the name 'walk_69_01' repeats"),
                       InputError);
  CHECK_THROWS_WITH_AS(load("skip.json", cmu31_manifest("{\"file\": \"walk_69_01.bvh\", \"role\": \"walk\", \"frames\": [0, 9]}", ", \"skip_first_frame\": true")),
                       doctest::Contains("skip.json: clips[0] (walk_69_01).frames: starts at frame 0"), InputError);
  CHECK_THROWS_WITH_AS(load("floor.json", cmu31_manifest("{\"file\": \"walk_69_01.bvh\", \"role\": \"walk\", \"floor\": \"low\"}")),
                       doctest::Contains("floor.json: clips[0] (walk_69_01).floor: must be \"auto\" or a height"), InputError);
  CHECK_THROWS_WITH_AS(load("reference.json", cmu31_manifest(walk, ", \"reference\": \"other.bvh\"")),
                       doctest::Contains("reference.json: reference: 'other.bvh' is not the file of any clip"), InputError);
  CHECK_THROWS_WITH_AS(load("steer_sign.json", cmu31_manifest("{\"file\": \"walk_69_01.bvh\", \"role\": \"turn_left\", \"steer_deg_per_s\": -40}")),
                       doctest::Contains("steer_sign.json: clips[0] (walk_69_01).steer_deg_per_s: turns the right way (positive is to the left), but the clip is 'turn_left'"),
                       InputError);
  CHECK_THROWS_WITH_AS(load("steer_rate.json", cmu31_manifest("{\"file\": \"walk_69_01.bvh\", \"role\": \"walk\", \"steer_deg_per_s\": 400}")),
                       doctest::Contains("steer_rate.json: clips[0] (walk_69_01).steer_deg_per_s: must be a rate of turn"), InputError);
  CHECK_THROWS_WITH_AS(load("steer_target.json", cmu31_manifest("{\"file\": \"duck_127_29.bvh\", \"role\": \"duck\", \"t_t\": 10, \"steer_deg_per_s\": 20}")),
                       doctest::Contains("steer_target.json: clips[0] (duck_127_29).steer_deg_per_s: only locomotion clips are steered"), InputError);
  // A clip file that is not there: the BVH reader names it.
  CHECK_THROWS_WITH_AS(load("missing_bvh.json", cmu31_manifest(walk + ", {\"file\": \"gone.bvh\", \"role\": \"walk\"}")),
                       doctest::Contains("cmu31/gone.bvh: cannot open"), InputError);
  // A clip from another skeleton (daz43 joints into a cmu31 set).
  CHECK_THROWS_WITH_AS(load("mixed.json", cmu31_manifest(walk + ", {\"file\": \"../daz43/walk_02_01.bvh\", \"role\": \"walk\"}")),
                       doctest::Contains("mixed.json: clips[1] (walk_02_01).file: '../daz43/walk_02_01.bvh' has 43 joints"), InputError);
}

TEST_CASE("steered turns: the heading gains rate x time, planted feet stay as still as in the walk, every joint but the root as it was") {
  struct Steered {
    const char* set;
    const char* walk;
    const char* turn;
    float deg_per_s;
  };
  for (const Steered& steered : {Steered{"cmu31", "walk_69_01", "turn_left_69_01", 40.0f}, Steered{"cmu31", "walk_69_01", "turn_right_69_01", -40.0f},
                                 Steered{"daz43", "walk_02_01", "turn_left_02_01", 40.0f}, Steered{"daz43", "walk_02_01", "turn_right_02_01", -40.0f}}) {
    const std::string name = steered.turn;
    CAPTURE(name);
    const MotionSet& cmu = manifest_set(steered.set);
    const MotionClip& walk = cmu.clips[static_cast<size_t>(cmu.find(steered.walk))];
    const MotionClip& turn = cmu.clips[static_cast<size_t>(cmu.find(steered.turn))];
    const float rate = glm::radians(steered.deg_per_s);
    REQUIRE(turn.steer_rad_per_s == doctest::Approx(rate));
    REQUIRE(turn.clip.frame_count() == walk.clip.frame_count());
    const int n = walk.clip.frame_count();
    const auto heading_gain = [&](int f) {
      return std::remainder(heading_of(turn.clip.frames[static_cast<size_t>(f)].rotations[0]) -
                                heading_of(walk.clip.frames[static_cast<size_t>(f)].rotations[0]),
                            2.0f * glm::pi<float>());
    };
    // Over the whole clip the heading gains rate x duration; it turns only off double support.
    CHECK(heading_gain(n - 1) == doctest::Approx(rate * static_cast<float>(n - 1) / walk.clip.fps).epsilon(1e-3));
    std::vector<glm::vec3> pw, pt;
    std::vector<glm::quat> rw, rt;
    FootPoints previous_walk{}, previous_turn{};
    float walk_motion = 0.0f, turn_motion = 0.0f;
    for (int f = 0; f < n; ++f) {
      const Pose& w = walk.clip.frames[static_cast<size_t>(f)];
      const Pose& t = turn.clip.frames[static_cast<size_t>(f)];
      CHECK(t.root_position.y == doctest::Approx(w.root_position.y));
      for (size_t j = 1; j < w.rotations.size(); ++j) CHECK(std::abs(glm::dot(t.rotations[j], w.rotations[j])) == doctest::Approx(1.0f));
      const FrameContacts& c = walk.contacts[static_cast<size_t>(f)];
      if (f > 0 && (c[kLeft].any() && c[kRight].any())) CHECK(heading_gain(f) == doctest::Approx(heading_gain(f - 1)));
      forward_kinematics(*cmu.skeleton, w, pw, &rw);
      forward_kinematics(*cmu.skeleton, t, pt, &rt);
      const FootPoints fw = foot_points(*cmu.skeleton, cmu.body, pw, rw), ft = foot_points(*cmu.skeleton, cmu.body, pt, rt);
      // A heel that stands still in the walk (down, moving under 3 mm a frame) stands still in the turn:
      // turning about it (or, in double support, not turning) adds under a millimetre a frame.
      if (f > 0) {
        for (size_t side = 0; side < 2; ++side) {
          const float in_walk = glm::length(fw.heel[side] - previous_walk.heel[side]);
          if (!c[side].heel || in_walk > 0.003f) continue;
          const float in_turn = glm::length(ft.heel[side] - previous_turn.heel[side]);
          walk_motion = std::max(walk_motion, in_walk);
          turn_motion = std::max(turn_motion, in_turn);
          CHECK(in_turn <= in_walk + 0.001f);
        }
      }
      previous_walk = fw;
      previous_turn = ft;
    }
    MESSAGE(name << ": a standing heel moves at most " << 1000.0f * turn_motion << " mm a frame (in the walk: " << 1000.0f * walk_motion << ")");
    // The same steps: the detector re-run on the turn agrees but for a frame or two where a swinging foot,
    // carried round faster or slower, meets its speed thresholds a frame earlier or later.
    int agree = 0;
    for (size_t f = 0; f < walk.contacts.size(); ++f) agree += turn.contacts[f] == walk.contacts[f];
    CHECK(agree >= static_cast<int>(0.96 * static_cast<double>(walk.contacts.size())));
  }
}

TEST_CASE("a set with no idle stands in a posture held from its walk: upright, feet side by side on the floor, arms down") {
  const MotionSet& set = manifest_set("cmu31");  // its takes have no quiet standing
  const int stand = set.find("walk_69_01_stand");
  REQUIRE(stand >= 0);
  const MotionClip& c = set.clips[static_cast<size_t>(stand)];
  CHECK(c.role == Role::Idle);
  CHECK(c.cyclic);
  CHECK(c.derived_from == "walk_69_01");
  REQUIRE(c.clip.frame_count() >= 3);
  CHECK(c.loop_last < c.clip.frame_count() - 1);  // a loop edge blends from the frame after loop_last
  const Pose& pose = c.clip.frames.front();
  for (const Pose& p : c.clip.frames) {  // held: no joint moves, the root does not travel
    CHECK(p.root_position == pose.root_position);
    for (size_t j = 0; j < p.rotations.size(); ++j) CHECK(p.rotations[j] == pose.rotations[j]);
  }
  std::vector<glm::vec3> at;
  std::vector<glm::quat> turned;
  forward_kinematics(*set.skeleton, pose, at, &turned);
  const BodyMap& b = set.body;
  const glm::vec3 forward = glm::normalize(glm::vec3(pose.rotations[0] * glm::vec3(0.0f, 0.0f, 1.0f)) * glm::vec3(1.0f, 0.0f, 1.0f));
  // On the floor: the lowest heel or toe tip at 0, both feet down (contacts on every frame).
  float lowest = INFINITY;
  for (const LegChain& leg : b.legs) {
    lowest = std::min(lowest, at[static_cast<size_t>(leg.ankle)].y);
    lowest = std::min(lowest, end_site_position(*set.skeleton, leg.toe_tip_joint, at, turned).y);
  }
  CHECK(std::abs(lowest) < 0.005f);
  for (const FrameContacts& f : c.contacts) {
    CHECK(f[kLeft].any());
    CHECK(f[kRight].any());
  }
  // Side by side: the ankles within 3 cm of each other along the facing, under the hips.
  const glm::vec3 left = at[static_cast<size_t>(b.legs[kLeft].ankle)], right = at[static_cast<size_t>(b.legs[kRight].ankle)];
  CHECK(std::abs(glm::dot(left - right, forward)) < 0.03f);
  // Upright: the head above the pelvis within 10 cm on the floor; the knees straight (the hip, knee and
  // ankle in a line within 2 cm).
  const glm::vec3 head = at[static_cast<size_t>(b.head)], pelvis = at[static_cast<size_t>(b.root)];
  CHECK(glm::length(glm::vec2(head.x - pelvis.x, head.z - pelvis.z)) < 0.10f);
  for (const LegChain& leg : b.legs) {
    const glm::vec3 hip = at[static_cast<size_t>(leg.hip)], knee = at[static_cast<size_t>(leg.knee)], ankle = at[static_cast<size_t>(leg.ankle)];
    CHECK(glm::length(glm::cross(glm::normalize(ankle - hip), knee - hip)) < 0.02f);
  }
  // The arms hang: each hand below its shoulder by most of the arm's length.
  for (const ArmChain& arm : b.arms) {
    const glm::vec3 shoulder = at[static_cast<size_t>(arm.shoulder)], hand = at[static_cast<size_t>(arm.wrist)];
    const float reach = glm::length(at[static_cast<size_t>(arm.elbow)] - shoulder) + glm::length(hand - at[static_cast<size_t>(arm.elbow)]);
    CHECK(shoulder.y - hand.y > 0.8f * reach);
  }
}
