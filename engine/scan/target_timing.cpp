#include "engine/scan/target_timing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

namespace prep {
namespace {

constexpr float kLookBackSeconds = 1.5f;     // how long before its lowest point a descent may start
constexpr float kDescentFraction = 0.05f;    // a descent has started once 5% of its drop is done
constexpr float kSmoothingSeconds = 0.025f;  // half-width of the smoothing before looking for a descent
constexpr float kMinHeadDrop = 0.15f;        // a duck or crawl lowers the head by 15% of standing height
constexpr float kToeLift = 0.02f;            // m above its planted height: the toe has left the floor
constexpr float kSwingSpeed = 1.0f;          // m/s: a foot faster than this is swinging, not planted
constexpr float kStrikeStart = 0.25f;        // a strike starts where the hand was at 25% of its peak speed
constexpr float kStrikeSpacing = 0.3f;       // s between two strikes of one hand

std::string describe(const char* what, int frame) {
  char text[96];
  std::snprintf(text, sizeof text, "%s %d", what, frame);
  return text;
}

// The frame where the fall of `h` to its low point `low` starts: the last frame that is still within
// kDescentFraction of the drop below the highest point since `earliest`. (Walking brings the head up and
// down a few centimetres at every step, so the descent is judged against its whole drop, not frame by
// frame.)
int descent_start(const std::vector<float>& h, int low, int earliest) {
  int top = earliest;
  for (int f = earliest; f <= low; ++f)
    if (h[static_cast<size_t>(f)] > h[static_cast<size_t>(top)]) top = f;
  const float still_up = h[static_cast<size_t>(top)] - kDescentFraction * (h[static_cast<size_t>(top)] - h[static_cast<size_t>(low)]);
  int start = top;
  for (int f = top; f <= low; ++f)
    if (h[static_cast<size_t>(f)] >= still_up) start = f;
  return start;
}

int argmin(const std::vector<float>& v, int first, int last) {
  int best = first;
  for (int f = first; f <= last; ++f)
    if (v[static_cast<size_t>(f)] < v[static_cast<size_t>(best)]) best = f;
  return best;
}

// Crawl and duck: the head's lowest point (for a crawl, which stays low, the first frame within 10% of
// the drop from it) and the start of the descent to it.
std::optional<TargetTiming> lowering_timing(Role role, const MotionSignals& s, int first, int last) {
  const std::vector<float> head = smoothed(s.head_height, s.frames_in(kSmoothingSeconds));
  int low = argmin(head, first, last);
  if (s.standing_head - head[static_cast<size_t>(low)] < kMinHeadDrop * s.standing_head) return std::nullopt;
  if (role == Role::Crawl) {
    // A crawl stays low, its head rising and falling with the hands: where it first gets down.
    const float nearly = head[static_cast<size_t>(low)] + 0.1f * (s.standing_head - head[static_cast<size_t>(low)]);
    low = first;
    while (head[static_cast<size_t>(low)] > nearly) ++low;
  }
  TargetTiming t;
  t.key_frame = low;
  t.target_frame = descent_start(head, low, std::max(first, low - s.frames_in(kLookBackSeconds)));
  t.rule = describe("head descends from", t.target_frame) + describe(", lowest at", low);
  return t;
}

// Jump: the longest flight's take-off; before it the crouch (the head's lowest point within
// kLookBackSeconds: the trunk bends as the knees do, so the head falls steadily where the root may pause)
// and the last landing of a foot. A standing jump's crouch starts long after its feet are down; a running
// jump's take-off foot lands after any dip of the head, and the jump starts there.
std::optional<TargetTiming> jump_timing(const MotionSignals& s, int first, int last) {
  const std::vector<Flight> all = flights(s, first, last);
  const Flight* longest = nullptr;
  for (const Flight& f : all)
    if (longest == nullptr || f.length() > longest->length()) longest = &f;
  if (longest == nullptr || longest->length() < 2 || longest->first <= first) return std::nullopt;
  const int takeoff = longest->first;
  const int earliest = std::max(first, takeoff - s.frames_in(kLookBackSeconds));
  const std::vector<float> head = smoothed(s.head_height, s.frames_in(kSmoothingSeconds));
  const int low = argmin(head, earliest, takeoff);
  const int crouch = descent_start(head, low, earliest);
  int landing = earliest;
  for (int f = earliest + 1; f < takeoff; ++f)
    for (int side : {kLeft, kRight})
      if (s.contacts[static_cast<size_t>(f)][static_cast<size_t>(side)].any() &&
          !s.contacts[static_cast<size_t>(f - 1)][static_cast<size_t>(side)].any())
        landing = f;
  TargetTiming t;
  t.key_frame = takeoff;
  t.target_frame = std::max(crouch, landing);
  t.rule = (crouch >= landing ? describe("crouch from", crouch) : describe("take-off foot lands at", landing)) +
           describe(", take-off at", takeoff);
  return t;
}

// Kick: the kicking foot's toe leaves the floor (kToeLift above its planted height, its lowest in the
// second before the strike: captured floors drift over a take) for the backswing before the strike.
std::optional<TargetTiming> kick_timing(const MotionSignals& s, int first, int last) {
  const Strike strike = fastest_foot(s, first, last);
  const std::vector<float>& toe = s.toe_height[static_cast<size_t>(strike.limb)];
  const int from = std::max(first, strike.peak - s.frames_in(1.0f));
  const float planted = *std::min_element(toe.begin() + from, toe.begin() + strike.peak + 1);
  // Back from the strike while the foot is up or still swinging (a kick along the floor strikes with the
  // toe low, moving fast).
  const std::vector<float>& speed = s.foot_speed[static_cast<size_t>(strike.limb)];
  int lift = strike.peak;
  while (lift > first && (toe[static_cast<size_t>(lift - 1)] > planted + kToeLift || speed[static_cast<size_t>(lift - 1)] > kSwingSpeed)) --lift;
  TargetTiming t;
  t.key_frame = strike.peak;
  t.target_frame = lift;
  t.rule = describe(strike.limb == kLeft ? "left toe lifts at" : "right toe lifts at", lift) + describe(", strike at", strike.peak);
  return t;
}

std::optional<TargetTiming> punch_timing(const MotionSignals& s, int first, const Strike& strike) {
  const std::vector<float>& speed = s.hand_speed[static_cast<size_t>(strike.limb)];
  int start = strike.peak;
  while (start > first && speed[static_cast<size_t>(start - 1)] >= kStrikeStart * strike.speed) --start;
  TargetTiming t;
  t.key_frame = strike.peak;
  t.target_frame = start;
  t.rule = describe(strike.limb == kLeft ? "left hand sets off at" : "right hand sets off at", start) +
           describe(", fastest at", strike.peak);
  return t;
}

}  // namespace

std::vector<Strike> hand_strikes(const MotionSignals& s, int first, int last) {
  float fastest = 0.0f;
  for (int side : {kLeft, kRight})
    for (int f = first; f <= last; ++f) fastest = std::max(fastest, s.hand_speed[static_cast<size_t>(side)][static_cast<size_t>(f)]);
  const float threshold = std::max(kPunchSpeed, 0.7f * fastest);
  const int spacing = s.frames_in(kStrikeSpacing);
  std::vector<Strike> out;
  for (int side : {kLeft, kRight}) {
    const std::vector<float>& v = s.hand_speed[static_cast<size_t>(side)];
    std::vector<Strike> mine;
    for (int f = std::max(first, 1); f < last; ++f) {
      const float x = v[static_cast<size_t>(f)];
      if (x < threshold || x < v[static_cast<size_t>(f - 1)] || x < v[static_cast<size_t>(f + 1)]) continue;
      // Reaching away from the body: the wrist farther from the root than a frame before.
      const glm::vec3 now = s.hand[static_cast<size_t>(side)][static_cast<size_t>(f)] - s.root[static_cast<size_t>(f)];
      const glm::vec3 before = s.hand[static_cast<size_t>(side)][static_cast<size_t>(f - 1)] - s.root[static_cast<size_t>(f - 1)];
      if (glm::length(now) <= glm::length(before)) continue;
      if (!mine.empty() && f - mine.back().peak < spacing) {
        if (x > mine.back().speed) mine.back() = {side, f, x};
        continue;
      }
      mine.push_back({side, f, x});
    }
    out.insert(out.end(), mine.begin(), mine.end());
  }
  std::sort(out.begin(), out.end(), [](const Strike& a, const Strike& b) { return a.peak < b.peak; });
  return out;
}

Strike fastest_foot(const MotionSignals& s, int first, int last) {
  Strike best;
  for (int side : {kLeft, kRight})
    for (int f = first; f <= last; ++f) {
      const float x = s.foot_speed[static_cast<size_t>(side)][static_cast<size_t>(f)];
      if (x > best.speed) best = {side, f, x};
    }
  return best;
}

std::optional<TargetTiming> find_target_timing(Role role, const MotionSignals& s, int first, int last, const Strike* strike) {
  switch (role) {
    case Role::Crawl:
    case Role::Duck:
      return lowering_timing(role, s, first, last);
    case Role::Jump:
      return jump_timing(s, first, last);
    case Role::Kick:
      return kick_timing(s, first, last);
    case Role::PunchLeft:
    case Role::PunchRight: {
      if (strike != nullptr) return punch_timing(s, first, *strike);
      const std::vector<Strike> strikes = hand_strikes(s, first, last);
      const int hand = role == Role::PunchLeft ? kLeft : kRight;
      for (const Strike& k : strikes)
        if (k.limb == hand) return punch_timing(s, first, k);
      return std::nullopt;
    }
    default:
      return std::nullopt;
  }
}

}  // namespace prep
