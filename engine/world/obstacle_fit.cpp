#include "engine/world/obstacle_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/motion/kinematics.h"
#include "engine/world/floor.h"
#include "engine/world/object_solids.h"
#include "engine/world/world.h"

namespace prep {

float max_fit(TargetAction action) {
  switch (action) {
    case TargetAction::Crawl: return 0.04f;  // knees and forearms on the floor: barely lower
    case TargetAction::Duck: return 0.22f;   // a deeper crouch, the knees bending further
    case TargetAction::Jump: return 0.20f;   // a higher flight
    default: return 0.0f;
  }
}

ClipSweep sweep_clip(const MotionSet& set, const BodyVolumes& volumes, int clip, int reference_frame) {
  ClipSweep sweep;
  const Clip& c = set.clips[static_cast<size_t>(clip)].clip;
  sweep.first_frame = reference_frame;
  sweep.fps = c.fps;
  const Pose& ref = c.frames[static_cast<size_t>(reference_frame)];
  const glm::vec2 origin = floor_plane::floor_xz(ref.root_position);
  const float heading = heading_of(ref.rotations[0]);
  const glm::vec2 fwd = floor_plane::forward_of(heading), left = floor_plane::left_of(heading);
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  std::vector<PlacedCapsule> placed;
  for (int f = reference_frame; f < c.frame_count(); ++f) {
    forward_kinematics(*set.skeleton, c.frames[static_cast<size_t>(f)], positions, &rotations);
    volumes.place(positions, rotations, placed);
    std::vector<ClipSweep::Segment> segments;
    segments.reserve(placed.size());
    for (const PlacedCapsule& p : placed)
      segments.push_back({glm::dot(floor_plane::floor_xz(p.a) - origin, fwd), p.a.y,
                          glm::dot(floor_plane::floor_xz(p.b) - origin, fwd), p.b.y, p.radius,
                          glm::dot(floor_plane::floor_xz(p.a) - origin, left), glm::dot(floor_plane::floor_xz(p.b) - origin, left)});
    sweep.frames.push_back(std::move(segments));
    sweep.root_z.push_back(glm::dot(floor_plane::floor_xz(positions[0]) - origin, fwd));
  }
  return sweep;
}

BodyReach body_reach(const ClipSweep& sweep, int last_frame) {
  BodyReach reach;
  constexpr int kSamples = 5;  // points along each capsule's segment
  const size_t frames = last_frame < 0 ? sweep.frames.size()
                                       : std::min(sweep.frames.size(), static_cast<size_t>(std::max(0, last_frame - sweep.first_frame + 1)));
  for (size_t k = 0; k < frames; ++k)
    for (const ClipSweep::Segment& s : sweep.frames[k]) {
      reach.half_width = std::max(reach.half_width, std::max(std::fabs(s.x0), std::fabs(s.x1)) + s.radius);
      for (int i = 0; i < kSamples; ++i) {
        const float u = static_cast<float>(i) / (kSamples - 1);
        const float z = s.z0 + u * (s.z1 - s.z0) + s.radius, y = s.y0 + u * (s.y1 - s.y0);
        const int lo = std::max(0, static_cast<int>(std::floor((y - s.radius) / BodyReach::kBand)));
        const int hi = std::max(lo, static_cast<int>(std::floor((y + s.radius) / BodyReach::kBand)));
        if (static_cast<size_t>(hi) >= reach.z.size()) reach.z.resize(static_cast<size_t>(hi) + 1, -std::numeric_limits<float>::infinity());
        for (int b = lo; b <= hi; ++b) reach.z[static_cast<size_t>(b)] = std::max(reach.z[static_cast<size_t>(b)], z);
      }
    }
  return reach;
}

float BodyReach::over(float y0, float y1) const {
  float farthest = -std::numeric_limits<float>::infinity();
  const int lo = std::max(0, static_cast<int>(std::floor(y0 / kBand)));
  const int hi = std::min(static_cast<int>(z.size()) - 1, static_cast<int>(std::floor(y1 / kBand)));
  for (int b = lo; b <= hi; ++b) farthest = std::max(farthest, z[static_cast<size_t>(b)]);
  return farthest;
}

float ObstacleFit::weight(float frame) const {
  if (last < first) return 0.0f;
  float x = 1.0f;
  if (frame < static_cast<float>(first)) x = 1.0f - (static_cast<float>(first) - frame) / std::max(ramp_frames, 1.0f);
  if (frame > static_cast<float>(last)) x = 1.0f - (frame - static_cast<float>(last)) / std::max(ramp_frames, 1.0f);
  x = std::clamp(x, 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}

ObstacleFit fit_obstacle(const ClipSweep& sweep, const TargetMotion& target, ObjectType type, glm::vec3 size) {
  ObstacleFit fit;
  fit.ramp_frames = kFitRamp * sweep.fps;
  const bool over = type == ObjectType::Hurdle;
  if (!(over || type == ObjectType::Bar || type == ObjectType::Beam)) return fit;
  // The rail's or board's depth along the crossing, as object_solids builds it.
  const float depth = size.z > 0.0f ? size.z : (over ? 0.03f : kDefaultRail);
  const float near = target.reach - 0.5f * depth, far = target.reach + 0.5f * depth;
  float extreme = over ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
  for (size_t k = 0; k < sweep.frames.size(); ++k) {
    bool touched = false;
    for (const ClipSweep::Segment& s : sweep.frames[k]) {
      // The part of the segment within the band the capsule can reach the rail from, as parameters t.
      const float lo = near - s.radius, hi = far + s.radius;
      float t0 = 0.0f, t1 = 1.0f;
      const float dz = s.z1 - s.z0;
      if (std::fabs(dz) < 1e-6f) {
        if (s.z0 < lo || s.z0 > hi) continue;
      } else {
        float a = (lo - s.z0) / dz, b = (hi - s.z0) / dz;
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
        if (t0 > t1) continue;
      }
      const float ya = s.y0 + t0 * (s.y1 - s.y0), yb = s.y0 + t1 * (s.y1 - s.y0);
      touched = true;
      if (over) extreme = std::min(extreme, std::min(ya, yb) - s.radius);
      else extreme = std::max(extreme, std::max(ya, yb) + s.radius);
    }
    if (touched) {
      const int frame = sweep.first_frame + static_cast<int>(k);
      if (fit.last < fit.first) fit.first = frame;
      fit.last = frame;
    }
  }
  if (fit.last < fit.first) return fit;  // the clip never comes near: nothing to fit
  fit.clip_height = extreme;
  fit.lift = over ? std::max(0.0f, size.y + kFitMargin - extreme) : std::min(0.0f, size.y - kFitMargin - extreme);
  fit.possible = std::fabs(fit.lift) <= max_fit(target.action) + 1e-4f;
  return fit;
}

}  // namespace prep
