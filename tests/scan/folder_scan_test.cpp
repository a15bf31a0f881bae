// The folder scan against our hand-made manifests of the shared mocap, and on takes whose names say
// nothing (the built-in clips written as BVH under neutral names).
#include "engine/scan/folder_scan.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "engine/control/action_effects.h"
#include "engine/graph/motion_graph.h"
#include "engine/library/builtin.h"
#include "engine/motion/bvh.h"
#include "engine/scan/loop_search.h"
#include "engine/util/error.h"
#include "engine/util/files.h"
#include "tests/support/paths.h"

using namespace prep;
namespace fs = std::filesystem;

namespace {

// A take as the scan measures it: in metres, on its floor, with its heading-frame poses.
struct MeasuredTake {
  Clip clip;
  BodyMap body;
  MotionSignals signals;
  std::unique_ptr<HeadingFramePoses> poses;
};

MeasuredTake measure_take(const std::string& path, float unit_scale) {
  MeasuredTake t;
  BvhReadOptions options;
  options.unit_scale = unit_scale;
  t.clip = read_bvh(path, options);
  t.body = BodyMap::detect(*t.clip.skeleton);
  const std::vector<float> floor = estimate_floor_heights(t.clip, t.body);
  for (size_t f = 0; f < t.clip.frames.size(); ++f) t.clip.frames[f].root_position.y -= floor[f];
  t.signals = measure_motion(t.clip, t.body, Params().contacts);
  t.poses = std::make_unique<HeadingFramePoses>(t.clip, t.signals);
  return t;
}

float scan_fps(const FolderScan& scan, const std::string& file) {
  for (const ScannedFile& f : scan.files)
    if (f.file == file) return f.fps;
  return 0.0f;
}

const ScannedClip* find_clip(const FolderScan& scan, const std::string& name) {
  for (const ScannedClip& c : scan.clips)
    if (c.name == name) return &c;
  return nullptr;
}

// Our hand-made manifest against the scan of its folder: every clip both have (same name, same file) has
// the same role, a loop within 10% of a gait cycle of ours or joining no worse, and T_t within 0.2 s.
void check_against_hand_made(const std::string& folder_name) {
  const FolderScan scan = scan_motion_folder(test::mocap() + "/" + folder_name, Params{});
  const nlohmann::json ours = nlohmann::json::parse(read_file(test::repo() + "/assets/manifests/" + folder_name + ".json"));
  int shared = 0, loops = 0, timings = 0;
  std::map<std::string, MeasuredTake> takes;
  for (const auto& mine : ours["clips"]) {
    const std::string name = mine["name"], file = mine["file"];
    const ScannedClip* found = find_clip(scan, name);
    if (found == nullptr || found->file != file) continue;
    CAPTURE(name);
    ++shared;
    CHECK(std::string(role_name(found->role)) == mine["role"].get<std::string>());
    if (!takes.count(file)) takes.emplace(file, measure_take(test::mocap() + "/" + folder_name + "/" + file, scan.unit_scale));
    const MeasuredTake& take = takes.at(file);
    const float fps = take.clip.fps;
    if (mine.contains("loop")) {
      ++loops;
      REQUIRE(found->loop.has_value());
      const int first = mine["loop"][0], last = mine["loop"][1];
      const int cycle = gait_cycle_frames(take.signals, 0, take.clip.frame_count() - 1);
      const float theirs_error = take.poses->join_error_cm(last, first);
      const float our_error = take.poses->join_error_cm(found->loop->last, found->loop->first);
      MESSAGE(name << ": loop " << found->loop->first << "-" << found->loop->last << " (" << our_error << " cm) against ours " << first
                   << "-" << last << " (" << theirs_error << " cm), gait cycle " << cycle << " frames");
      const bool close = cycle > 0 && std::abs(found->loop->first - first) <= 0.1 * cycle &&
                         std::abs(found->loop->last - last) <= 0.1 * cycle;
      CHECK((close || our_error <= theirs_error + 1e-4f));
    }
    if (mine.contains("t_t")) {
      ++timings;
      REQUIRE(found->target_frame.has_value());
      MESSAGE(name << ": T_t " << *found->target_frame << " against ours " << mine["t_t"].get<int>() << " at " << fps << " fps");
      CHECK(std::abs(*found->target_frame - mine["t_t"].get<int>()) <= 0.2f * fps + 1e-3f);
    }
  }
  MESSAGE(folder_name << ": " << shared << " clips shared with our manifest, " << loops << " loops, " << timings << " T_t");
  CHECK(shared >= 7);
  CHECK(loops >= 1);
  CHECK(timings >= 3);

  // What it writes loads, as the clips it found, and the graph has every core role.
  const std::string out = test::tmp_dir() + "/scan-" + folder_name + "/" + folder_name + ".json";
  fs::create_directories(fs::path(out).parent_path());
  write_file_atomic(out, scan_manifest_json(scan, out).dump(2));
  const MotionSet set = load_motion_set(out, Params{});
  // Every take found, in order; then, for a set with no idle (cmu31), the stand held from its walk.
  const bool has_idle = std::any_of(scan.clips.begin(), scan.clips.end(), [](const ScannedClip& c) { return c.role == Role::Idle; });
  REQUIRE(set.clips.size() == scan.clips.size() + (has_idle ? 0 : 1));
  if (!has_idle) CHECK(set.clips.back().role == Role::Idle);
  for (size_t i = 0; i < scan.clips.size(); ++i) {
    const MotionClip& loaded = set.clips[i];
    const ScannedClip& found = scan.clips[i];
    CAPTURE(found.name);
    CHECK(loaded.clip.name == found.name);
    CHECK(loaded.role == found.role);
    CHECK(loaded.clip.frame_count() == found.last - found.first + 1);
    CHECK(loaded.cyclic == found.loop.has_value());
    if (found.loop) CHECK(loaded.loop_first == found.loop->first - found.first);
    if (found.target_frame) CHECK(loaded.target_frame == *found.target_frame - found.first);
  }
  const MotionGraph graph = MotionGraph::build(set, Params().graph);
  for (Role role : {Role::Walk, Role::TurnLeft, Role::TurnRight}) {
    bool core = false;
    for (const GraphNode& n : graph.nodes()) core = core || (n.role == role && n.core);
    CHECK_MESSAGE(core, role_name(role));
  }
  CHECK(default_core_clips(set).size() >= 3);
}

}  // namespace

TEST_CASE("prep manifest on cmu31: roles, loops and T_t as in our hand-made manifest, and it loads with every core role") {
  const FolderScan scan = scan_motion_folder(test::mocap() + "/cmu31", Params{});
  CHECK(scan.units == "cmu");
  CHECK(scan.figure_height > 1.4f);
  CHECK(scan.figure_height < 2.1f);
  CHECK_FALSE(scan.skip_first_frame);
  CHECK(scan.reference == "walk_69_01.bvh");
  // The take of a jab then a cross gives one clip per strike.
  const ScannedClip* jab = find_clip(scan, "punch_left_14_01");
  const ScannedClip* cross = find_clip(scan, "punch_right_14_01");
  REQUIRE(jab);
  REQUIRE(cross);
  CHECK(jab->last < *cross->target_frame);
  // The recorded 90-degree turn loops where it keeps turning (at 15 degrees/s or more over the loop) and
  // joins within 2 cm; the data has no right turn, so that one is steered from the walk.
  const ScannedClip* turn = find_clip(scan, "turn_left_69_27");
  REQUIRE(turn);
  if (turn->loop) {
    const MeasuredTake take = measure_take(test::mocap() + "/cmu31/turn_left_69_27.bvh", scan.unit_scale);
    const float turned = take.signals.heading[static_cast<size_t>(turn->loop->last)] - take.signals.heading[static_cast<size_t>(turn->loop->first)];
    CHECK(turned * 180.0f / 3.14159265f / take.signals.seconds(turn->loop->last - turn->loop->first) >= 15.0f);
    CHECK(take.poses->join_error_cm(turn->loop->last, turn->loop->first) < 2.0f);
    CHECK(turn->core);
  }
  const ScannedClip* steered = find_clip(scan, "turn_right_69_01");
  REQUIRE(steered);
  CHECK(steered->steer_deg_per_s < 0.0f);
  CHECK(steered->core);
  // A kick is what this set lacks, and the scan says so.
  bool says_no_kick = false;
  for (const std::string& l : scan.lacks) says_no_kick = says_no_kick || l.find("no kick") == 0;
  CHECK(says_no_kick);
  check_against_hand_made("cmu31");
}

TEST_CASE("prep manifest on daz43: roles, loops and T_t as in our hand-made manifest, and the reference pose is left out") {
  const FolderScan scan = scan_motion_folder(test::mocap() + "/daz43", Params{});
  CHECK(scan.units == "centimetres");
  CHECK(scan.skip_first_frame);
  for (const ScannedClip& c : scan.clips) CHECK(c.first >= 1);
  // A slow walk among the walks, and the controller's walk an everyday pace.
  int slow = 0;
  for (const ScannedClip& c : scan.clips) {
    if (c.core_as == "slow walk") ++slow;
    if (c.core_as == "walk") {
      CHECK(c.speed > 0.9f);
      CHECK(c.speed < 1.7f);
    }
  }
  CHECK(slow == 1);
  check_against_hand_made("daz43");
}

TEST_CASE("prep manifest from the motion alone: built-in clips under names that say nothing") {
  const std::string folder = test::tmp_dir() + "/scan-neutral";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const MotionSet builtin = make_builtin_motion_set(Params{});
  std::map<std::string, Role> truth;
  std::map<std::string, float> target_frames;  // T_t in seconds, of the clips that are not cyclic
  int k = 0;
  for (const MotionClip& c : builtin.clips) {
    // Several loops of each cyclic clip, so that the take has footsteps to find a gait cycle in.
    Clip take = c.clip;
    if (c.cyclic) {
      take.frames.clear();
      glm::vec3 offset(0.0f);
      for (int loop = 0; loop < 4; ++loop) {
        const Pose& start = c.clip.frames[static_cast<size_t>(c.loop_first)];
        const Pose& end = c.clip.frames[static_cast<size_t>(c.loop_last)];
        for (int f = c.loop_first; f < c.loop_last; ++f) {
          Pose p = c.clip.frames[static_cast<size_t>(f)];
          p.root_position += offset;
          take.frames.push_back(p);
        }
        offset += glm::vec3(end.root_position.x - start.root_position.x, 0.0f, end.root_position.z - start.root_position.z);
      }
    }
    char name[32];
    std::snprintf(name, sizeof name, "take_%02d.bvh", ++k);
    BvhWriteOptions metres;
    metres.unit_scale = 1.0f;
    write_bvh(take, folder + "/" + name, metres);
    truth[name] = c.role;
    if (!c.cyclic) target_frames[name] = static_cast<float>(c.target_frame) / c.clip.fps;
  }
  const FolderScan scan = scan_motion_folder(folder, Params{});
  CHECK(scan.units == "metres");
  int right = 0, total = 0;
  for (const auto& [file, role] : truth) {
    if (role == Role::TurnLeft || role == Role::TurnRight || role == Role::StepLeft || role == Role::StepRight) continue;
    ++total;
    for (const ScannedClip& c : scan.clips)
      if (c.file == file && c.steer_deg_per_s == 0.0f) {
        MESSAGE(file << ": built as " << std::string(role_name(role)) << ", found " << std::string(role_name(c.role)) << " (" << c.evidence << ")");
        if (c.role == role) ++right;
        if (target_frames.count(file)) {
          REQUIRE(c.target_frame.has_value());
          const float found_at = static_cast<float>(*c.target_frame) / scan_fps(scan, file);
          MESSAGE(file << ": T_t at " << found_at << " s, built at " << target_frames[file] << " s");
          CHECK(std::abs(found_at - target_frames[file]) <= 0.2f);
        }
        break;
      }
  }
  MESSAGE(right << " of " << total << " roles found from the motion alone");
  CHECK(right >= total - 1);
}

TEST_CASE("prep manifest refuses a folder with no takes and leaves out a broken one, naming its file and line") {
  const std::string empty = test::tmp_dir() + "/scan-empty";
  fs::remove_all(empty);
  fs::create_directories(empty);
  CHECK_THROWS_WITH_AS(scan_motion_folder(empty, Params{}), doctest::Contains("holds no BVH file"), InputError);
  CHECK_THROWS_WITH_AS(scan_motion_folder(empty + "/nowhere", Params{}), doctest::Contains("is not a folder"), InputError);

  const std::string mixed = test::tmp_dir() + "/scan-mixed";
  fs::remove_all(mixed);
  fs::create_directories(mixed);
  fs::copy_file(test::mocap() + "/cmu31/walk_69_01.bvh", mixed + "/walk_69_01.bvh");
  write_file_atomic(mixed + "/broken.bvh", "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 zero\n");
  const FolderScan scan = scan_motion_folder(mixed, Params{});
  REQUIRE(scan.files.size() == 2);
  CHECK(scan.files[0].file == "broken.bvh");
  CHECK_FALSE(scan.files[0].used);
  CHECK(scan.files[0].note.find("left out") == 0);
  CHECK(scan.files[0].note.find("broken.bvh") != std::string::npos);
  CHECK(scan.files[0].note.find("broken.bvh:4:") != std::string::npos);  // the file and its line
  CHECK(scan.files[1].used);
  CHECK(find_clip(scan, "walk_69_01") != nullptr);
}
