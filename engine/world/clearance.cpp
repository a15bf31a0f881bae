#include "engine/world/clearance.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/motion/kinematics.h"

namespace prep {

namespace {

// Signed distance from a point to an axis-aligned box centred at the origin (negative inside).
float point_box_distance(glm::vec3 p, glm::vec3 half) {
  const glm::vec3 q = glm::abs(p) - half;
  const float outside = glm::length(glm::max(q, glm::vec3(0.0f)));
  const float inside = std::min(std::max(q.x, std::max(q.y, q.z)), 0.0f);
  return outside + inside;
}

}  // namespace

glm::vec3 closest_on_segment(glm::vec3 p, glm::vec3 a, glm::vec3 b) {
  const glm::vec3 ab = b - a;
  const float len2 = glm::dot(ab, ab);
  const float t = len2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
  return a + t * ab;
}

bool is_striking_limb(TargetAction punch, BodyPart part) {
  if (punch == TargetAction::PunchLeft) return part == BodyPart::LeftHand || part == BodyPart::LeftArm;
  return part == BodyPart::RightHand || part == BodyPart::RightArm;
}

float segment_box_distance(glm::vec3 a, glm::vec3 b, glm::vec3 centre, glm::vec3 half) {
  // The signed distance to a convex set is convex along a line, so its minimum over the segment is found by
  // a golden-section search (30 steps: 0.618^30 of the length, far below a millimetre).
  a -= centre;
  b -= centre;
  auto f = [&](float t) { return point_box_distance(a + t * (b - a), half); };
  constexpr float kInvPhi = 0.61803399f;
  float lo = 0.0f, hi = 1.0f;
  float x1 = hi - kInvPhi * (hi - lo), x2 = lo + kInvPhi * (hi - lo);
  float f1 = f(x1), f2 = f(x2);
  for (int k = 0; k < 30; ++k) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - kInvPhi * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + kInvPhi * (hi - lo);
      f2 = f(x2);
    }
  }
  return std::min({f1, f2, f(0.0f), f(1.0f)});
}

float segment_segment_distance(glm::vec3 p1, glm::vec3 q1, glm::vec3 p2, glm::vec3 q2) {
  // Closest points of two segments: minimise |p1 + s d1 - p2 - t d2| over s, t in [0, 1].
  const glm::vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const float a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
  constexpr float kTiny = 1e-12f;
  float s = 0.0f, t = 0.0f;
  if (a <= kTiny && e <= kTiny) return glm::length(r);
  if (a <= kTiny) {
    t = std::clamp(f / e, 0.0f, 1.0f);
  } else {
    const float c = glm::dot(d1, r);
    if (e <= kTiny) {
      s = std::clamp(-c / a, 0.0f, 1.0f);
    } else {
      const float b = glm::dot(d1, d2), denom = a * e - b * b;
      s = denom > kTiny ? std::clamp((b * f - c * e) / denom, 0.0f, 1.0f) : 0.0f;  // parallel: any s
      t = (b * s + f) / e;
      if (t < 0.0f) {
        t = 0.0f;
        s = std::clamp(-c / a, 0.0f, 1.0f);
      } else if (t > 1.0f) {
        t = 1.0f;
        s = std::clamp((b - c) / a, 0.0f, 1.0f);
      }
    }
  }
  return glm::length(p1 + s * d1 - (p2 + t * d2));
}

namespace {

// capsule_solid_distance with the capsule's ends already in the object's frame.
float framed_capsule_solid_distance(glm::vec3 a, glm::vec3 b, float radius, const ObjectSolid& s) {
  if (s.sphere) return glm::length(closest_on_segment(s.centre, a, b) - s.centre) - 0.5f * s.extents.x - radius;
  return segment_box_distance(a, b, s.centre, 0.5f * s.extents) - radius;
}

}  // namespace

float capsule_solid_distance(const PlacedCapsule& pc, const ObjectSolid& s, glm::vec2 at, float heading) {
  return framed_capsule_solid_distance(to_object_frame(pc.a, at, heading), to_object_frame(pc.b, at, heading), pc.radius, s);
}

float capsule_solid_depth(const PlacedCapsule& pc, const ObjectSolid& s, glm::vec2 at, float heading) {
  return framed_capsule_solid_depth({to_object_frame(pc.a, at, heading), to_object_frame(pc.b, at, heading), pc.radius}, s);
}

float framed_capsule_solid_depth(const PlacedCapsule& framed, const ObjectSolid& s) {
  const glm::vec3 a = framed.a, b = framed.b;
  const PlacedCapsule& pc = framed;
  // The capsule's bounding box apart from the solid's along one of the object's axes: nothing reaches in.
  // (A sphere's box is its cube.) Most limbs near an obstacle are told apart here.
  const glm::vec3 half = s.sphere ? glm::vec3(0.5f * s.extents.x) : 0.5f * s.extents;
  const glm::vec3 low = glm::min(a, b) - pc.radius - s.centre, high = glm::max(a, b) + pc.radius - s.centre;
  if (low.x > half.x || low.y > half.y || low.z > half.z || high.x < -half.x || high.y < -half.y || high.z < -half.z) return 0.0f;
  const glm::vec3 middle = 0.5f * (a + b);
  const float to_middle = s.sphere ? glm::length(middle - s.centre) - 0.5f * s.extents.x
                                   : point_box_distance(middle - s.centre, 0.5f * s.extents);
  if (to_middle - 0.5f * glm::length(b - a) - pc.radius > kSurelyClear) return 0.0f;
  return std::max(0.0f, -framed_capsule_solid_distance(a, b, pc.radius, s));
}

ClearanceMeter::ClearanceMeter(const Skeleton& skeleton) : volumes_(skeleton) {}

float ClearanceMeter::feet_to_object(const World& world, int character, int object) const {
  const WorldObject& o = world.objects()[static_cast<size_t>(object)];
  const glm::vec2 at(o.position.x, o.position.z);
  float gap = std::numeric_limits<float>::infinity();
  for (const ObjectSolid& s : object_solids(o.spec.type, o.spec.size))
    for (size_t c = 0; c < volumes_.capsules().size(); ++c) {
      const BodyPart part = volumes_.capsules()[c].part;
      if (part == BodyPart::LeftFoot || part == BodyPart::RightFoot)
        gap = std::min(gap, capsule_solid_distance(placed_[static_cast<size_t>(character)][c], s, at, o.spec.heading));
    }
  return gap;
}

void ClearanceMeter::measure(const World& world) {
  const auto& characters = world.characters();
  const auto& objects = world.objects();
  const Skeleton& skeleton = *world.assets().set->skeleton;
  const size_t n = characters.size();
  result_.assign(n, CharacterClearance{});
  placed_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    forward_kinematics(skeleton, characters[i].pose, positions_, &rotations_);
    volumes_.place(positions_, rotations_, placed_[i]);
  }
  const auto& capsules = volumes_.capsules();
  const float tolerance_objects = clearance_metric::kObjectTolerance, tolerance_bodies = clearance_metric::kCharacterTolerance;
  constexpr float kBodyReach = 1.6f;  // m: no capsule is farther than this from the root on the floor

  // Each object's solids, once per frame for every character.
  solids_.resize(objects.size());
  for (size_t k = 0; k < objects.size(); ++k) solids_[k] = object_solids(objects[k].spec.type, objects[k].spec.size);

  for (size_t i = 0; i < n; ++i) {
    CharacterClearance& out = result_[i];
    std::vector<bool> deep(capsules.size(), false);
    const glm::vec2 root = characters[i].position;

    for (size_t k = 0; k < objects.size(); ++k) {
      const WorldObject& o = objects[k];
      if (o.spec.type == ObjectType::Opponent) continue;
      const glm::vec2 at(o.position.x, o.position.z);
      const float object_reach = 0.5f * glm::length(o.spec.size) + kHurdleFootLength;
      if (glm::length(at - root) > object_reach + kBodyReach) continue;
      const std::vector<ObjectSolid>& solids = solids_[k];
      for (size_t c = 0; c < capsules.size(); ++c) {
        for (const ObjectSolid& s : solids) {
          const float d = capsule_solid_distance(placed_[i][c], s, at, o.spec.heading);
          if (d < out.object.distance) out.object = Nearest{d, static_cast<int>(c), static_cast<int>(k), -1, s.part, -1};
          if (d < -tolerance_objects) deep[c] = true;
        }
      }
    }

    const WorldCharacter& me = characters[i];
    for (size_t j = 0; j < n; ++j) {
      if (j == i || glm::length(characters[j].position - root) > 2.0f * kBodyReach) continue;
      const WorldCharacter& other = characters[j];
      for (size_t c = 0; c < capsules.size(); ++c) {
        const bool my_strike = me.arm_out_at == static_cast<int>(j) && is_striking_limb(me.playing, capsules[c].part);
        if (my_strike) continue;
        const PlacedCapsule& pc = placed_[i][c];
        for (size_t e = 0; e < capsules.size(); ++e) {
          if (other.arm_out_at == static_cast<int>(i) && is_striking_limb(other.playing, capsules[e].part)) continue;
          const PlacedCapsule& pe = placed_[j][e];
          const float d = segment_segment_distance(pc.a, pc.b, pe.a, pe.b) - pc.radius - pe.radius;
          if (d < out.character.distance)
            out.character = Nearest{d, static_cast<int>(c), -1, static_cast<int>(j), SolidPart::Rail, static_cast<int>(e)};
          if (d < -tolerance_bodies) deep[c] = true;
        }
      }
    }
    for (size_t c = 0; c < capsules.size(); ++c)
      if (deep[c]) out.penetrating.push_back(static_cast<int>(c));
  }
}

std::string ClearanceMeter::describe(const World& world, int character, const Nearest& n) const {
  if (n.capsule < 0) return "nothing near";
  const BodyCapsule& c = volumes_.capsules()[static_cast<size_t>(n.capsule)];
  char buf[256];
  const char* how = n.distance < 0.0f ? "inside" : "from";
  const int cm = static_cast<int>(std::lround(std::fabs(n.distance) * 100.0f));
  if (n.object >= 0) {
    const WorldObject& o = world.objects()[static_cast<size_t>(n.object)];
    std::snprintf(buf, sizeof buf, "character %d's %s (%s) %d cm %s the %s of the %s at (%.2f, %.2f)", character,
                  body_part_name(c.part), c.name.c_str(), cm, how, solid_part_name(n.part), object_type_name(o.spec.type),
                  o.spec.position.x, o.spec.position.y);
  } else {
    const BodyCapsule& e = volumes_.capsules()[static_cast<size_t>(n.other_capsule)];
    std::snprintf(buf, sizeof buf, "character %d's %s (%s) %d cm %s character %d's %s (%s)", character, body_part_name(c.part),
                  c.name.c_str(), cm, how, n.character, body_part_name(e.part), e.name.c_str());
  }
  return buf;
}

ClearanceLog::ClearanceLog(const World& world) : meter_(*world.assets().set->skeleton) {
  launches_seen_ = world.launches().size();
  open_.assign(world.characters().size(), -1);
  observe(world);
}

void ClearanceLog::observe(const World& world) {
  meter_.measure(world);
  ClearanceSummary& s = summary;
  ++s.frames;
  const auto& chars = world.characters();
  for (; launches_seen_ < world.launches().size(); ++launches_seen_) {
    const LaunchRecord& r = world.launches()[launches_seen_];
    LaunchClearance l;
    l.character = r.character;
    l.action = r.action;
    l.time = r.time;
    launches.push_back(l);
    object_of_.push_back(r.object);
    open_[static_cast<size_t>(r.character)] = static_cast<int>(launches.size()) - 1;
  }
  bool object_deep = false, character_deep = false;
  char when[32];
  std::snprintf(when, sizeof when, " at %.2f s", world.time());
  for (size_t i = 0; i < chars.size(); ++i) {
    const CharacterClearance& c = meter_.result()[i];
    object_deep |= c.object.distance < -clearance_metric::kObjectTolerance;
    character_deep |= c.character.distance < -clearance_metric::kCharacterTolerance;
    if (c.object.distance < s.min_object) {
      s.min_object = c.object.distance;
      s.min_object_what = meter_.describe(world, static_cast<int>(i), c.object) + when;
    }
    if (c.character.distance < s.min_character) {
      s.min_character = c.character.distance;
      s.min_character_what = meter_.describe(world, static_cast<int>(i), c.character) + when;
    }
    int& open = open_[i];
    if (open >= 0 && !chars[i].in_target) open = -1;
    if (open >= 0) {
      LaunchClearance& l = launches[static_cast<size_t>(open)];
      const bool punch = l.action == TargetAction::PunchLeft || l.action == TargetAction::PunchRight;
      const Nearest& n = punch ? c.character : c.object;
      if (n.distance < l.min_clearance) {
        l.min_clearance = n.distance;
        l.nearest = meter_.describe(world, static_cast<int>(i), n) + when;
      }
      const int ball = object_of_[static_cast<size_t>(open)];
      if (l.action == TargetAction::Kick && ball >= 0 && std::isnan(l.strike_gap) &&
          glm::length(world.objects()[static_cast<size_t>(ball)].velocity) > 0.0f)
        l.strike_gap = meter_.feet_to_object(world, static_cast<int>(i), ball);
    }
  }
  s.object_frames += object_deep;
  s.character_frames += character_deep;
}

nlohmann::json clearance_json(const ClearanceSummary& s) {
  auto metres = [](float v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"frames", s.frames},
          {"object_penetration_frames", s.object_frames},
          {"character_overlap_frames", s.character_frames},
          {"min_object_m", metres(s.min_object)},
          {"min_object", s.min_object_what},
          {"min_character_m", metres(s.min_character)},
          {"min_character", s.min_character_what}};
}

std::string clearance_text(const ClearanceSummary& s) {
  const auto nearest = [](float metres, const std::string& what) {
    if (!std::isfinite(metres)) return std::string("none near");
    char text[64];
    std::snprintf(text, sizeof text, "%.1f cm", 100.0f * metres);
    return std::string(text) + (what.empty() ? "" : ": " + what);
  };
  return "clearance over " + std::to_string(s.frames) + " frames: " + std::to_string(s.object_frames) +
         " with a body in an object, " + std::to_string(s.character_frames) + " with two bodies overlapping\n" +
         "  nearest to an object " + nearest(s.min_object, s.min_object_what) + "\n" + "  nearest to another body " +
         nearest(s.min_character, s.min_character_what) + "\n";
}

}  // namespace prep
