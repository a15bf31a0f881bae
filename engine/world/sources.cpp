// The sources of influence (Sec. 7.2): which object or character each character prepares for, the launch
// point where its target clip meets it, the approach to that point, and the arrival there (arrival.h).
#include <algorithm>
#include <cmath>
#include <optional>
#include <limits>

#include "engine/control/arrival.h"
#include "engine/world/floor.h"
#include "engine/world/world.h"
#include "engine/world/world_runtime.h"

namespace prep {

namespace {

using floor_plane::floor_xz;
using floor_plane::crossing_direction;
using floor_plane::forward_of;
using floor_plane::is_across;
using floor_plane::kPi;
using floor_plane::left_of;

const float kCos45 = std::cos(kPi / 4.0f);
constexpr float kArrivalFacing = 75.0f * kPi / 180.0f;  // rad off an obstacle's crossing (update_arrival)
// rad off an obstacle's crossing at which it is launched at: an obstacle crossed at a slant passes the body
// under (or over) it along a longer, lower line than the clip was made for.
constexpr float kSquareCrossing = 10.0f * kPi / 180.0f;
constexpr float kSourceKeptAngle = 2.0f * kPi / 3.0f;   // 120 degrees (choose_source)
constexpr float kSourceKeptWidth = 1.0f;                // m beyond an obstacle's end (choose_source)
// m: a launch needs the character this close to the span's part kSpanMargin inside the ends (approach); the
// launch slides the rest in before the body reaches the obstacle (World::start_target).
constexpr float kSpanTolerance = 0.25f;
constexpr float kOpponentHold = 0.5f;  // m short of its launch point at which an opponent stops (update_arrival)
// m beyond an obstacle's end that the way to the goal may cross its line and the obstacle still be a source
// (choose_source): a body passing nearer would clip its post, so it is passed through its span instead;
// farther, it is walked round with room.
constexpr float kBesideEnd = 0.6f;
constexpr float kLateralStep = 0.1f;     // m between the places along a span tried for room (launch_lateral)
constexpr float kBodyLineSpacing = 0.1f; // m between the lines across its width a clip's body is followed along (launch_room_short)
constexpr float kRoomMargin = 0.05f;     // m kept between a clip's body and the next obstacle (launch_room_short)

// The lateral place (along the obstacle's width, from its middle) where the straight way from `from` to `to`
// crosses the line of an obstacle at `p` turned `heading`; nullopt when it does not cross it.
std::optional<float> crossing_lateral(glm::vec2 from, glm::vec2 to, glm::vec2 p, float heading) {
  const glm::vec2 n = forward_of(heading), along = left_of(heading);
  const float s0 = glm::dot(from - p, n), s1 = glm::dot(to - p, n);
  if (s0 * s1 > 0.0f || s0 == s1) return std::nullopt;
  const glm::vec2 x = from + (s0 / (s0 - s1)) * (to - from);
  return glm::dot(x - p, along);
}

// How far `p` is from an obstacle's line, along its crossing direction.
float from_line(const WorldObject& o, glm::vec2 p) {
  return std::fabs(glm::dot(p - floor_xz(o.position), forward_of(o.spec.heading)));
}

}  // namespace

// The launch point for an action at an object: where the character stands when the action's clip, entered
// at T_p, meets the object. For balls and characters it is along the line from the character to the object.
glm::vec2 World::launch_point(int index, glm::vec2 object, TargetAction action) const {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  const glm::vec2 d = object - c.position;
  const float len = glm::length(d);
  const glm::vec2 dir = len > 1e-4f ? d / len : forward_of(c.heading);
  return object - assets_->target(action).reach * dir;
}

// Across obstacles (bar, beam, hurdle) the approach is along the obstacle's normal, at the lateral place
// launch_lateral chooses.
glm::vec2 World::launch_point(int index, int obstacle) const {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  const WorldObject& o = objects_[static_cast<size_t>(obstacle)];
  const glm::vec2 object = floor_xz(o.position);
  const glm::vec2 n = crossing_direction(o.spec.heading, object, c.position);  // the approach runs from the character's side
  // Already nearer to the obstacle than the clip's reach (out of the previous obstacle's clip), the
  // character is past its launch point: the point is where it stands, so that it goes on to the
  // obstacle (and enters the clip late) rather than turning back through what it has just crossed.
  const float before = std::clamp(glm::dot(object - c.position, n), 0.0f, assets_->target(o.spec.action).reach);
  return object + launch_lateral(index, obstacle) * left_of(o.spec.heading) - before * n;
}

// The character's own lateral place, kept kSpanMargin inside the ends; if the obstacle's clip launched there
// would run into another obstacle before it may be left (two obstacles close together and at an angle, the
// gap between them narrowing toward one end), or the next obstacle's clip could not follow on out of it
// without being slid back through this one, the nearest place along the span that leaves room for both. A
// person lines up where the gap is wide enough to come up in. Where no place has room for both, the nearest
// with room for the clip's body, else the one with the most: a walk along the span for a follow-on that
// lacks room everywhere would gain nothing.
float World::launch_lateral(int index, int obstacle) const {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const WorldObject& o = objects_[static_cast<size_t>(obstacle)];
  const glm::vec2 object = floor_xz(o.position);
  glm::vec2 n = forward_of(o.spec.heading);
  const bool from_front = glm::dot(object - c.position, n) >= 0.0f;
  if (!from_front) n = -n;
  const float span = std::max(0.5f * o.spec.size.x - kSpanMargin, 0.0f);
  const float own = std::clamp(glm::dot(c.position - object, left_of(o.spec.heading)), -span, span);
  const int samples = static_cast<int>(std::floor(2.0f * span / kLateralStep)) + 1;
  const auto at = [&](int k) { return -span + static_cast<float>(k) * kLateralStep; };
  if (rt.room_obstacle != obstacle || rt.room_from_front != from_front) {
    rt.room_obstacle = obstacle;
    rt.room_from_front = from_front;
    rt.room.resize(static_cast<size_t>(samples));
    for (int k = 0; k < samples; ++k) rt.room[static_cast<size_t>(k)] = launch_room_short(obstacle, o.spec.action, n, at(k));
  }
  // How far along the crossing from the T_p root the front of the character's body reaches (the same at
  // every place). A rail between the root and the obstacle that the body has reached is not moved away from:
  // the walk along the span to a place with room would carry the body along under or beside it (a duck left
  // under a beam for a hurdle beyond walked on upright, its head in the rail).
  const float body_front = glm::dot(c.position - object, n) + assets_->target(o.spec.action).reach + kStandingRadius;
  const auto body_short = [&](int k) { return rt.room[static_cast<size_t>(k)].body_from(body_front); };
  const int nearest = std::clamp(static_cast<int>(std::lround((own + span) / kLateralStep)), 0, samples - 1);
  const auto room_for_both = [&](int k) { return body_short(k) <= 0.0f && rt.room[static_cast<size_t>(k)].follow <= 0.0f; };
  rt.room_moved = false;
  if (room_for_both(nearest)) return own;
  int best = -1;
  for (int k = 0; k < samples; ++k)
    if (room_for_both(k) && (best < 0 || std::fabs(at(k) - own) < std::fabs(at(best) - own))) best = k;
  if (best < 0) {
    if (body_short(nearest) <= 0.0f) return own;
    best = nearest;
    for (int k = 0; k < samples; ++k) {
      const float shortfall = std::max(body_short(k), 0.0f);
      const float best_shortfall = std::max(body_short(best), 0.0f);
      if (shortfall < best_shortfall || (shortfall == best_shortfall && std::fabs(at(k) - own) < std::fabs(at(best) - own))) best = k;
    }
  }
  rt.room_moved = best != nearest;
  return best == nearest ? own : at(best);
}

// How much room (m) the clip of `action`, launched at the obstacle along `n` at `lateral` from its middle,
// lacks before the solids of the other across obstacles beyond: its body (BodyReach, up to the frame the
// clip may be left, as wide as it reaches either side of its line) comes within kRoomMargin of one by this
// much (RoomShort::body). <= 0: it has room. The body's width is followed along parallel lines
// kBodyLineSpacing apart; each solid is widened by half that, so that a narrow one (a hurdle's foot) cannot
// fall between two lines. RoomShort::between: the same for a rail or board between the T_p root and the
// obstacle. RoomShort::follow: how much farther than its late entry covers the next obstacle's clip would
// be slid back, started at this clip's release frame.
World::RoomShort World::launch_room_short(int obstacle, TargetAction action, glm::vec2 n, float lateral) const {
  RoomShort room{-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                 -std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
  const BodyReach& body = assets_->body_reaches[static_cast<size_t>(action)];
  if (body.z.empty()) return room;
  const WorldObject& o = objects_[static_cast<size_t>(obstacle)];
  const TargetMotion& target = assets_->target(action);
  const float reach = target.reach;
  const float body_farthest = *std::max_element(body.z.begin(), body.z.end());
  const glm::vec2 along = left_of(o.spec.heading);
  for (size_t k = 0; k < objects_.size(); ++k) {
    const WorldObject& next = objects_[k];
    if (static_cast<int>(k) == obstacle || !is_across(next.spec.type)) continue;
    const glm::vec2 p2 = floor_xz(next.position), n2 = forward_of(next.spec.heading), along2 = left_of(next.spec.heading);
    const float cosine = glm::dot(n, n2);
    // The upright ends of another obstacle (posts, a hurdle's legs and feet) standing in the clip's way on
    // this side of the crossing, or beyond it where that obstacle runs all but parallel to the way across (the
    // lines below do not meet it): the body crawls or ducks past them within its width. Short by as much as
    // the launch must move aside to pass them.
    {
      const glm::vec2 root = floor_xz(o.position) + lateral * along - reach * n;  // the T_p root
      const ObjectFrame frame(p2, next.spec.heading);
      const float farthest = std::fabs(cosine) < 0.2f ? body_farthest : reach;
      for (const ObjectSolid& solid : solids_[k]) {
        if (solid.part != SolidPart::Post && solid.part != SolidPart::Leg && solid.part != SolidPart::Foot) continue;
        const glm::vec2 centre = p2 + glm::vec2(frame.cos_heading * solid.centre.x + frame.sin_heading * solid.centre.z,
                                                -frame.sin_heading * solid.centre.x + frame.cos_heading * solid.centre.z);
        const float radius = 0.5f * glm::length(glm::vec2(solid.extents.x, solid.extents.z));
        const float z = glm::dot(centre - root, n), x = glm::dot(centre - root, along);
        if (z < -radius || z > farthest + radius) continue;
        const float y0 = solid.centre.y - 0.5f * solid.extents.y, y1 = solid.centre.y + 0.5f * solid.extents.y;
        if (!std::isfinite(body.over(y0, y1))) continue;  // the body has nothing at its heights
        room.body = std::max(room.body, body.half_width + radius + kRoomMargin - std::fabs(x));
      }
    }
    if (std::fabs(cosine) < 0.2f) continue;  // all but parallel to the way across: not crossed on it
    const int lines = static_cast<int>(std::ceil(2.0f * body.half_width / kBodyLineSpacing)) + 1;
    const float spacing = lines > 1 ? 2.0f * body.half_width / static_cast<float>(lines - 1) : 0.0f;
    for (int line = 0; line < lines; ++line) {
      const float side = -body.half_width + static_cast<float>(line) * spacing;
      // The line the T_p root's facing runs along (z = 0 at the T_p root), and where it meets `next`'s frame.
      const glm::vec2 root = floor_xz(o.position) + (lateral + side) * along - reach * n;
      const float z_at_axis = glm::dot(p2 - root, n2) / cosine;
      const float x_at_axis = glm::dot(root + z_at_axis * n - p2, along2);
      const TargetMotion& follow = assets_->target(next.spec.action);
      if (line == lines / 2 && z_at_axis > reach && z_at_axis - follow.reach < body_farthest) {
        // `next` is so close that its launch point lies within this clip's body, and the root's own line
        // meets it outside the part a launch is made from (kSpanMargin inside its ends), within its width
        // or beside its end where it is still in the way (kBesideEnd): its action could not follow straight
        // on out of this clip, and the character would walk along it, under or beside its rail, to where
        // it can. Short by as much as the line is outside.
        const float half = 0.5f * next.spec.size.x, usable = std::max(half - kSpanMargin, 0.0f);
        const float outside = std::fabs(x_at_axis) - usable;
        if (outside > 0.0f && std::fabs(x_at_axis) < half + kBesideEnd) room.body = std::max(room.body, outside);
        // Within it, `next`'s clip follows on at this clip's release, entered as far on as the root has come
        // past its launch point. A clip that covers little ground before its body nears its obstacle (a crawl
        // kneels where it stands) cannot make up more than that: the rest would be slid back, out of the
        // landing and through the obstacle just crossed. Short by what the late entry cannot take.
        if (target.release_frame >= 0 && !follow.advance.empty()) {
          const float past = target.release_advance - (z_at_axis - follow.reach);
          room.follow = std::max(room.follow, past - follow.advance.back());
        }
      }
      for (const ObjectSolid& solid : solids_[k]) {
        if (std::fabs(x_at_axis - solid.centre.x) > 0.5f * (solid.extents.x + spacing)) continue;
        // The solid's depth (along n2) as a stretch of z, and the body's farthest z at the solid's heights.
        const float z0 = z_at_axis + (solid.centre.z - 0.5f * solid.extents.z) / cosine;
        const float z1 = z_at_axis + (solid.centre.z + 0.5f * solid.extents.z) / cosine;
        const float near = std::min(z0, z1), far = std::max(z0, z1);
        const float y0 = solid.centre.y - 0.5f * solid.extents.y, y1 = solid.centre.y + 0.5f * solid.extents.y;
        if (near <= reach) {
          // On this side of the obstacle crossed: out of the way behind the T_p root; between the root and
          // the obstacle (`next` runs across this one's way, the two meeting within the clip's width) a rail
          // or board is passed on the way in wherever the body reaches it at its heights. Upright parts are
          // the block's above.
          if (far > 0.0f && (solid.part == SolidPart::Rail || solid.part == SolidPart::Board)) {
            const float short_by = body.over(y0, y1) + kRoomMargin - std::max(near, 0.0f);
            if (short_by > 0.0f) {
              room.between = std::max(room.between, short_by);
              room.between_from = std::max(room.between_from, near);
            }
          }
          continue;
        }
        room.body = std::max(room.body, body.over(y0, y1) + kRoomMargin - near);
      }
    }
  }
  return room;
}

float World::reach_past_object(TargetAction action) const {
  const BodyReach& body = assets_->body_reaches[static_cast<size_t>(action)];
  if (body.z.empty()) return 0.0f;
  return std::max(*std::max_element(body.z.begin(), body.z.end()) - assets_->target(action).reach, 0.0f);
}

int World::obstacle_between(glm::vec2 from, glm::vec2 to) const {
  int nearest = -1;
  float nearest_distance = std::numeric_limits<float>::infinity();
  for (int k = 0; k < static_cast<int>(objects_.size()); ++k) {
    const WorldObject& o = objects_[static_cast<size_t>(k)];
    if (o.used || !is_across(o.spec.type) || assets_->target(o.spec.action).clip < 0) continue;
    const glm::vec2 p = floor_xz(o.position);
    const std::optional<float> cross = crossing_lateral(from, to, p, o.spec.heading);
    if (!cross || std::fabs(*cross) > 0.5f * o.spec.size.x + kBesideEnd) continue;
    const float distance = from_line(o, from);
    if (distance < nearest_distance) {
      nearest_distance = distance;
      nearest = k;
    }
  }
  return nearest;
}

// The room an opponent leaves beyond the obstacle: as far as the user's clip reaches past the obstacle's
// line (its body up to the frame it may be left), and a strike's reach more. Nearer, the user's clip would
// come up into it; walking up to the line, the two stood face to face across the rail, each short of its
// launch point, for good.
bool World::waiting_beyond_obstacle(const WorldCharacter& c) const {
  if (c.control != Control::Opponent || c.defeated || c.source_character < 0) return false;
  const WorldCharacter& u = characters_[static_cast<size_t>(c.source_character)];
  const Runtime& user_rt = *runtime_[static_cast<size_t>(c.source_character)];
  const auto within_room = [&](int k) {
    if (k < 0) return false;
    const WorldObject& o = objects_[static_cast<size_t>(k)];
    return from_line(o, c.position) <= reach_past_object(o.spec.action) + assets_->target(c.met_with).reach;
  };
  // The user crossing one now (the obstacle is used from its launch): waited for until it is out of its
  // clip. And the next one between them is kept to as well: an opponent walking on while the user crosses
  // an obstacle farther off came up to that one's rail, guard against it, before the user was through.
  const int crossing = u.in_target && user_rt.target_object >= 0 &&
                               is_across(objects_[static_cast<size_t>(user_rt.target_object)].spec.type)
                           ? user_rt.target_object
                           : -1;
  return within_room(crossing) || within_room(obstacle_between(c.position, u.position));
}

int World::ball_before_opponent(int index, float opponent_distance) const {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  const Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const glm::vec2 fwd = forward_of(c.heading);
  int chosen = -1;
  float nearest = std::numeric_limits<float>::infinity();
  for (int k = 0; k < static_cast<int>(objects_.size()); ++k) {
    const WorldObject& o = objects_[static_cast<size_t>(k)];
    if (o.used || o.spec.type != ObjectType::Ball || assets_->target(o.spec.action).clip < 0) continue;
    const glm::vec2 d = floor_xz(o.position) - c.position;
    const float distance = glm::length(d);
    // Chosen once, it is kept while it lies within kSourceKeptAngle of the facing (the opponent, waiting,
    // no longer comes nearer, and the halfway mark would pass it over again at the last step).
    const bool kept = k == rt.source_key;
    const float within = kept ? std::cos(kSourceKeptAngle) : kCos45;
    if (glm::dot(d, fwd) <= within * distance) continue;
    if (!kept && distance >= 0.5f * opponent_distance) continue;
    if (obstacle_between(c.position, floor_xz(o.position)) >= 0) continue;
    if (distance < nearest) {
      nearest = distance;
      chosen = k;
    }
  }
  return chosen;
}

bool World::waiting_for_kick(const WorldCharacter& c) const {
  if (c.control != Control::Opponent || c.defeated) return false;
  const WorldCharacter& u = characters_[static_cast<size_t>(user_)];
  const Runtime& user_rt = *runtime_[static_cast<size_t>(user_)];
  // Making for a ball, or kicking one that has not yet left the foot.
  int ball = -1;
  if (u.in_target && u.playing == TargetAction::Kick && !user_rt.struck) ball = user_rt.target_object;
  else if (!u.in_target && u.source_object >= 0 && objects_[static_cast<size_t>(u.source_object)].spec.type == ObjectType::Ball)
    ball = u.source_object;
  if (ball < 0) return false;
  const float from_ball = glm::length(c.position - floor_xz(objects_[static_cast<size_t>(ball)].position));
  return from_ball <= reach_past_object(TargetAction::Kick) + assets_->target(c.met_with).reach + 2.0f * kPersonalSpace;
}

bool World::waits_its_turn(const WorldCharacter& c) const { return waiting_beyond_obstacle(c) || waiting_for_kick(c); }

bool World::stands_aside(const WorldCharacter& c) const {
  return c.control == Control::Opponent && !c.defeated && assets_->target(c.met_with).clip < 0;
}

// Sec. 7.2: the source of influence. User: the closest opponent still fighting (fight), or the obstacle
// between the two, or a ball on the way to it reached well before it, else the closest unused object in the
// facing direction (within 90 degrees; an across obstacle also within its width, and used or not while the
// way to the goal crosses it).
// Opponents: the user's character.
void World::choose_source(int index) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  const glm::vec2 last_launch = c.source;  // the last tick's source's launch point
  c.has_source = false;
  c.source_object = c.source_character = -1;
  const glm::vec2 fwd = forward_of(c.heading);
  if (c.control == Control::Opponent) {
    const WorldCharacter& u = characters_[static_cast<size_t>(user_)];
    if (c.defeated || stands_aside(c)) return;
    c.has_source = true;
    c.source_character = user_;
    c.prepared_for = c.met_with;
    c.source_object_position = u.position;
    c.source = launch_point(index, u.position, c.met_with);
    return;
  }
  if (picked_source_ >= 0) {  // picked by hand (set_source): kept while it can still be acted on
    const WorldObject& o = objects_[static_cast<size_t>(picked_source_)];
    if (o.spec.type == ObjectType::Opponent && o.character >= 0) {
      const WorldCharacter& opponent = characters_[static_cast<size_t>(o.character)];
      if (!opponent.defeated && !stands_aside(opponent)) {
        c.has_source = true;
        c.source_character = o.character;
        c.prepared_for = opponent.met_with;
        c.source_object_position = opponent.position;
        c.source = launch_point(index, opponent.position, c.prepared_for);
        return;
      }
    } else if (!o.used && assets_->target(o.spec.action).clip >= 0) {
      c.has_source = true;
      c.source_object = picked_source_;
      c.prepared_for = o.spec.action;
      c.source_object_position = floor_xz(o.position);
      c.source = is_across(o.spec.type) ? launch_point(index, picked_source_) : launch_point(index, c.source_object_position, c.prepared_for);
      return;
    }
    picked_source_ = -1;  // used or defeated: the automatic choice resumes
  }
  float best = std::numeric_limits<float>::infinity();
  for (int k = 0; k < static_cast<int>(characters_.size()); ++k) {
    const WorldCharacter& o = characters_[static_cast<size_t>(k)];
    if (o.control != Control::Opponent || o.defeated || stands_aside(o)) continue;
    const float d = glm::length(o.position - c.position);
    if (d < best) {
      best = d;
      c.has_source = true;
      c.source_character = k;
      c.prepared_for = o.met_with;
      c.source_object_position = o.position;
    }
  }
  // objects_[k] as the source (in place of an opponent, or the nearest object below).
  const auto object_source = [&](int k) {
    const WorldObject& o = objects_[static_cast<size_t>(k)];
    c.source_character = -1;
    c.source_object = k;
    c.prepared_for = o.spec.action;
    c.source_object_position = floor_xz(o.position);
    c.source = is_across(o.spec.type) ? launch_point(index, k) : launch_point(index, c.source_object_position, c.prepared_for);
  };
  if (c.has_source) {
    // A ball on the way, reached well before the two meet (and before an obstacle between them), is kicked
    // first: the opponent waits (waiting_for_kick). An obstacle between the two is crossed next: the
    // opponent waits beyond it (waiting_beyond_obstacle).
    const int between = obstacle_between(c.position, c.source_object_position);
    int ball = ball_before_opponent(index, glm::length(c.source_object_position - c.position));
    if (ball >= 0 && between >= 0 &&
        glm::length(floor_xz(objects_[static_cast<size_t>(ball)].position) - c.position) >=
            from_line(objects_[static_cast<size_t>(between)], c.position))
      ball = -1;
    if (ball >= 0) {
      object_source(ball);
    } else if (between >= 0) {
      object_source(between);
    } else {
      c.source = launch_point(index, c.source_object_position, c.prepared_for);
    }
    return;
  }
  // During a cross-fade (out of a target clip, kept preparation) the stream's root has been placed by the
  // floor alignment of the two clips, and may face tens of degrees away from the body shown: the source
  // kept from the last tick is kept if it lies ahead of either.
  const Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const bool fading = rt.fade_left > 0.0f && !c.pose.rotations.empty();
  const glm::vec2 shown_fwd = fading ? forward_of(heading_of(c.pose.rotations[0])) : fwd;
  // Inside a target clip the pelvis may face far from the way the clip goes (a duck turned sideways under
  // its beam): the source kept is kept if it lies ahead of the heading the clip was started facing, too.
  const glm::vec2 way_fwd = c.in_target ? forward_of(rt.launch_heading) : fwd;
  for (int k = 0; k < static_cast<int>(objects_.size()); ++k) {
    const WorldObject& o = objects_[static_cast<size_t>(k)];
    if (o.spec.type == ObjectType::Opponent || assets_->target(o.spec.action).clip < 0) continue;
    const glm::vec2 p = floor_xz(o.position), d = p - c.position;
    // An obstacle crossed is crossed again when the way on leads back over it (a waypoint reached on its far
    // side): the character stands on the other side from its launch, the goal on the side it came from. So
    // is one it was carried across and has come back round to (steered round its end): the goal lies
    // beyond it again. A crossing that ended where it began is not tried again (world.h); a ball kicked or
    // an opponent beaten is done with.
    if (o.used) {
      const float own_side = glm::dot(c.position - p, forward_of(o.spec.heading));
      const bool crossed = o.launched_from * own_side < 0.0f;
      if (is_across(o.spec.type) && c.control == Control::User && o.launched_from * own_side < -kCarriedAcross)
        objects_[static_cast<size_t>(k)].carried_across = true;
      if (!(is_across(o.spec.type) && (crossed || o.carried_across) && !c.goal.empty() &&
            glm::dot(c.goal.front() - p, forward_of(o.spec.heading)) * own_side < 0.0f))
        continue;
    }
    // The source of the last tick is kept more loosely (kSourceKeptAngle, kSourceKeptWidth): a character
    // that weaves or turns on its approach does not lose it and find it again past its launch point.
    const bool kept = k == rt.source_key;
    float distance;
    if (is_across(o.spec.type)) {
      const glm::vec2 n = forward_of(o.spec.heading), along = left_of(o.spec.heading);
      const float half_width = 0.5f * o.spec.size.x + (kept ? kSourceKeptWidth : 0.0f);
      // Beside it, and the way to the goal passes its end with room: not in the way. A way that would clip
      // its end makes it a source, passed through its span (the launch point is inside it).
      if (std::fabs(glm::dot(c.position - p, along)) > half_width) {
        const std::optional<float> cross =
            c.goal.empty() ? std::nullopt : crossing_lateral(c.position, c.goal.front(), p, o.spec.heading);
        if (!cross || std::fabs(*cross) > 0.5f * o.spec.size.x + kBesideEnd) continue;
      } else if (!c.goal.empty()) {
        // In front of it, but the goal (a waypoint to visit first) lies on this side and no nearer to it
        // than the character: the way there leads away from it. Crossed now, it would be crossed back.
        const float goal_side = glm::dot(c.goal.front() - p, n), own_side = glm::dot(c.position - p, n);
        if (goal_side * own_side > 0.0f && std::fabs(goal_side) >= std::fabs(own_side)) continue;
      }
      distance = std::fabs(glm::dot(d, n));
    } else {
      distance = glm::length(d);
    }
    // Behind: not in the facing direction. A ball on the way to the goal is not behind, though: a character
    // turned off its way (as a fight leaves it, facing where the opponent stood) still passes it
    // (RuntimeParams::make_for_ball_source).
    const bool on_way = params_.runtime.make_for_ball_source && !is_across(o.spec.type) && !c.goal.empty() &&
                        glm::dot(d, c.goal.front() - c.position) > 0.0f;
    if (!kept && glm::dot(d, fwd) <= 0.0f && !on_way) continue;
    // Walked along to a launch place away from its middle (launch_lateral), an obstacle's middle falls
    // behind while its launch point still lies ahead: the launch point counts too.
    const glm::vec2 to_launch = last_launch - c.position;
    const bool launch_ahead = kept && is_across(o.spec.type) && glm::dot(to_launch, fwd) > std::cos(kSourceKeptAngle) * glm::length(to_launch);
    if (kept && !launch_ahead &&
        std::max({glm::dot(d, fwd), glm::dot(d, shown_fwd), glm::dot(d, way_fwd)}) <= std::cos(kSourceKeptAngle) * glm::length(d))
      continue;
    if (distance < best) {
      best = distance;
      c.has_source = true;
      c.source_object = k;
      c.prepared_for = o.spec.action;
      c.source_object_position = p;
    }
  }
  if (c.has_source) object_source(c.source_object);
}

World::Approach World::approach(int index) const {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Approach a;
  a.to_launch = std::numeric_limits<float>::infinity();
  if (!c.has_source) return a;
  const TargetMotion& t = assets_->target(c.prepared_for);
  const glm::vec2 fwd = forward_of(c.heading);
  const glm::vec2 to_object = c.source_object_position - c.position;
  const float d = glm::length(to_object);
  if (c.source_object >= 0 && is_across(objects_[static_cast<size_t>(c.source_object)].spec.type)) {
    // Along the obstacle's normal, from the character's side (as launch_point() places the point).
    glm::vec2 n = forward_of(objects_[static_cast<size_t>(c.source_object)].spec.heading);
    if (glm::dot(to_object, n) < 0.0f) n = -n;
    const float along = glm::dot(to_object, n);
    a.to_launch = along - t.reach;
    // Beside the place along the span a launch starts from (launch_lateral): not there yet, however near.
    const float lateral = glm::dot(c.position - c.source_object_position, left_of(objects_[static_cast<size_t>(c.source_object)].spec.heading));
    const float beside = std::fabs(lateral - launch_lateral(index, c.source_object)) - kSpanTolerance;
    if (beside > 0.0f) a.to_launch = std::max(a.to_launch, beside);
    a.beside = beside > 0.0f;
    a.ahead = along > 0.0f && glm::dot(fwd, n) >= kCos45;
    a.facing = along > 0.0f && glm::dot(fwd, n) >= std::cos(kArrivalFacing);
    a.square = a.ahead && glm::dot(fwd, n) >= std::cos(kSquareCrossing);
  } else if (d > 1e-4f) {
    a.to_launch = d - t.reach;
    a.ahead = glm::dot(to_object, fwd) >= kCos45 * d;
    // A ball is kicked along the facing: faced within kSquareCrossing (the arrival turns to it).
    const bool ball = c.source_object >= 0 && objects_[static_cast<size_t>(c.source_object)].spec.type == ObjectType::Ball;
    a.square = a.ahead && (!ball || glm::dot(to_object, fwd) >= std::cos(kSquareCrossing) * d);
    // A ball met off to the side, as an obstacle met off square, is arrived at (and turned to) within
    // kArrivalFacing: walking on past it, the character would leave it unkicked.
    a.facing = ball && glm::dot(to_object, fwd) >= std::cos(kArrivalFacing) * d;
  }
  return a;
}

// Arrival at the launch point (engine/control/arrival.h): how far the character still has to go along the
// approach, whether the source lies ahead, and the forcing of the played alpha once within the arrival
// radius. Runs after the tick's pose, so the next tick plays the forced alpha.
void World::update_arrival(int index) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  Controller& ctl = *rt.controller;
  const float dt = params_.runtime.fixed_dt;
  const int key = !c.has_source ? -2 : c.source_object >= 0 ? c.source_object : -c.source_character - 3;
  if (key != rt.source_key) {  // another source (or none): its approach starts afresh
    rt.source_key = key;
    rt.source_position = c.source_object_position;
    rt.source_closing_speed = 0.0f;
    rt.approach_seen = false;
    c.level_at_arrival = c.alpha_at_1m = -1.0f;
    if (ctl.arrived()) ctl.set_arrived(false);
  }
  c.to_launch = std::numeric_limits<float>::infinity();
  c.source_ahead = false;
  rt.facing = false;
  rt.square = false;
  rt.beside = false;
  if (c.has_source && !c.in_target) {
    const Approach a = approach(index);
    c.to_launch = a.to_launch;
    c.source_ahead = a.ahead;
    rt.facing = a.facing;
    rt.square = a.square;
    rt.beside = a.beside;
    const glm::vec2 to_object = c.source_object_position - c.position;
    const float d = glm::length(to_object);
    // How fast the source itself comes toward the character (an opponent walking in), smoothed over about
    // a gait cycle (the root sways within one).
    if (d > 1e-4f) {
      const float closing = -glm::dot(c.source_object_position - rt.source_position, to_object / d) / dt;
      const float k = dt / (dt + 0.5f);
      rt.source_closing_speed += k * (std::max(0.0f, closing) - rt.source_closing_speed);
    }
    rt.source_position = c.source_object_position;
    // The alpha 1 m before the launch point, for an approach that began farther away (one that starts
    // closer, e.g. out of the previous obstacle's clip, has no such moment: left at -1).
    if (!rt.approach_seen) {
      rt.approach_seen = true;
      rt.approach_from_far = c.to_launch > 1.0f;
    }
    if (rt.approach_from_far && c.alpha_at_1m < 0.0f && c.to_launch <= 1.0f) c.alpha_at_1m = c.alpha;
  }
  c.source_in_range = c.has_source && !c.in_target && c.to_launch <= params_.runtime.preparation_range;
  // Without preparation (the naive baseline, set_preparation) synthesis ignores alpha, so nothing would
  // stop the character: it walks on to the launch point and launches there.
  // A character whose policy has itself chosen the top level inside the source radius has stopped there
  // (w_r = 1, Eq. 3-4): it has arrived as near as it will get, and launches where it stands (the shortfall
  // is the launch's miss). Seen with slow core walks, whose stride at 0.8 does not pay for moving on
  // inside the radius (reward.h).
  const bool stopped = ctl.alpha_level() == ctl.policy().table.alpha_levels - 1;
  // An obstacle is arrived at facing it more loosely than it is launched at: the arrival squares the
  // character up to it (steer_tightly), and the launch waits for that (try_auto_launch: ahead).
  const bool within = preparation_ && (c.source_ahead || rt.facing) && !rt.beside &&
                      (c.to_launch <= arrival_->radius(rt.source_closing_speed) ||
                       // An opponent stops at striking distance and waits there for the user to come in
                       // (world.h): two characters each walking to the other's launch point circle.
                       (c.control == Control::Opponent && c.to_launch <= kOpponentHold) ||
                       ((stopped || ctl.arrived()) && c.to_launch <= params_.reward.source_radius));
  if (within && !ctl.arrived()) {
    c.level_at_arrival = ctl.alpha_of_level(ctl.alpha_level());
    ctl.set_arrived(true);
  } else if (!within && ctl.arrived()) {
    ctl.set_arrived(false);
  }
  c.arrived = ctl.arrived();
  if (c.arrived) c.chosen_alpha = 1.0f;
}

}  // namespace prep
