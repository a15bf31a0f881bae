#include "engine/control/action_effects.h"

#include <algorithm>
#include <cmath>

#include "engine/control/angles.h"
#include "engine/synthesis/blending.h"
#include "engine/synthesis/trajectory.h"
#include "engine/util/error.h"

namespace prep {
namespace {

using control_angles::kPi;

float wrap_angle(float a) {
  while (a > kPi) a -= 2.0f * kPi;
  while (a <= -kPi) a += 2.0f * kPi;
  return a;
}

// Replays frames [first, last] of the clip through Eq. 3-4 and measures the travel in the character's frame
// at `first`. That frame is the heading of the travel, not the root's yaw of that frame: the pelvis sways
// a few degrees either way within a gait cycle, and an action that starts and ends at the same phase of
// the sway would otherwise carry it as a sideways drift (0.1 m per cycle of the built-in walk). So the
// heading is the least-squares line through the root's (unwrapped) yaw over the frames, taken at `first`.
ActionEffect half_cycle(const Clip& clip, int first, int last, float w_root) {
  glm::vec2 p(0.0f);
  float turn = 0.0f;
  double sum_t = 0, sum_h = 0, sum_tt = 0, sum_th = 0;
  const auto add = [&](int k, float h) {
    const double t = k - first;
    sum_t += t, sum_h += h, sum_tt += t * t, sum_th += t * h;
  };
  add(first, 0.0f);
  for (int k = first; k < last; ++k) {
    const Pose& a = clip.frames[static_cast<size_t>(k)];
    const Pose& b = clip.frames[static_cast<size_t>(k + 1)];
    p = advance_root(p, b.root_position - a.root_position, w_root);  // Eq. 3-4
    turn += wrap_angle(heading_of(b.rotations[0]) - heading_of(a.rotations[0]));
    add(k + 1, turn);
  }
  const double n = last - first + 1, det = n * sum_tt - sum_t * sum_t;
  const double slope = det > 0 ? (n * sum_th - sum_t * sum_h) / det : 0.0;
  const float offset = static_cast<float>((sum_h - slope * sum_t) / n);  // the line at `first`
  const float h = heading_of(clip.frames[static_cast<size_t>(first)].rotations[0]) + offset;
  ActionEffect e;
  e.forward = p.x * std::sin(h) + p.y * std::cos(h);
  e.left = p.x * std::cos(h) - p.y * std::sin(h);
  e.turn = turn;
  e.duration = static_cast<float>(last - first) / clip.fps;
  return e;
}

}  // namespace

// Footsteps in the loop: two per gait cycle, and a gait cycle per touchdown (a foot entering contact) of
// the foot that touches down most often in the loop's frames (so one touchdown missed by the contact
// detector on the other foot does not matter). Clips without contacts, or standing ones, count as one
// gait cycle.
int footsteps_in_loop(const MotionClip& clip) {
  if (static_cast<int>(clip.contacts.size()) != clip.clip.frame_count()) return 2;
  int cycles = 1;
  for (int f = 0; f < 2; ++f) {
    int touchdowns = 0;
    for (int k = clip.loop_first + 1; k <= clip.loop_last; ++k)
      if (clip.contacts[static_cast<size_t>(k)][static_cast<size_t>(f)].any() &&
          !clip.contacts[static_cast<size_t>(k - 1)][static_cast<size_t>(f)].any())
        ++touchdowns;
    cycles = touchdowns > cycles ? touchdowns : cycles;
  }
  return 2 * cycles;
}

float RootCurve::weight(float alpha) const { return linear ? alpha : blend_weight(alpha, C, c); }  // Eq. 1

RootCurve root_curve(const MotionSet& set, const BlendParams& blend) {
  const BlendCurves curves = make_blend_curves(*set.skeleton, set.body, blend);
  RootCurve r;
  r.C = curves.C[static_cast<size_t>(curves.root)];
  r.c = curves.c[static_cast<size_t>(curves.root)];
  r.linear = curves.linear;
  return r;
}

ActionEffect action_effect(const MotionClip& clip, float w_root, int footsteps, const std::string& source_name) {
  const int n = clip.clip.frame_count();
  if (!clip.cyclic || clip.loop_first < 0 || clip.loop_last >= n || clip.loop_last - clip.loop_first < 2 ||
      clip.clip.fps <= 0.0f)
    throw InputError(source_name, "core motion '" + clip.clip.name +
                                      "' needs a loop range of at least 2 frames to give an action's effect");
  if (clip.clip.skeleton == nullptr) throw InputError(source_name, "core motion '" + clip.clip.name + "' has no skeleton");
  // The loop's footsteps grouped into actions of `footsteps` each (a loop shorter than one action is one).
  const int steps = std::max(1, footsteps_in_loop(clip) / std::max(1, footsteps));
  const int span = clip.loop_last - clip.loop_first;
  ActionEffect e;
  for (int k = 0; k < steps; ++k) {
    const ActionEffect part = half_cycle(clip.clip, clip.loop_first + span * k / steps,
                                         clip.loop_first + span * (k + 1) / steps, w_root);
    e.forward += part.forward / static_cast<float>(steps);
    e.left += part.left / static_cast<float>(steps);
    e.turn += part.turn / static_cast<float>(steps);
    e.duration += part.duration / static_cast<float>(steps);
  }
  e.precompute();
  return e;
}

void ActionEffect::precompute() {
  cos_turn = std::cos(turn);
  sin_turn = std::sin(turn);
  const float chord2 = forward * forward + left * left;
  inv_chord2 = chord2 > 1e-12f ? 1.0f / chord2 : 0.0f;
}

ActionTable tabulate_action_effects(const std::vector<const MotionClip*>& core, const RootCurve& curve,
                                    int alpha_levels, float alpha_step, int footsteps_per_action,
                                    const std::string& source_name) {
  ActionTable t;
  t.motions = static_cast<int>(core.size());
  t.alpha_levels = alpha_levels;
  t.curve = curve;
  for (const MotionClip* clip : core) {
    t.motion_names.push_back(clip->clip.name);
    t.motion_roles.push_back(role_name(clip->role));
    for (int l = 0; l < alpha_levels; ++l)
      t.effects.push_back(
          action_effect(*clip, curve.weight(static_cast<float>(l) * alpha_step), footsteps_per_action, source_name));
  }
  return t;
}

float loop_speed(const MotionClip& clip) {
  const glm::vec3 a = clip.clip.frames[static_cast<size_t>(clip.loop_first)].root_position;
  const glm::vec3 b = clip.clip.frames[static_cast<size_t>(clip.loop_last)].root_position;
  const float seconds = static_cast<float>(clip.loop_last - clip.loop_first) / clip.clip.fps;
  return seconds > 0.0f ? glm::length(glm::vec2(b.x - a.x, b.z - a.z)) / seconds : 0.0f;
}

std::vector<const MotionClip*> default_core_clips(const MotionSet& set) {
  const std::string source = set.manifest_path.empty() ? set.name : set.manifest_path;
  auto first_cyclic = [&](Role role) -> const MotionClip* {
    for (const MotionClip& c : set.clips)
      if (c.role == role && c.cyclic) return &c;
    return nullptr;
  };
  std::vector<const MotionClip*> out;
  for (Role role : {Role::Walk, Role::TurnLeft, Role::TurnRight}) {
    const MotionClip* c = first_cyclic(role);
    if (c == nullptr)
      throw InputError(source, std::string("the controller's core motions need a cyclic '") + role_name(role) +
                                   "' clip (a loop range; a turn can be a walk steered with steer_deg_per_s)");
    out.push_back(c);
  }
  // The slow walk: the slowest other cyclic walk, when it is clearly slower than the walk.
  const MotionClip* slow = nullptr;
  const float walk_speed = loop_speed(*out.front());
  for (const MotionClip& c : set.clips)
    if (c.role == Role::Walk && c.cyclic && &c != out.front() && loop_speed(c) <= kSlowWalkRatio * walk_speed &&
        (slow == nullptr || loop_speed(c) < loop_speed(*slow)))
      slow = &c;
  if (slow != nullptr) out.push_back(slow);
  return out;
}

std::vector<const MotionClip*> core_clips(const MotionSet& set, const QuantizationParams& q) {
  if (q.core_roles.empty()) return default_core_clips(set);
  const std::string source = set.manifest_path.empty() ? set.name : set.manifest_path;
  std::vector<const MotionClip*> out;
  for (const std::string& name : q.core_roles) {
    const MotionClip* found = nullptr;
    if (const std::optional<Role> role = parse_role(name)) {
      if (!is_locomotion(*role))
        throw InputError(source, "quantization.core_roles: '" + name + "' is not a locomotion (core) role");
      for (const MotionClip& c : set.clips)
        if (c.role == *role && c.cyclic) {
          found = &c;
          break;
        }
      if (found == nullptr)
        throw InputError(source, "no cyclic clip with role '" + name + "' for the controller's core motions");
    } else {
      for (const MotionClip& c : set.clips)
        if (c.clip.name == name) found = &c;
      if (found == nullptr)
        throw InputError(source, "quantization.core_roles: '" + name + "' is neither a role nor a clip of the set");
      if (!is_locomotion(found->role) || !found->cyclic)
        throw InputError(source, "quantization.core_roles: clip '" + name + "' is not a cyclic locomotion clip");
    }
    if (std::find(out.begin(), out.end(), found) != out.end())
      throw InputError(source, "quantization.core_roles: clip '" + found->clip.name + "' is named twice");
    out.push_back(found);
  }
  return out;
}

ActionTable tabulate_action_effects(const MotionSet& set, const Params& params) {
  const std::string source = set.manifest_path.empty() ? set.name : set.manifest_path;
  return tabulate_action_effects(core_clips(set, params.quantization), root_curve(set, params.blend),
                                 params.quantization.alpha_levels, params.quantization.alpha_step,
                                 params.quantization.footsteps_per_action, source);
}

}  // namespace prep
