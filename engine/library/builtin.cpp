// The built-in motion library: every generated clip, assembled into a MotionSet, and written as BVH + manifest.
#include "engine/library/builtin.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "engine/library/generated.h"
#include "engine/motion/bvh.h"
#include "engine/util/files.h"

namespace prep {
namespace library {

std::vector<GeneratedClip> make_all_clips() {
  std::vector<GeneratedClip> clips;
  clips.push_back(make_idle("idle"));
  clips.push_back(make_walk("walk", 1.4f, 1.0f));
  clips.push_back(make_walk("walk_slow", 0.9f, 0.8f));
  clips.push_back(make_turn("turn_left", true));
  clips.push_back(make_turn("turn_right", false));
  clips.push_back(make_side_step("step_left", true));
  clips.push_back(make_side_step("step_right", false));
  clips.push_back(make_crawl("crawl", nullptr));
  clips.push_back(make_duck("duck", nullptr));
  clips.push_back(make_jump("jump", nullptr));
  clips.push_back(make_punch("punch_left", true));
  clips.push_back(make_punch("punch_right", false));
  clips.push_back(make_kick("kick"));
  return clips;
}

Obstacle obstacle_of(const std::string& clip_name) {
  Obstacle o;
  if (clip_name == "crawl") make_crawl(clip_name, &o);
  if (clip_name == "duck") make_duck(clip_name, &o);
  if (clip_name == "jump") make_jump(clip_name, &o);
  return o;
}

}  // namespace library

MotionSet make_builtin_motion_set(const Params& params) {
  MotionSet set;
  set.name = "builtin";
  set.skeleton = builtin_skeleton();
  for (library::GeneratedClip& g : library::make_all_clips()) {
    MotionClip m;
    m.clip = std::move(g.clip);
    m.role = g.role;
    m.cyclic = g.cyclic;
    m.loop_first = g.loop_first;
    m.loop_last = g.loop_last;
    m.target_frame = g.target_frame;
    m.source_file = "builtin";
    set.clips.push_back(std::move(m));
  }
  finalize_motion_set(set, params);
  return set;
}

void write_builtin_library(const MotionSet& set, const std::string& folder) {
  std::filesystem::create_directories(folder);
  nlohmann::json clips = nlohmann::json::array();
  for (const MotionClip& m : set.clips) {
    const std::string file = m.clip.name + ".bvh";
    write_bvh(m.clip, (std::filesystem::path(folder) / file).string());
    nlohmann::json c = {{"name", m.clip.name}, {"file", file}, {"role", role_name(m.role)}, {"frames", {0, m.clip.frame_count() - 1}}};
    if (m.cyclic) c["loop"] = {m.loop_first, m.loop_last};
    if (m.target_frame >= 0) c["t_t"] = m.target_frame;
    clips.push_back(c);
  }
  const nlohmann::json manifest = {{"name", set.name},
                                   {"folder", std::filesystem::absolute(folder).string()},
                                   {"unit_scale", 0.01},
                                   {"skip_first_frame", false},
                                   {"reference", set.clips.empty() ? "" : set.clips.front().clip.name + ".bvh"},
                                   {"clips", clips}};
  write_file_atomic((std::filesystem::path(folder) / "manifest.json").string(), manifest.dump(2) + "\n");
}

}  // namespace prep
