// Steering beyond the policy's walking turns: what a person does near a goal that the walking turns cannot
// reach without circling it, and when a waypoint on the way counts as passed.
//
// The policy's core turns curve at a fixed rate (the built-in turns 37.5 deg/s): at 1.4 m/s that is a
// turning radius of about 2 m. A goal inside the circle of that radius beside the character (closer than
// 2 R |sin(bearing)|), or behind it within the circle's diameter, cannot be reached by walking turns
// without a loop around it, and a controller that only sees quantized bearings orbits it. A person
// shortens the stride and turns sharply there, pivoting on the foot they stand on. So, while the goal is
// inside that circle, the world moves the character's motion stream on top of the played clip
// (MotionStream::move):
// - it turns the stream toward the goal about the stance foot, only in single support (with both feet
//   down a turn would drag one of them), at the bearing over kTightTurnTime, capped at
//   RuntimeParams::tight_turn_deg_per_s;
// - it shortens the stride to cos(bearing) of the clip's, at least kTightStride (a goal to the side or
//   behind: a third of the stride), as Eq. 3-4 do for preparation: the foot IK keeps the planted feet where
//   they landed. The scale follows its target over kStrideTime so that entering and leaving the circle do
//   not jolt the pace.
// The orbit this prevents: turning at an effective w while moving at v circles with radius v / w; the goal
// at distance d and bearing b lies on a circle of radius d / (2 sin b). At the cap of 180 deg/s, applied in
// single support (about 60% of a walk), and a third of 1.4 m/s, the circle is 0.25 m: goals from 0.5 m out
// at any bearing are reached.
// A goal behind the character (more than kTurnBack off its facing) is turned to the same way, however far
// it is: a person who has the goal at their back turns round within a step or two. The walking turns
// would first carry the character a turning circle's width away from it (a loop of about 6 m for a goal
// straight behind), and with the goal close to straight behind the policy's bearing bins flip between
// left and right, so it may walk on away while it decides (random courses starting with the goal behind
// walked up to 2.4 times their route). Not while a source is in range: the policy turns toward the source
// then, and a turn toward the goal behind could take the next obstacle out of range on the way out of a
// target motion, and the preparation kept for it with it.
#pragma once

#include <glm/vec2.hpp>

namespace prep {

constexpr float kTightTurnTime = 0.4f;  // s: the tight turn faces the goal in about this time
constexpr float kTightStride = 0.3f;    // the shortest stride, as a fraction of the clip's
constexpr float kStrideTime = 0.2f;     // s: time constant of the stride scale
// Near a goal the heading is also corrected toward it (without shortening the stride) when it is off by
// more than kNearBearing: the policy's bearings are quantized in 45 degree bins (Table I), so left to
// itself it walks up to about 22 degrees off a goal close ahead and weaves onto it.
constexpr float kNearGoal = 3.0f;                          // m
constexpr float kNearBearing = 10.0f * 3.14159265f / 180;  // rad
constexpr float kTurnBack = 0.5f * 3.14159265f;             // rad: a goal farther off the facing is behind

// Signed bearing (rad, in (-pi, pi], positive toward +X from a heading of 0) of `target` seen from
// `position` facing `heading` (a character at heading h faces (sin h, cos h) on the floor).
float bearing_to(glm::vec2 position, float heading, glm::vec2 target);

// Whether walking turns of radius `turning_radius` cannot reach `goal` without circling it (see above).
bool inside_turning_circle(glm::vec2 position, float heading, glm::vec2 goal, float turning_radius);

struct TightTurn {
  float rate = 0.0f;    // rad/s of extra heading (the sign of the bearing)
  float stride = 1.0f;  // target stride scale
};
// The tight turn toward `goal`: none (rate 0, stride 1) unless the goal is inside the turning circle, or
// behind (more than kTurnBack off the facing) when `turn_back`, or nearer than kNearGoal and off by more
// than kNearBearing (then the heading only).
TightTurn tight_turn(glm::vec2 position, float heading, glm::vec2 goal, float turning_radius, float max_rate,
                     bool turn_back = true);

// Squaring up to an obstacle: once arrived at the launch point of a bar, beam or hurdle (arrival.h) the
// heading turns toward the obstacle's crossing direction (its normal, from the character's side), so the
// target clip crosses it square. The policy steers toward the launch point, not along the normal: on an
// obstacle turned 30 degrees it could come in more than 45 degrees off the crossing, where the world did
// not count the source as ahead, and launched on the point without its arrival.
constexpr float kSquareTolerance = 2.0f * 3.14159265f / 180;   // rad: left alone within this
// m: an obstacle or a ball whose launch point was already this near and ahead when it became the source is
// squared up to (or faced) before the arrival too. Out of a previous obstacle's clip the next one may lie
// this near at an angle, and the policy, seeing the launch point within a bearing bin of ahead, may turn
// the other way or walk past a ball to the side. (One approached from farther is walked to as the policy
// steers, and squared up to on arrival.) A ball this near is faced however it was approached: met off to
// the side, short of its arrival radius, it was walked past.
constexpr float kSquareAhead = 1.0f;
// The yaw rate (rad/s) that squares `heading` up to `crossing_heading`, capped at `max_rate`.
float squaring_rate(float heading, float crossing_heading, float max_rate);

// A waypoint the character goes by: within `pass_radius` of it and no longer ahead, more than kPassedBearing
// off its facing (beside or behind it). Straight behind was too strict: a character turning toward a
// waypoint half a metre to its side faced it again before it fell behind, and stepped about it, turning
// this way and that, without ever reaching it.
constexpr float kPassedBearing = 0.25f * 3.14159265f;  // rad
bool passed_waypoint(glm::vec2 position, float heading, glm::vec2 waypoint, float pass_radius);

}  // namespace prep
