// The target motions of a motion set as the world uses them (WorldAssets): T_p, where each clip meets its
// object (reach, lateral), where its target movement is over (release_frame) and how far it has come by
// each frame before T_t (advance); and loading a scenario's motions, Params and policy.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/graph/reference_posture.h"
#include "engine/library/builtin.h"
#include "engine/library/generated.h"
#include "engine/motion/body_volumes.h"
#include "engine/motion/center_of_mass.h"
#include "engine/motion/kinematics.h"
#include "engine/synthesis/preparation_run.h"
#include "engine/util/error.h"
#include "engine/util/files.h"

#include "engine/world/clearance.h"
#include "engine/world/floor.h"
#include "engine/world/policy_cache.h"
#include "engine/world/world.h"

namespace prep {

namespace {

using floor_plane::floor_xz;
using floor_plane::forward_of;
using floor_plane::left_of;

// Where a target clip meets its object, in the clip's coordinates on the floor (x, z).
// - Built-in obstacle clips: the middle of the obstacle they were made for (library::obstacle_of).
// - Kicks and punches: the farthest point the striking foot (toe tips) or hand (wrist) reaches ahead of
//   the T_p root during the target movement (T_t to one second after it).
// - Other obstacle clips (a manifest's crawl, duck, jump): the root's position half a second after T_t,
//   about where the body passes the obstacle.
// `peak_frame` (optional) receives the frame where a striking effector reached that point (-1 otherwise).
glm::vec2 interaction_point(const MotionSet& set, const MotionClip& mc, TargetAction action, int reference_frame,
                            int* peak_frame = nullptr) {
  if (peak_frame) *peak_frame = -1;
  if (set.name == "builtin") {
    const library::Obstacle o = library::obstacle_of(mc.clip.name);
    if (o.height > 0.0f) return {0.0f, 0.5f * (o.z_near + o.z_far)};
  }
  const Clip& clip = mc.clip;
  const int t_t = std::clamp(mc.target_frame, 0, clip.frame_count() - 1);
  const int end = std::min(clip.frame_count() - 1, t_t + static_cast<int>(std::lround(clip.fps)));
  const Pose& ref = clip.frames[static_cast<size_t>(reference_frame)];
  const glm::vec2 origin = floor_xz(ref.root_position);
  const glm::vec2 fwd = forward_of(heading_of(ref.rotations[0]));
  std::vector<int> effectors;
  std::vector<bool> end_site;
  const BodyMap& body = set.body;
  if (action == TargetAction::Kick) {
    for (const auto& leg : body.legs)
      if (leg.toe_tip_joint >= 0) effectors.push_back(leg.toe_tip_joint);
  } else if (action == TargetAction::PunchLeft) {
    effectors.push_back(body.arms[kLeft].wrist);
  } else if (action == TargetAction::PunchRight) {
    effectors.push_back(body.arms[kRight].wrist);
  }
  effectors.erase(std::remove(effectors.begin(), effectors.end(), -1), effectors.end());
  if (effectors.empty()) {
    const int f = std::min(clip.frame_count() - 1, t_t + static_cast<int>(std::lround(0.5f * clip.fps)));
    return floor_xz(clip.frames[static_cast<size_t>(f)].root_position);
  }
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  glm::vec2 best = origin;
  float best_forward = -std::numeric_limits<float>::infinity();
  for (int f = t_t; f <= end; ++f) {
    forward_kinematics(*set.skeleton, clip.frames[static_cast<size_t>(f)], positions, &rotations);
    for (int j : effectors) {
      const bool kick = action == TargetAction::Kick;
      const glm::vec3 p = kick && set.skeleton->joints[static_cast<size_t>(j)].has_end_site
                              ? end_site_position(*set.skeleton, j, positions, rotations)
                              : positions[static_cast<size_t>(j)];
      const float ahead = glm::dot(floor_xz(p) - origin, fwd);
      if (ahead > best_forward) {
        best_forward = ahead;
        best = floor_xz(p);
        if (peak_frame) *peak_frame = f;
      }
    }
  }
  return best;
}

std::optional<Role> role_of(TargetAction a) { return parse_role(role_name_of(a)); }

// m along the T_p facing: where an obstacle of the target's kind is best passed by the swept clip, searched
// in 2 cm steps over the ground the clip covers: the highest board cleared (a jump), the lowest rail passed
// under (a crawl or duck), for a rail or board 0.1 m deep.
float best_crossing(const ClipSweep& sweep, TargetMotion t) {
  const ObjectType type = t.action == TargetAction::Jump ? ObjectType::Hurdle
                          : t.action == TargetAction::Duck ? ObjectType::Beam
                                                            : ObjectType::Bar;
  // Only where the root passes the obstacle's line from one side to the other, with room on both.
  constexpr float kRoom = 0.2f;
  const float lo = sweep.root_z.front() + kRoom, hi = sweep.root_z.back() - kRoom;
  float best_z = t.reach, best = type == ObjectType::Hurdle ? -1e9f : 1e9f;
  for (float z = lo; z <= hi; z += 0.02f) {
    t.reach = z;
    const ObstacleFit f = fit_obstacle(sweep, t, type, {1.0f, 1.0f, 0.1f});
    if (f.last < f.first) continue;
    const bool better = type == ObjectType::Hurdle ? f.clip_height > best : f.clip_height < best;
    if (better) best = f.clip_height, best_z = z;
  }
  return best_z;
}

// m: how far the trunk's and head's capsules reach in front of the root, along its facing, in a pose.
float trunk_front(const MotionSet& set, const BodyVolumes& volumes, const Pose& pose) {
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  std::vector<PlacedCapsule> placed;
  forward_kinematics(*set.skeleton, pose, positions, &rotations);
  volumes.place(positions, rotations, placed);
  const glm::vec2 origin = floor_xz(pose.root_position), fwd = forward_of(heading_of(pose.rotations[0]));
  float front = 0.0f;
  for (size_t k = 0; k < placed.size(); ++k) {
    const BodyPart part = volumes.capsules()[k].part;
    if (part != BodyPart::Trunk && part != BodyPart::Head) continue;
    for (const glm::vec3& end : {placed[k].a, placed[k].b})
      front = std::max(front, glm::dot(floor_xz(end) - origin, fwd) + placed[k].radius);
  }
  return front;
}

// The strike of a kick or punch (TargetMotion::strike_frame): between T_t and the effector's farthest reach
// (`peak_frame`), the frame at which it moves forward fastest, where a strike meets its target. For a kick
// the ball's centre is then placed where the kicking foot's capsules just touch a ball of kBallDiameter
// (forward of the toe tip along the foot's travel on the floor); for a punch the point is the wrist.
struct Strike {
  int frame = -1;
  glm::vec2 target{0.0f};  // the ball's centre (kick) or the wrist (punch), clip coordinates on the floor
  float speed = 0.0f;      // m/s: the effector's speed over the floor there
};

Strike strike_of(const MotionSet& set, const BodyVolumes& volumes, const MotionClip& mc, TargetAction action, int peak_frame) {
  Strike s;
  const bool kick = action == TargetAction::Kick;
  if (peak_frame < 0 || !(kick || action == TargetAction::PunchLeft || action == TargetAction::PunchRight)) return s;
  const Clip& clip = mc.clip;
  const Skeleton& skeleton = *set.skeleton;
  const int t_t = std::clamp(mc.target_frame, 0, clip.frame_count() - 1);
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  // The effector: the toe tip that reaches farthest at the peak (kick), the punching wrist.
  auto effector_at = [&](int frame, int side) {
    forward_kinematics(skeleton, clip.frames[static_cast<size_t>(frame)], positions, &rotations);
    if (!kick) return positions[static_cast<size_t>(set.body.arms[static_cast<size_t>(side)].wrist)];
    const int tip = set.body.legs[static_cast<size_t>(side)].toe_tip_joint;
    return skeleton.joints[static_cast<size_t>(tip)].has_end_site ? end_site_position(skeleton, tip, positions, rotations)
                                                                  : positions[static_cast<size_t>(tip)];
  };
  const Pose& ref = clip.frames[static_cast<size_t>(t_t)];
  const glm::vec2 fwd = forward_of(heading_of(ref.rotations[0]));
  int side = action == TargetAction::PunchLeft ? kLeft : kRight;
  if (kick) {
    float best = -std::numeric_limits<float>::infinity();
    for (int k : {kLeft, kRight}) {
      if (set.body.legs[static_cast<size_t>(k)].toe_tip_joint < 0) continue;
      const float ahead = glm::dot(floor_xz(effector_at(peak_frame, k)), fwd);
      if (ahead > best) best = ahead, side = k;
    }
  }
  float fastest = -1.0f;
  for (int f = std::max(t_t, 1); f <= peak_frame; ++f) {
    const glm::vec2 step = floor_xz(effector_at(f, side)) - floor_xz(effector_at(f - 1, side));
    const float v = glm::dot(step, fwd) * clip.fps;
    if (v > fastest) fastest = v, s.frame = f, s.speed = glm::length(step) * clip.fps;
  }
  if (s.frame < 0) return s;
  const glm::vec3 tip = effector_at(s.frame, side);
  s.target = floor_xz(tip);
  if (!kick) return s;
  // The ball: slid forward from the toe tip until the foot's capsules (ankle to toe tip) just touch it.
  const glm::vec3 travel3 = tip - effector_at(s.frame - 1, side);
  glm::vec2 travel = floor_xz(travel3);
  travel = glm::length(travel) > 1e-6f ? glm::normalize(travel) : fwd;
  effector_at(s.frame, side);  // FK of the strike frame again (effector_at(s.frame - 1) replaced it)
  std::vector<PlacedCapsule> placed;
  volumes.place(positions, rotations, placed);
  const BodyPart foot = side == kLeft ? BodyPart::LeftFoot : BodyPart::RightFoot;
  const float r = 0.5f * kBallDiameter;
  auto gap = [&](float slide) {  // the foot's nearest capsule to a ball slid this far along the travel
    const glm::vec2 c = floor_xz(tip) + slide * travel;
    const glm::vec3 centre(c.x, r, c.y);
    float g = std::numeric_limits<float>::infinity();
    for (size_t k = 0; k < placed.size(); ++k)
      if (volumes.capsules()[k].part == foot)
        g = std::min(g, segment_segment_distance(placed[k].a, placed[k].b, centre, centre) - placed[k].radius - r);
    return g;
  };
  float lo = -0.3f, hi = 0.6f;  // the gap grows with the slide here: bisect for the touching slide
  for (int k = 0; k < 40; ++k) {
    const float mid = 0.5f * (lo + hi);
    (gap(mid) < 0.0f ? lo : hi) = mid;
  }
  s.target = floor_xz(tip) + hi * travel;
  return s;
}

constexpr float kReleaseClearance = 0.1f;    // m: every joint this far beyond the obstacle's far side
constexpr float kReleaseAfterStrike = 0.2f;  // s after a strike's farthest reach (the hand or foot returning)
constexpr float kRailHalfDepth = 0.05f;      // m: half the depth of an obstacle's rail (scenario objects' 0.1)

// TargetMotion::release_frame. Obstacles (a bar, beam or hurdle is crossed along the T_p facing): the first
// frame after T_t at which every joint lies beyond the obstacle's far side by kReleaseClearance; the far side
// is the built-in clip's own obstacle, else the interaction point plus a rail's half depth. Strikes:
// kReleaseAfterStrike after the effector's farthest reach.
int release_frame_of(const MotionSet& set, const MotionClip& mc, TargetAction action, int reference_frame,
                     glm::vec2 interaction, int peak_frame) {
  const Clip& clip = mc.clip;
  const int t_t = std::clamp(mc.target_frame, 0, clip.frame_count() - 1);
  if (action == TargetAction::Kick || action == TargetAction::PunchLeft || action == TargetAction::PunchRight) {
    if (peak_frame < 0) return -1;
    const int f = peak_frame + static_cast<int>(std::lround(kReleaseAfterStrike * clip.fps));
    return f < clip.frame_count() ? f : -1;
  }
  const Pose& ref = clip.frames[static_cast<size_t>(reference_frame)];
  const glm::vec2 origin = floor_xz(ref.root_position);
  const glm::vec2 fwd = forward_of(heading_of(ref.rotations[0]));
  float far_side = glm::dot(interaction - origin, fwd) + kRailHalfDepth;
  if (set.name == "builtin") {
    const library::Obstacle o = library::obstacle_of(clip.name);
    if (o.height > 0.0f) far_side = glm::dot(glm::vec2(0.0f, o.z_far) - origin, fwd);
  }
  std::vector<glm::vec3> positions;
  for (int f = t_t; f < clip.frame_count(); ++f) {
    forward_kinematics(*set.skeleton, clip.frames[static_cast<size_t>(f)], positions);
    bool beyond = true;
    for (const glm::vec3& p : positions) beyond = beyond && glm::dot(floor_xz(p) - origin, fwd) > far_side + kReleaseClearance;
    if (beyond) return f;
  }
  return -1;
}

}  // namespace

std::shared_ptr<const MotionSet> load_scenario_motions(const Scenario& scenario, const Params& params) {
  if (scenario.motions == "builtin") return std::make_shared<const MotionSet>(make_builtin_motion_set(params));
  const std::string path = scenario.motions.front() == '/' ? scenario.motions : source_dir() + "/" + scenario.motions;
  return std::make_shared<const MotionSet>(load_motion_set(path, params));
}

bool same_world_assets_params(const Params& a, const Params& b) {
  const nlohmann::json ja = nlohmann::json::parse(params_to_json(a)), jb = nlohmann::json::parse(params_to_json(b));
  for (const char* section : {"contacts", "graph", "reference", "quantization"})
    if (ja.value(section, nlohmann::json()) != jb.value(section, nlohmann::json())) return false;
  return true;
}

Params load_scenario_params(const Scenario& scenario) {
  return scenario.params_file.empty() ? Params{} : load_params(scenario.params_file);
}

std::shared_ptr<const WorldAssets> prepare_world_assets(const Scenario& scenario, const Params& params,
                                                        const std::string& cache_dir, bool* trained) {
  auto assets = std::make_shared<WorldAssets>(make_world_assets(load_scenario_motions(scenario, params), params));
  assets->policy = load_or_train_policy(*assets->set, *assets->graph, params, cache_dir, {}, trained);
  return assets;
}

WorldAssets make_world_assets(std::shared_ptr<const MotionSet> set, const Params& params) {
  WorldAssets a;
  a.params = params;
  a.set = set;
  a.graph = std::make_shared<const MotionGraph>(MotionGraph::build(*set, params.graph));
  a.synthesizer = std::make_shared<const Synthesizer>(*set, params);
  const std::string source = set->manifest_path.empty() ? set->name : set->manifest_path;

  for (const MotionClip* c : core_clips(*set, params.quantization)) a.core_nodes.push_back(static_cast<int>(c - set->clips.data()));
  a.idle_node = find_cyclic_clip(*set, Role::Idle);
  if (a.idle_node < 0) a.idle_node = find_cyclic_clip(*set, Role::Walk);
  if (a.idle_node < 0) throw InputError(source, "the motion set has neither a cyclic idle nor a cyclic walk clip");

  a.targets.resize(kTargetActionCount);
  a.sweeps.resize(kTargetActionCount);
  a.body_reaches.resize(kTargetActionCount);
  a.volumes = std::make_shared<const BodyVolumes>(*set->skeleton);
  std::vector<int> ankles;
  for (const LegChain& leg : set->body.legs)
    if (leg.ankle >= 0) ankles.push_back(leg.ankle);
  a.foot_segments = segments_moved_by_turning(*set->skeleton, set->mass, ankles);
  const BodyVolumes& volumes = *a.volumes;
  for (int k = 0; k < kTargetActionCount; ++k) {
    TargetMotion& t = a.targets[static_cast<size_t>(k)];
    t.action = static_cast<TargetAction>(k);
    const auto role = role_of(t.action);
    for (size_t i = 0; i < set->clips.size() && t.clip < 0; ++i)
      if (role && set->clips[i].role == *role && set->clips[i].target_frame >= 0) t.clip = static_cast<int>(i);
    if (t.clip < 0) continue;
    const MotionClip& mc = set->clips[static_cast<size_t>(t.clip)];
    t.reference_frame = find_reference_posture(*set, t.clip, params).frame;  // Sec. 4.2
    t.reference = mc.clip.frames[static_cast<size_t>(t.reference_frame)];
    const glm::vec2 origin = floor_xz(t.reference.root_position);
    const float h = heading_of(t.reference.rotations[0]);
    int peak_frame = -1;
    glm::vec2 meets = interaction_point(*set, mc, t.action, t.reference_frame, &peak_frame);
    const bool across = t.action == TargetAction::Crawl || t.action == TargetAction::Duck || t.action == TargetAction::Jump;
    if (across) {
      a.sweeps[static_cast<size_t>(k)] = sweep_clip(*set, volumes, t.clip, t.reference_frame);
      // A recorded obstacle clip was not made for a known obstacle: it meets its obstacle where its body
      // passes it best (obstacle_fit.h's sweep): the highest board it clears, the lowest rail it passes.
      const bool designed = set->name == "builtin" && library::obstacle_of(mc.clip.name).height > 0.0f;
      if (!designed) meets = origin + best_crossing(a.sweeps[static_cast<size_t>(k)], t) * forward_of(h);
    }
    const glm::vec2 q = meets - origin;
    t.reach = glm::dot(q, forward_of(h));
    t.lateral = glm::dot(q, left_of(h));
    t.release_frame = release_frame_of(*set, mc, t.action, t.reference_frame, meets, peak_frame);
    if (t.release_frame >= 0)
      t.release_advance = glm::dot(floor_xz(mc.clip.frames[static_cast<size_t>(t.release_frame)].root_position) - origin, forward_of(h));
    const Strike strike = strike_of(*set, volumes, mc, t.action, peak_frame);
    if (strike.frame >= 0) {
      t.strike_frame = strike.frame;
      t.strike_speed = strike.speed;
      if (t.action == TargetAction::Kick) {  // the ball is met where the foot touches it, not at the toe's farthest reach
        t.reach = glm::dot(strike.target - origin, forward_of(h));
        t.lateral = glm::dot(strike.target - origin, left_of(h));
      } else {
        // A punch meets the front of the target's body, not its root: the reach grows by how far the trunk
        // stands out in front of the root in the prepared posture (the target is prepared too). Two
        // characters that far apart keep their guards clear of each other until the strike.
        t.reach += trunk_front(*set, volumes, t.reference);
      }
    }
    // Late entries reach to T_t, and for an obstacle clip on to where the body nears the obstacle (its fit
    // fading in): a character already nearer than the launch point enters the clip as far on as it is.
    int last_entry = std::max(t.reference_frame, mc.target_frame);
    if (!a.sweeps[static_cast<size_t>(k)].frames.empty()) {
      const ObjectType type = t.action == TargetAction::Crawl ? ObjectType::Bar
                              : t.action == TargetAction::Duck ? ObjectType::Beam
                                                                : ObjectType::Hurdle;
      const ObstacleFit near = fit_obstacle(a.sweeps[static_cast<size_t>(k)], t, type, {1.0f, 1.0f, kDefaultRail});
      if (near.last >= near.first)
        last_entry = std::max(last_entry, near.first - static_cast<int>(std::lround(near.ramp_frames)));
    }
    t.last_entry_frame = last_entry;
    if (!a.sweeps[static_cast<size_t>(k)].frames.empty())
      a.body_reaches[static_cast<size_t>(k)] = body_reach(a.sweeps[static_cast<size_t>(k)], t.release_frame);
    for (int f = t.reference_frame; f <= last_entry; ++f)
      t.advance.push_back(glm::dot(floor_xz(mc.clip.frames[static_cast<size_t>(f)].root_position) - origin, forward_of(h)));
  }
  return a;
}

int TargetMotion::entry_frame(float past_launch_point) const {
  for (size_t k = 0; k < advance.size(); ++k)
    if (advance[k] >= past_launch_point) return reference_frame + static_cast<int>(k);
  return reference_frame + static_cast<int>(advance.size()) - 1;  // last_entry_frame at the latest
}

}  // namespace prep
