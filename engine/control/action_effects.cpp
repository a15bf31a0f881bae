#include "engine/control/action_effects.h"

#include <cmath>

#include "engine/synthesis/blending.h"
#include "engine/synthesis/trajectory.h"
#include "engine/util/error.h"

namespace prep {
namespace {

constexpr float kPi = 3.14159265358979323846f;

float wrap_angle(float a) {
  while (a > kPi) a -= 2.0f * kPi;
  while (a <= -kPi) a += 2.0f * kPi;
  return a;
}

// Replays frames [first, last] of the clip through Eq. 3-4 and measures the travel in the frame of the
// heading at `first`.
ActionEffect half_cycle(const Clip& clip, int first, int last, float w_root) {
  glm::vec2 p(0.0f);
  float turn = 0.0f;
  for (int k = first; k < last; ++k) {
    const Pose& a = clip.frames[static_cast<size_t>(k)];
    const Pose& b = clip.frames[static_cast<size_t>(k + 1)];
    p = advance_root(p, b.root_position - a.root_position, w_root);  // Eq. 3-4
    turn += wrap_angle(heading_of(b.rotations[0]) - heading_of(a.rotations[0]));
  }
  const float h = heading_of(clip.frames[static_cast<size_t>(first)].rotations[0]);
  ActionEffect e;
  e.forward = p.x * std::sin(h) + p.y * std::cos(h);
  e.left = p.x * std::cos(h) - p.y * std::sin(h);
  e.turn = turn;
  e.duration = static_cast<float>(last - first) / clip.fps;
  return e;
}

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

}  // namespace

float RootCurve::weight(float alpha) const { return linear ? alpha : blend_weight(alpha, C, c); }  // Eq. 1

RootCurve root_curve(const MotionSet& set, const BlendParams& blend) {
  const BlendCurves curves = make_blend_curves(*set.skeleton, set.body, blend);
  RootCurve r;
  r.C = curves.C[static_cast<size_t>(curves.root)];
  r.c = curves.c[static_cast<size_t>(curves.root)];
  r.linear = curves.linear;
  return r;
}

ActionEffect footstep_effect(const MotionClip& clip, float w_root, const std::string& source_name) {
  const int n = clip.clip.frame_count();
  if (!clip.cyclic || clip.loop_first < 0 || clip.loop_last >= n || clip.loop_last - clip.loop_first < 2 ||
      clip.clip.fps <= 0.0f)
    throw InputError(source_name, "core motion '" + clip.clip.name +
                                      "' needs a loop range of at least 2 frames to give an action's effect");
  if (clip.clip.skeleton == nullptr) throw InputError(source_name, "core motion '" + clip.clip.name + "' has no skeleton");
  const int steps = footsteps_in_loop(clip);
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
  e.cos_turn = std::cos(e.turn);
  e.sin_turn = std::sin(e.turn);
  return e;
}

ActionTable tabulate_action_effects(const std::vector<const MotionClip*>& core, const RootCurve& curve,
                                    int alpha_levels, float alpha_step, const std::string& source_name) {
  ActionTable t;
  t.motions = static_cast<int>(core.size());
  t.alpha_levels = alpha_levels;
  t.curve = curve;
  for (const MotionClip* clip : core) {
    t.motion_names.push_back(clip->clip.name);
    t.motion_roles.push_back(role_name(clip->role));
    for (int l = 0; l < alpha_levels; ++l)
      t.effects.push_back(footstep_effect(*clip, curve.weight(static_cast<float>(l) * alpha_step), source_name));
  }
  return t;
}

std::vector<const MotionClip*> core_clips(const MotionSet& set, const QuantizationParams& q) {
  const std::string source = set.manifest_path.empty() ? set.name : set.manifest_path;
  std::vector<const MotionClip*> out;
  for (const std::string& name : q.core_roles) {
    const std::optional<Role> role = parse_role(name);
    if (!role) throw InputError(source, "quantization.core_roles: unknown role '" + name + "'");
    if (!is_locomotion(*role))
      throw InputError(source, "quantization.core_roles: '" + name + "' is not a locomotion (core) role");
    const MotionClip* found = nullptr;
    for (const MotionClip& c : set.clips)
      if (c.role == *role) {
        found = &c;
        break;
      }
    if (found == nullptr) throw InputError(source, "no clip with role '" + name + "' for the controller's core motions");
    out.push_back(found);
  }
  return out;
}

ActionTable tabulate_action_effects(const MotionSet& set, const Params& params) {
  const std::string source = set.manifest_path.empty() ? set.name : set.manifest_path;
  return tabulate_action_effects(core_clips(set, params.quantization), root_curve(set, params.blend),
                                 params.quantization.alpha_levels, params.quantization.alpha_step, source);
}

}  // namespace prep
