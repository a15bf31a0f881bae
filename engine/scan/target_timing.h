// T_t, the first frame of a target motion's target movement (Sec. 4.2), found in a recorded take by one
// rule per role, each written beside its function:
//   crawl, duck: the head's descent to its lowest point starts;
//   jump: the head's descent into the crouch before the longest flight, or the take-off foot's landing,
//         whichever is later;
//   kick: the kicking foot's toe leaves the floor for the backswing;
//   punch: the striking hand starts its strike.
// And the strikes themselves: the frames where a hand or foot is fastest.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/motion/motion_set.h"
#include "engine/scan/motion_signals.h"

namespace prep {

struct Strike {
  int limb = 0;        // kLeft or kRight
  int peak = 0;        // the frame of the hand's (or foot's) greatest speed
  float speed = 0.0f;  // m/s at the peak: a hand relative to the root, a foot over the ground
};

// Punches in [first, last]: each local peak of a wrist's speed relative to the root of at least
// kPunchSpeed m/s and at least 70% of the fastest hand's, as the hand reaches away from the body; peaks of
// one hand closer than 0.3 s keep the faster. In time order.
std::vector<Strike> hand_strikes(const MotionSignals& s, int first, int last);
constexpr float kPunchSpeed = 3.0f;

// The fastest foot in [first, last] and its frame: the kick, when it is a kick.
Strike fastest_foot(const MotionSignals& s, int first, int last);

struct TargetTiming {
  int target_frame = -1;  // T_t
  int key_frame = -1;     // what it was found from: the lowest head, the take-off, the strike
  std::string rule;       // the rule and what it found, for the scan's table
};

// T_t for a take of the given target role within frames [first, last]; `strike` (punches) names which
// strike. nullopt when the take has no such event (no flight for a jump, no descent for a duck).
std::optional<TargetTiming> find_target_timing(Role role, const MotionSignals& s, int first, int last,
                                               const Strike* strike = nullptr);

}  // namespace prep
