// Bodies kept clear of what they meet (clearance.h measures it): an obstacle clip's pose fitted to its
// obstacle (obstacle_fit.h), bodies set back out of obstacles they are not crossing, characters kept apart,
// and a defeated opponent stepping out of the way.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "engine/control/arrival.h"
#include "engine/motion/kinematics.h"
#include "engine/synthesis/foot_ik.h"
#include "engine/world/clearance.h"
#include "engine/world/floor.h"
#include "engine/world/world.h"
#include "engine/world/world_runtime.h"

namespace prep {

using floor_plane::floor_xz;
using floor_plane::crossing_direction;
using floor_plane::forward_of;
using floor_plane::is_across;

namespace {

// f(i, j, d, distance) for every two characters i < j whose roots are nearer than `within` on the floor
// (d from i's root to j's), as they stand when the pair comes up.
template <class F>
void for_each_pair_within(const std::vector<WorldCharacter>& characters, float within, F&& f) {
  for (size_t i = 0; i < characters.size(); ++i)
    for (size_t j = i + 1; j < characters.size(); ++j) {
      const glm::vec2 d = characters[j].position - characters[i].position;
      const float distance = glm::length(d);
      if (distance < within) f(i, j, d, distance);
    }
}

// How far a ball's solids reach from the vertical through its middle: its spheres' radii beyond their
// centres' distance from that line.
float ball_floor_reach(const std::vector<ObjectSolid>& solids) {
  float reach = 0.0f;
  for (const ObjectSolid& s : solids) {
    const float half_width = s.sphere ? 0.5f * s.extents.x : 0.5f * glm::length(glm::vec2(s.extents.x, s.extents.z));
    reach = std::max(reach, glm::length(glm::vec2(s.centre.x, s.centre.z)) + half_width);
  }
  return reach;
}

// Far beyond rounding (bodies and balls are metres across at most): a body this far out of a ball's
// reach has no capsule whose depth in it rounds above 0.
constexpr float kSurelyApart = 0.01f;

}  // namespace

// Characters keep their distance: two whose roots come closer than kPersonalSpace on the floor are set
// apart along the line between them, each by the share of the closing that is its own (closing_share; the
// one walking in is also turned aside as much). The whole character moves: its stream, synthesis state,
// planted feet and balance history, so the next frame carries on from there.
void World::keep_apart() {
  const size_t n = characters_.size();
  if (n < 2) return;
  std::vector<glm::vec2>& shove = shove_;  // kept between ticks: no allocation per tick
  shove.assign(n, glm::vec2(0.0f));
  for_each_pair_within(characters_, kFacingSpace, [&](size_t i, size_t j, glm::vec2 d, float distance) {
    const WorldCharacter& a = characters_[i];
    const WorldCharacter& b = characters_[j];
    const glm::vec2 dir = distance > 1e-4f ? d / distance : forward_of(a.heading);
    // A character's arms reach farther in front of it than to its sides or back (a guard, a fighting
    // stance turned side on, arms swinging as it walks): each one facing the other adds its half of the
    // extra room, so two squarely facing each other keep kFacingSpace apart.
    const float facing = std::clamp(glm::dot(forward_of(a.heading), dir), 0.0f, 1.0f) +
                         std::clamp(-glm::dot(forward_of(b.heading), dir), 0.0f, 1.0f);
    float space = kPersonalSpace + 0.5f * (kFacingSpace - kPersonalSpace) * facing;
    // One whose source is the other is let come as near as it needs to strike. Without preparation (the
    // naive baseline) nothing stops it short of its launch point, so it launches only there: it is let
    // come that near. Prepared, it arrives within its arrival radius of the launch point and strikes from
    // where it stands (update_arrival). A punch whose reach is so short (a motion set's jab) that the
    // facing space keeps its launch point out of that radius is let come to half the radius of it.
    auto striking_distance = [&](size_t index, size_t other) {
      const WorldCharacter& c = characters_[index];
      if (!c.has_source || c.source_character != static_cast<int>(other)) return kFacingSpace;
      const float reach = glm::length(c.source_object_position - c.source);
      if (!preparation_) return reach - kStrikeSlack;
      const float radius = arrival_->radius(runtime_[index]->source_closing_speed);
      return reach + radius < kFacingSpace ? reach + 0.5f * radius : kFacingSpace;
    };
    space = std::max(std::min({space, striking_distance(i, j), striking_distance(j, i)}), kPersonalSpace);
    if (distance >= space) return;
    const float share_a = closing_share(i, j, dir);
    const float gap = space - distance;
    // The one walking in is also turned aside, toward the side its way already leans to, so that it goes
    // round the other instead of pressing against it.
    const glm::vec2 across(-dir.y, dir.x);
    auto aside = [&](const glm::vec2& velocity) {
      const float lean = glm::dot(velocity, across);
      return (lean >= 0.0f ? 1.0f : -1.0f) * across;
    };
    shove[i] += share_a * gap * (-dir + aside(runtime_[i]->velocity));
    shove[j] += (1.0f - share_a) * gap * (dir + aside(runtime_[j]->velocity));
  });
  // At most a brisk step's pace per tick: a character pressed between two others is eased out over a few
  // ticks rather than thrown (the pushes of both would add up to a jump).
  const float most = kMaxShoveSpeed * params_.runtime.fixed_dt;
  for (size_t i = 0; i < n; ++i) {
    const float length = glm::length(shove[i]);
    displace(static_cast<int>(i), length > most ? shove[i] * (most / length) : shove[i]);
  }
}

// A punched opponent stops fighting and steps aside, out of the way its striker is going (to the side it
// already stands on, and a little back), then stands: left where it was hit, it would stand in the user's
// way, and a user walking on would be pressed between it and the next opponent. The way is the one the
// striker faces, unless the spot aside from it would stand on a waypoint or goal the striker has still to
// reach: a striker faces whom it punches, not its route, and bodies keep apart, so it could never come near
// enough to reach that point and would circle it. Then the way is toward the striker's next point.
void World::defeat(int opponent, int striker) {
  WorldCharacter& o = characters_[static_cast<size_t>(opponent)];
  const WorldCharacter& s = characters_[static_cast<size_t>(striker)];
  o.defeated = true;
  const auto aside_from = [&](glm::vec2 way) {
    glm::vec2 away = o.position - s.position;
    away = glm::length(away) > 1e-4f ? glm::normalize(away) : way;
    const glm::vec2 left(way.y, -way.x);  // floor_plane::left_of a heading facing `way`
    const glm::vec2 side = glm::dot(o.position - s.position, left) >= 0.0f ? left : -left;
    return o.position + kStepAside * glm::normalize(side + 0.5f * away);
  };
  // Nearer than this to a point the striker must reach, the opponent would keep it out of that point's radius.
  const float blocking = kPersonalSpace + params_.reward.goal_radius;
  const auto blocks_a_goal = [&](glm::vec2 spot) {
    for (const glm::vec2& g : s.goal)
      if (glm::length(g - spot) < blocking) return true;
    return false;
  };
  glm::vec2 spot = aside_from(forward_of(s.heading));
  const glm::vec2 to_next = s.goal.empty() ? glm::vec2(0.0f) : s.goal.front() - s.position;
  if (blocks_a_goal(spot) && glm::length(to_next) > 1e-4f) spot = aside_from(glm::normalize(to_next));
  o.goal = {spot};
}

int World::body_on_crossing(int index, int obstacle) const {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  const WorldObject& o = objects_[static_cast<size_t>(obstacle)];
  const BodyReach& body = assets_->body_reaches[static_cast<size_t>(o.spec.action)];
  const glm::vec2 object = floor_xz(o.position);
  const glm::vec2 n = crossing_direction(o.spec.heading, object, c.position);
  const glm::vec2 across(n.y, -n.x);
  const float to_line = glm::dot(object - c.position, n);
  // The clip's body sweeps body.half_width to either side of the character's line; a standing body reaches
  // kStandingRadius around its root.
  const float half_width = body.half_width + kStandingRadius;
  int nearest = -1;
  float nearest_along = std::numeric_limits<float>::infinity();
  for (size_t j = 0; j < characters_.size(); ++j) {
    const WorldCharacter& other = characters_[j];
    if (static_cast<int>(j) == index || other.in_target) continue;
    const glm::vec2 d = other.position - c.position;
    const float along = glm::dot(d, n);
    if (along <= 0.0f || along > to_line + kStandingRadius || std::fabs(glm::dot(d, across)) > half_width) continue;
    if (along < nearest_along) {
      nearest_along = along;
      nearest = static_cast<int>(j);
    }
  }
  return nearest;
}

bool World::clip_runs_into(int index, int obstacle) const {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  const Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const TargetMotion& t = assets_->target(c.playing);
  const ClipSweep& sweep = assets_->sweeps[static_cast<size_t>(c.playing)];
  const int now = rt.stream.clip_frame() - sweep.first_frame;
  const int frames = static_cast<int>(sweep.frames.size());
  if (now < 0 || now >= frames) return false;
  const int last = std::min(frames - 1, t.release_frame >= 0 ? t.release_frame - sweep.first_frame : frames - 1);
  // The sweep's frame: z along the clip's facing from where its T_p root would be, the root now on it.
  const glm::vec2 forward = forward_of(rt.launch_heading);
  const glm::vec2 origin = floor_xz(rt.stream.pose().root_position) - sweep.root_z[static_cast<size_t>(now)] * forward;
  const WorldObject& o = objects_[static_cast<size_t>(obstacle)];
  const glm::vec2 crossing = forward_of(o.spec.heading);
  const float cosine = glm::dot(forward, crossing);
  if (std::fabs(cosine) < 0.2f) return false;  // lying along the clip's way: it is not walked into head-on
  // Where the obstacle's line crosses the clip's, and its depth along the clip's way.
  const float z = glm::dot(floor_xz(o.position) - origin, crossing) / cosine;
  const float half_depth = 0.5f * o.spec.size.z / std::fabs(cosine);
  const bool board = o.spec.type == ObjectType::Hurdle;  // a board to clear, else a rail to pass under
  for (int k = now; k <= last; ++k)
    for (const ClipSweep::Segment& g : sweep.frames[static_cast<size_t>(k)]) {
      // The capsule's segment within the obstacle's depth (grown by its radius), its highest or lowest point there.
      const float lo = z - half_depth - g.radius, hi = z + half_depth + g.radius;
      const float dz = g.z1 - g.z0;
      float u0 = 0.0f, u1 = 1.0f;
      if (std::fabs(dz) < 1e-6f) {
        if (g.z0 < lo || g.z0 > hi) continue;
      } else {
        u0 = std::clamp((lo - g.z0) / dz, 0.0f, 1.0f);
        u1 = std::clamp((hi - g.z0) / dz, 0.0f, 1.0f);
        if (u0 > u1) std::swap(u0, u1);
        if (u0 == u1) continue;
      }
      const float ya = g.y0 + u0 * (g.y1 - g.y0), yb = g.y0 + u1 * (g.y1 - g.y0);
      if (board ? std::min(ya, yb) - g.radius < o.spec.size.y : std::max(ya, yb) + g.radius > o.spec.size.y) return true;
    }
  return false;
}

bool World::entry_clear_of(int index, int next, int obstacle) const {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  const TargetMotion& t = assets_->target(objects_[static_cast<size_t>(next)].spec.action);
  if (t.clip < 0) return false;
  const Clip& clip = assets_->set->clips[static_cast<size_t>(t.clip)].clip;
  const float past_launch_point = -approach(index).to_launch;  // as start_target enters it
  const int entry = past_launch_point > 0.0f ? t.entry_frame(past_launch_point) : t.reference_frame;
  const FloorTransform placed = place_frame(clip, entry, c.position, heading_to_launch_at(index, next, c.heading));
  CallScratch& k = call_scratch();
  k.pose = clip.frames[static_cast<size_t>(entry)];
  k.pose.root_position = placed.apply(k.pose.root_position);  // placed as the player places a clip's frame
  k.pose.rotations[0] = placed.rotation() * k.pose.rotations[0];
  forward_kinematics(*assets_->set->skeleton, k.pose, k.positions, &k.rotations);
  volumes_->place(k.positions, k.rotations, k.capsules);
  const WorldObject& o = objects_[static_cast<size_t>(obstacle)];
  for (const PlacedCapsule& capsule : k.capsules)
    for (const ObjectSolid& solid : solids_[static_cast<size_t>(obstacle)])
      if (capsule_solid_depth(capsule, solid, floor_xz(o.position), o.spec.heading) > 0.0f) return false;
  return true;
}

void World::make_way(int standing, int crossing, int obstacle) {
  WorldCharacter& s = characters_[static_cast<size_t>(standing)];
  if (s.control != Control::Opponent || !s.defeated) return;  // the others have ways of their own
  const WorldCharacter& c = characters_[static_cast<size_t>(crossing)];
  const WorldObject& o = objects_[static_cast<size_t>(obstacle)];
  const glm::vec2 n = crossing_direction(o.spec.heading, floor_xz(o.position), c.position);
  const glm::vec2 across(n.y, -n.x);
  const float lateral = glm::dot(s.position - c.position, across);
  // Out of the swept width on the side it already leans to, by a stride more.
  const float half_width = assets_->body_reaches[static_cast<size_t>(o.spec.action)].half_width + kStandingRadius;
  const float side = lateral >= 0.0f ? 1.0f : -1.0f;
  s.goal = {s.position + (side * (half_width + kMakeWayMargin) - lateral) * across};
}

// Bodies never pass through obstacles. A body that has gone into an obstacle's solids (a trailing leg swung
// into a hurdle's board by a turn just after the jump, a head walked into a rail) is set back out along the
// obstacle's crossing direction, to the root's side, by the depth: as a wall stops a body, not as a
// correction of the motion. The obstacle a target clip is crossing is left to the clip's fit
// (obstacle_fit.h) once the launch's cross-fade is over, but for its ends: the fit lowers or raises the body
// and does not see a post or a hurdle's leg, which a clip that drifts sideways (a recorded duck veering off
// its line) can run into; such a body is set in toward the middle of the span. A ball is kept out of all but
// its kick.
void World::keep_clear_of_obstacles(int index) {
  if (!params_.runtime.keep_clear) return;
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  constexpr float kBodyReach = 1.6f;  // m: no capsule is farther than this from the root on the floor
  bool placed = false;
  glm::vec2 body_low(0.0f), body_high(0.0f);  // the body's box on the floor, once placed
  glm::vec2 push(0.0f);
  for (size_t k = 0; k < objects_.size(); ++k) {
    const WorldObject& o = objects_[k];
    // The clip's own obstacle is the fit's, but for a rail while the launch's cross-fade lasts: the body is
    // then part the pose it came in with (upright, out of a walk) and is held back until it is low enough.
    // A hurdle is left to the jump throughout: held back, its run-up would never take off.
    const bool own = c.in_target && static_cast<int>(k) == rt.target_object;
    const bool ball = o.spec.type == ObjectType::Ball;
    if (!(is_across(o.spec.type) || ball) || (own && ball)) continue;
    // Crossing it: only its ends are kept out of, the rest is the fit's (and the jump's, throughout).
    const bool ends_only = own && (rt.fade_left <= 0.0f || o.spec.type == ObjectType::Hurdle);
    const glm::vec2 at = floor_xz(o.position);
    const float object_reach = 0.5f * glm::length(glm::vec2(o.spec.size.x, o.spec.size.z)) + kHurdleFootLength;
    if (glm::length(at - c.position) > object_reach + kBodyReach) continue;
    // The object within a circle about its middle: a body whose floor box is farther from that middle is
    // clear. A ball is a sphere about the vertical through its middle: a body whose floor box (capsule radii
    // included, moved by the push so far) stays farther from that line than the radius and kSurelyApart is
    // clear of it, as depth_at would find capsule by capsule (each depth is 0 for a capsule any distance
    // out). A character standing at its ball is told apart here on most ticks.
    const auto clear_by_box = [&](glm::vec2 low, glm::vec2 high) {
      if (glm::length(glm::clamp(at, low, high) - at) > object_reach) return true;
      return ball && glm::length(glm::clamp(at, low + push, high + push) - at) > ball_floor_reach(solids_[k]) + kSurelyApart;
    };
    if (!placed) {
      // The joints' bound first: it holds the capsules' box, so the object is at least as far from that box
      // as from this one. Clear by it, the body is clear by its capsules, which need not be placed.
      if (rt.kinematics_of_pose) {
        glm::vec2 bound_low, bound_high;
        volumes_->floor_box_bound(rt.scratch.positions, bound_low, bound_high);
        if (clear_by_box(bound_low, bound_high)) continue;
      }
      place_body(index, body_low, body_high);
      placed = true;
    }
    if (clear_by_box(body_low, body_high)) continue;
    glm::vec2 n = forward_of(o.spec.heading);
    if (ball && glm::length(c.position - at) > 1e-4f) n = glm::normalize(c.position - at);  // away from it
    if (glm::dot(c.position - at, n) < 0.0f) n = -n;
    // The depth is the nearest way out, which may be up (a foot on the board's top): a step along n by it
    // may leave the body in; a few steps finish the way out. A narrow solid lying along n (a hurdle's foot
    // or leg, a post) is left sooner to its side: a step that along n would leave the body in goes along
    // the obstacle's width instead where that leaves it clear.
    const ObjectFrame frame(at, o.spec.heading);
    std::vector<PlacedCapsule>& framed = call_scratch().framed;  // the capsules in the object's frame
    // The body's box in the object's frame first: a solid apart from it along one axis has no capsule in it.
    const auto depth_at = [&](glm::vec2 offset) {
      const V3 moved = V3::load(glm::vec3(offset.x, 0.0f, offset.y));
      framed.resize(rt.capsules.size());
      V3 low_in = V3::splat(std::numeric_limits<float>::infinity()), high_in = V3::splat(-std::numeric_limits<float>::infinity());
      for (size_t i = 0; i < rt.capsules.size(); ++i) {
        const PlacedCapsule& capsule = rt.capsules[i];
        PlacedCapsule& f = framed[i];
        const V3 a = frame.to_local(V3::load(capsule.a) + moved), b = frame.to_local(V3::load(capsule.b) + moved);
        a.store(f.a);
        b.store(f.b);
        f.radius = capsule.radius;
        const V3 radius = V3::splat(capsule.radius);
        low_in = min(low_in, min(a, b) - radius);
        high_in = max(high_in, max(a, b) + radius);
      }
      const glm::vec3 low = low_in.vec(), high = high_in.vec();
      float depth = 0.0f;
      for (const ObjectSolid& s : solids_[k]) {
        if (ends_only && s.part != SolidPart::Post && s.part != SolidPart::Leg && s.part != SolidPart::Foot) continue;
        const glm::vec3 half = s.sphere ? glm::vec3(0.5f * s.extents.x) : 0.5f * s.extents;
        if (glm::any(glm::greaterThan(low - s.centre, half)) || glm::any(glm::lessThan(high - s.centre, -half))) continue;
        for (const PlacedCapsule& f : framed) depth = std::max(depth, framed_capsule_solid_depth(f, s));
      }
      return depth;
    };
    const glm::vec2 along = floor_plane::left_of(o.spec.heading);
    float depth = depth_at(push);
    if (ends_only) {  // in toward the middle, as far as its end solids need
      const glm::vec2 inward = glm::dot(c.position - at, along) > 0.0f ? -along : along;
      for (int step = 0; step < 4 && depth > 0.0f; ++step) {
        push += (depth + kClearSkin) * inward;
        depth = depth_at(push);
      }
      continue;
    }
    for (int step = 0; step < 4 && depth > 0.0f; ++step) {
      const float by = depth + kClearSkin;
      glm::vec2 best = push + by * n;
      float best_depth = depth_at(best);
      // Sideways the way out may be longer than the depth (a foot 2 cm down in a hurdle's foot, 5 cm wide,
      // is out sideways only by the foot's width and its own): twice and four times it are tried too.
      for (const float times : {1.0f, 2.0f, 4.0f}) {
        if (ball || best_depth <= 0.0f) break;
        for (const glm::vec2 side : {along, -along})
          if (best_depth > 0.0f && depth_at(push + times * by * side) <= 0.0f) {
            best = push + times * by * side;
            best_depth = 0.0f;
          }
      }
      push = best;
      depth = best_depth;
    }
  }
  displace(index, push);
}

// Two bodies keep apart where their roots do not tell: a hand in guard held out across another's way, an
// arm swinging past a shoulder. Where two characters' capsules come nearer than kBodyGap (a punch's
// striking arm against the one it is launched at aside), they are set apart along the line between their
// roots to that gap, each by the share of the closing that is its own, as keep_apart does. The gap is a
// tick's worth of two hands swinging toward each other, so that the next frame's motion does not carry one
// into the other before it is set apart again.
void World::keep_bodies_apart() {
  const size_t n = characters_.size();
  if (n < 2 || !params_.runtime.keep_clear) return;
  constexpr float kBodyReach = 1.6f;  // m: no capsule is farther than this from the root on the floor
  const std::vector<BodyCapsule>& parts = volumes_->capsules();
  std::vector<glm::vec2>& low = body_low_;  // kept between ticks: no allocation per tick
  std::vector<glm::vec2>& high = body_high_;
  std::vector<char>& placed = body_placed_;
  low.resize(n);
  high.resize(n);
  placed.assign(n, 0);
  for_each_pair_within(characters_, 2.0f * kBodyReach, [&](size_t i, size_t j, glm::vec2 d, float distance) {
    const WorldCharacter& a = characters_[i];
    const WorldCharacter& b = characters_[j];
    for (size_t k : {i, j})
      if (!placed[k]) {
        place_body(static_cast<int>(k), low[k], high[k]);
        placed[k] = 1;
      }
    // Floor boxes apart: no capsule of one meets one of the other.
    if (glm::any(glm::greaterThan(low[i], high[j])) || glm::any(glm::greaterThan(low[j], high[i]))) return;
    const std::vector<PlacedCapsule>& ca = runtime_[i]->capsules;
    const std::vector<PlacedCapsule>& cb = runtime_[j]->capsules;
    float nearest = std::numeric_limits<float>::infinity();
    for (size_t p = 0; p < ca.size(); ++p) {
      if (a.arm_out_at == static_cast<int>(j) && is_striking_limb(a.playing, parts[p].part)) continue;
      for (size_t q = 0; q < cb.size(); ++q) {
        if (b.arm_out_at == static_cast<int>(i) && is_striking_limb(b.playing, parts[q].part)) continue;
        nearest = std::min(nearest, segment_segment_distance(ca[p].a, ca[p].b, cb[q].a, cb[q].b) - ca[p].radius - cb[q].radius);
      }
    }
    if (nearest >= kBodyGap) return;
    const glm::vec2 dir = distance > 1e-4f ? d / distance : forward_of(a.heading);
    const float share_a = closing_share(i, j, dir);
    const float gap = kBodyGap - nearest;
    const float most = kMaxShoveSpeed * params_.runtime.fixed_dt;
    displace(static_cast<int>(i), -std::min(share_a * gap, most) * dir);
    displace(static_cast<int>(j), std::min((1.0f - share_a) * gap, most) * dir);
    for (size_t k : {i, j}) placed[k] = 0;
  });
}

// The share of setting characters i and j apart along `dir` (from i toward j) that falls to i: the share of
// the closing that is its own (the one walking in yields to the one standing), half each when neither
// moves toward the other. One crossing an obstacle yields nothing: its clip is placed to pass over or under
// the obstacle (start_target slides it onto its launch), and a shove would carry it into the rail or board.
float World::closing_share(size_t i, size_t j, glm::vec2 dir) const {
  const auto crossing = [&](size_t k) {
    const int object = runtime_[k]->target_object;
    return characters_[k].in_target && object >= 0 && is_across(objects_[static_cast<size_t>(object)].spec.type);
  };
  const bool i_crossing = crossing(i), j_crossing = crossing(j);
  if (i_crossing != j_crossing) return i_crossing ? 0.0f : 1.0f;
  const float vi = std::max(0.0f, glm::dot(runtime_[i]->velocity, dir));
  const float vj = std::max(0.0f, -glm::dot(runtime_[j]->velocity, dir));
  return vi + vj > 1e-4f ? vi / (vi + vj) : 0.5f;
}

// The body's capsules this frame into the character's Runtime::capsules, and their box on the floor.
void World::place_body(int index, glm::vec2& low, glm::vec2& high) {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  if (rt.kinematics_of_pose) {
    volumes_->place(rt.scratch.positions, rt.scratch.rotations, rt.capsules);
  } else {
    CallScratch& k = call_scratch();
    forward_kinematics(*assets_->set->skeleton, c.pose, k.positions, &k.rotations);
    volumes_->place(k.positions, k.rotations, rt.capsules);
  }
  // The box in registers (x and z; y rides along unread), glm's min and max lane by lane.
  V3 low_in = V3::splat(std::numeric_limits<float>::infinity()), high_in = V3::splat(-std::numeric_limits<float>::infinity());
  for (const PlacedCapsule& p : rt.capsules) {
    const V3 a = V3::load(p.a), b = V3::load(p.b), radius = V3::splat(p.radius);
    low_in = min(low_in, min(a, b) - radius);
    high_in = max(high_in, max(a, b) + radius);
  }
  low = floor_xz(low_in.vec());
  high = floor_xz(high_in.vec());
}

void World::displace(int index, glm::vec2 offset) {
  if (offset == glm::vec2(0.0f)) return;
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const glm::vec3 o3(offset.x, 0.0f, offset.y);
  FloorTransform shift;
  shift.offset = offset;
  rt.stream.move(shift);
  rt.synthesis_previous_root += o3;
  SynthesisState& s = rt.synthesis;
  s.previous_locomotion_root += o3;
  s.root_xz += offset;
  for (FootPlant& f : s.feet) {
    f.heel_anchor += o3;
    f.toe_anchor += o3;
  }
  for (size_t side = 0; side < 2; ++side) {
    s.previous_locomotion_feet.heel[side] += o3;
    s.previous_locomotion_feet.toe[side] += o3;
  }
  for (glm::vec3& p : s.previous) p += o3;
  for (glm::vec3& p : s.before_previous) p += o3;
  c.pose.root_position += o3;
  rt.kinematics_of_pose = false;
  c.position += offset;
  c.com += o3;
}

// The obstacle clip's fit (obstacle_fit.h) on this frame: the body raised or lowered by the lift's share,
// the feet kept where the clip has them (lowered: both, so a swing foot does not sink into the floor;
// raised: the feet on the floor, the others rise with the body in flight).
void World::fit_pose(int index, Pose& pose) {
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const float lift = rt.fit.lift * rt.fit.weight(static_cast<float>(rt.stream.clip_frame()));
  if (lift == 0.0f) return;
  const MotionSet& set = *assets_->set;
  CallScratch& k = call_scratch();
  forward_kinematics(*set.skeleton, pose, k.positions, &k.rotations);
  const FrameContacts contacts = rt.stream.contacts();
  pose.root_position.y += lift;
  const glm::vec3 forward = pose.rotations[0] * glm::vec3(0.0f, 0.0f, 1.0f);
  for (int side : {kLeft, kRight}) {
    if (lift > 0.0f && !contacts[static_cast<size_t>(side)].any()) continue;
    const LegChain& leg = set.body.legs[static_cast<size_t>(side)];
    const size_t ankle = static_cast<size_t>(leg.ankle);
    solve_leg(*set.skeleton, leg, params_.ik, pose, k.positions, k.rotations, k.positions[ankle], k.rotations[ankle],
              forward, glm::vec3(0.0f, lift, 0.0f));
  }
}

}  // namespace prep
