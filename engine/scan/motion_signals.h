// What a recorded take does, frame by frame: the signals the folder scan decides roles, loops and T_t by.
// The take is in metres with its floor at y = 0 (estimate_floor_heights), on its own skeleton.
#pragma once

#include <array>
#include <vector>

#include <glm/vec3.hpp>

#include "engine/motion/body_map.h"
#include "engine/motion/clip.h"
#include "engine/motion/contacts.h"
#include "engine/params/params.h"

namespace prep {

struct MotionSignals {
  float fps = 30.0f;
  int frames = 0;
  float standing_head = 0.0f;                 // the head joint's height in the rest pose, feet on the floor
  std::vector<glm::vec3> root;                // the root joint
  std::vector<float> heading;                 // facing (radians, unwrapped): normal to the hips' left-right line
  std::vector<float> head_height;             // the head joint's height
  std::vector<float> lowest_foot;             // the lowest heel or toe point of either foot
  std::array<std::vector<float>, 2> toe_height;      // per foot ([kLeft], [kRight]), the toe tip's height
  std::array<std::vector<glm::vec3>, 2> hand;        // the wrists
  std::array<std::vector<glm::vec3>, 2> ankle;
  std::vector<FrameContacts> contacts;

  // Rates, by central differences over about 1/15 s whatever the frame rate.
  std::vector<float> ground_speed;                   // the root's horizontal speed, m/s
  std::vector<float> turn_rate;                      // d heading / dt, rad/s (positive: to the left)
  std::array<std::vector<float>, 2> hand_speed;      // each wrist relative to the root, m/s
  std::array<std::vector<float>, 2> foot_speed;      // each ankle, m/s

  float seconds(int frame_count) const { return static_cast<float>(frame_count) / fps; }
  int frames_in(float seconds) const;  // at least 1
};

MotionSignals measure_motion(const Clip& clip, const BodyMap& body, const ContactParams& contacts);

// Frames [first, last] (inclusive) where both feet are off the floor, per flight, in order.
struct Flight {
  int first = 0;
  int last = 0;
  int length() const { return last - first + 1; }
};
std::vector<Flight> flights(const MotionSignals& s, int first, int last);

// Mean of v over a centred window of `half` frames each side (clamped to [0, size)).
std::vector<float> smoothed(const std::vector<float>& v, int half);

// Median of v[first..last].
float median_of(const std::vector<float>& v, int first, int last);

}  // namespace prep
