#include "engine/library/action.h"

#include <algorithm>
#include <cmath>

#include "engine/library/angles.h"
#include "engine/library/rig.h"
#include "engine/library/spline.h"

namespace prep::library {
namespace {
constexpr float kGravity = 9.81f;
constexpr float kLegHandover = 0.35f;  // s over which the legs pass from the walk to the keys and back
}  // namespace

Walker walk_in(const ActionSpec& spec) { return Walker(spec.gait, 0.0f, {0.0f, 0.0f}, 0.0f); }

Walker walk_out(const ActionSpec& spec) { return Walker(spec.gait, spec.resume_phase, spec.resume_origin, 0.0f); }

DofPose standing_pose(glm::vec2 xz, float root_height) {
  DofPose d;
  d[kRootX] = xz.x;
  d[kRootY] = root_height;
  d[kRootZ] = xz.y;
  d[kPelvisTilt] = 6 * kDeg;
  d[kSpineFlex] = -4 * kDeg;
  d[kHeadFlex] = 3 * kDeg;
  for (int side = 0; side < 2; ++side) {
    d.at(side, kShoulderAbduct) = 7 * kDeg;
    d.at(side, kShoulderFlex) = 3 * kDeg;
    d.at(side, kShoulderTwist) = 10 * kDeg;
    d.at(side, kElbowFlex) = 14 * kDeg;
    d.at(side, kWristFlex) = 5 * kDeg;
    d.at(side, kHipFlex) = 4 * kDeg;
    d.at(side, kKneeFlex) = 4 * kDeg;
    d.at(side, kHipRotation) = 2 * kDeg;
  }
  return d;
}

GeneratedClip compose_action(const ActionSpec& spec) {
  const Walker in = walk_in(spec), out = walk_out(spec);
  const float fps = spec.gait.fps;
  // Keys: the join, the action, the hand-over to the walk-out, each end with the walk's own velocity.
  std::vector<PoseKey> keys;
  keys.push_back({0.0f, in.pose(0.0f), true, in.velocity(0.0f)});
  for (const PoseKey& k : spec.keys) keys.push_back(k);
  keys.push_back({spec.resume_time, out.pose(0.0f), true, out.velocity(0.0f)});
  // Ballistic root between the flight keys: exact positions and gravity-consistent velocities at both ends.
  const bool flight = spec.flight_from >= 0.0f && spec.flight_to > spec.flight_from;
  glm::vec3 p0{0.0f}, v0{0.0f};
  if (flight) {
    auto find = [&](float t) -> PoseKey& {
      for (PoseKey& k : keys)
        if (std::fabs(k.t - t) < 1e-4f) return k;
      return keys.front();
    };
    PoseKey& a = find(spec.flight_from);
    PoseKey& b = find(spec.flight_to);
    const float T = spec.flight_to - spec.flight_from;
    p0 = {a.pose[kRootX], a.pose[kRootY], a.pose[kRootZ]};
    const glm::vec3 p1{b.pose[kRootX], b.pose[kRootY], b.pose[kRootZ]};
    v0 = (p1 - p0) / T + glm::vec3(0.0f, 0.5f * kGravity * T, 0.0f);
    const glm::vec3 v1 = v0 - glm::vec3(0.0f, kGravity * T, 0.0f);
    for (PoseKey* k : {&a, &b}) {
      if (!k->has_velocity) {  // Catmull-Rom slopes for every other entry
        const size_t i = static_cast<size_t>(k - keys.data());
        k->velocity = (keys[std::min(i + 1, keys.size() - 1)].pose - keys[i > 0 ? i - 1 : 0].pose) *
                      (1.0f / (keys[std::min(i + 1, keys.size() - 1)].t - keys[i > 0 ? i - 1 : 0].t));
        k->has_velocity = true;
      }
      const glm::vec3 v = k == &a ? v0 : v1;
      k->velocity[kRootX] = v.x;
      k->velocity[kRootY] = v.y;
      k->velocity[kRootZ] = v.z;
    }
  }
  Draft draft;
  draft.name = spec.name;
  draft.fps = fps;
  // Generated with a gait cycle of padding at both ends (cropped at the end), so that the supports
  // running over the clip's first and last frames roll exactly as in the walk.
  const float pad = spec.gait.cycle_s;
  const float t_begin = -spec.walk_in_s - pad, t_end = spec.resume_time + spec.walk_out_s + pad;
  const int count = static_cast<int>(std::lround((t_end - t_begin) * fps)) + 1;
  for (int f = 0; f < count; ++f) {
    const float t = t_begin + static_cast<float>(f) / fps;
    DofPose d = t < 0.0f ? in.pose(t) : (t > spec.resume_time ? out.pose(t - spec.resume_time) : sample_keys(keys, t));
    // Near the joins the legs keep walking a little longer (the trailing foot rolls off, the leading foot
    // comes down as in the walk), handing over to the keyed legs smoothly.
    if (t >= 0.0f && t <= spec.resume_time) {
      const float to_action = smooth5(t / kLegHandover);
      const float to_walk = smooth5((t - (spec.resume_time - kLegHandover)) / kLegHandover);
      const DofPose walk_legs = to_walk > 0.0f ? out.pose(t - spec.resume_time) : in.pose(t);
      const float keyed = to_walk > 0.0f ? 1.0f - to_walk : to_action;
      for (int side = 0; side < 2; ++side)
        for (SideDof j : {kHipFlex, kHipAbduct, kHipRotation, kKneeFlex, kAnkleDorsi, kToeExtension})
          d.at(side, j) = keyed * d.at(side, j) + (1.0f - keyed) * walk_legs.at(side, j);
    }
    if (flight && t > spec.flight_from && t < spec.flight_to) {
      const float s = t - spec.flight_from;
      const glm::vec3 p = p0 + v0 * s - glm::vec3(0.0f, 0.5f * kGravity * s * s, 0.0f);
      d[kRootX] = p.x;
      d[kRootY] = p.y;
      d[kRootZ] = p.z;
    }
    draft.frames.push_back(d);
  }
  const auto frame_of = [&](float t) { return static_cast<int>(std::lround((t - t_begin) * fps)); };
  for (int side = 0; side < 2; ++side) {
    std::vector<Support>& feet = draft.feet[static_cast<size_t>(side)];
    for (Support s : in.supports(side, t_begin, 0.0f, t_begin))
      if (s.first <= frame_of(0.0f)) feet.push_back(s);
    for (Support s : out.supports(side, 0.0f, spec.walk_out_s, t_begin - spec.resume_time))
      if (s.last >= frame_of(spec.resume_time)) feet.push_back(s);
    for (int limb = 0; limb < 2; ++limb) {
      const auto& specs = limb == 0 ? spec.feet[static_cast<size_t>(side)] : spec.hands[static_cast<size_t>(side)];
      std::vector<Support>& target = limb == 0 ? feet : draft.hands[static_cast<size_t>(side)];
      for (const SupportSpec& ss : specs) {
        Support s;
        s.first = frame_of(ss.on);
        s.last = frame_of(ss.off);
        s.hold = ss.hold;
        s.explicit_anchor = ss.explicit_anchor;
        s.anchor_xz = ss.anchor_xz;
        s.anchor_yaw = ss.anchor_yaw;
        s.lift_before = ss.lift_before;
        target.push_back(s);
      }
      merge_supports(target);
    }
  }
  GeneratedClip g;
  const int pad_frames = static_cast<int>(std::lround(pad * fps));
  g.clip = crop(realize(draft, &g.report), pad_frames, count - 2 * pad_frames);
  g.role = spec.role;
  g.cyclic = false;
  g.target_frame = frame_of(spec.target_time) - pad_frames;
  return g;
}

}  // namespace prep::library
