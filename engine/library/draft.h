// A motion in the making: per-frame angle poses plus the intervals in which each foot (and, for the crawl,
// each hand) rests on the floor. realize() turns it into a Clip whose supports really stay put: every
// support gets an anchor on the floor, and the legs (arms) are solved by two-bone IK to hold it, while
// between supports the limb follows its keyed path, shifted smoothly from one anchor to the next.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/library/dof_pose.h"
#include "engine/motion/clip.h"

namespace prep::library {

// How a limb in support holds on to the floor.
enum class Hold {
  RollingFoot,  // a walking foot: rolls over the heel before mid-support and over the ball after it, flat between
  RigidFoot,    // keeps the keyed foot's mid-support orientation, toe tip on the floor (kneeling, crawling)
  PalmDown,     // a hand flat on the floor, fingers along anchor_yaw
};

struct Support {
  int first = 0, last = 0;        // frames, inclusive
  Hold hold = Hold::RollingFoot;
  bool explicit_anchor = false;   // else the anchor is where the keyed pose puts the limb at mid-support
  glm::vec2 anchor_xz{0.0f};      // ankle (wrist) position on the floor plane
  float anchor_yaw = 0.0f;        // foot (hand) heading
  float lift_before = 0.0f;       // extra clearance (m) at mid-swing of the swing that ends here
};

struct Draft {
  std::string name;
  float fps = 60.0f;
  std::vector<DofPose> frames;
  std::array<std::vector<Support>, 2> feet;   // [left, right]
  std::array<std::vector<Support>, 2> hands;  // used by the crawl only

  float time(int frame) const { return static_cast<float>(frame) / fps; }
};

// A walking foot in support (Hold::RollingFoot), given its flat-foot ankle anchor and heading and its toe-up
// pitch relative to mid-support (`roll`): before mid-support it turns about the ankle (heel rocker, toes
// up only); after it the heel rises, the toes bend up at the ball by up to 40 degrees, and beyond that the
// whole foot turns about the toe tip (pre-swing).
struct FootHold {
  glm::vec3 ankle{0.0f};
  glm::quat foot{1, 0, 0, 0};  // world rotations
  glm::quat toes{1, 0, 0, 0};
};
FootHold roll_foot(glm::vec3 flat_ankle, float yaw, float roll, bool before_mid);

struct RealizeReport {
  int unreachable_frames = 0;  // limb IK targets out of reach (should be 0)
  float worst_overreach = 0.0f;  // m beyond the limb's length at worst
};

// Merges overlapping or touching supports of each limb (keeping the first's anchor and lift).
void merge_supports(std::vector<Support>& supports);

Clip realize(const Draft& draft, RealizeReport* report = nullptr);

}  // namespace prep::library
