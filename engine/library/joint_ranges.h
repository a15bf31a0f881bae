// Documented ranges of motion of the human joints our clips use, and a checker.
//
// Ranges (degrees) from the American Academy of Orthopaedic Surgeons' normal values (Greene & Heckman,
// "The Clinical Measurement of Joint Motion", 1994) and Kapandji, "The Physiology of the Joints":
// knee flexion 0-150 (we allow 5 of hyperextension), hip flexion -30 (extension) to 125 and abduction
// -30 (adduction) to 45, ankle dorsiflexion -50 (plantarflexion) to 45 (loaded: the weight-bearing lunge
// reaches ~45 degrees of shank inclination, Bennell et al. 1998; unloaded AAOS gives 20), toe (MTP) extension -40 to 70,
// elbow flexion 0-150, wrist at most 95 from neutral (70 of active extension; a palm flat on the floor under a
// vertical arm, as on hands and knees, loads it to ~90), lumbar/thoracic joints at most 40 each, neck at most
// 60, head on neck at most 45, clavicle at most 30 from rest.
#pragma once

#include <string>
#include <vector>

#include "engine/motion/pose.h"

namespace prep::library {

struct JointRange {
  const char* joint;    // our joint name
  const char* measure;  // what is measured
  float min_deg, max_deg;
};

const std::vector<JointRange>& joint_ranges();

struct JointAngle {
  std::string joint, measure;
  float degrees;
  float min_deg, max_deg;
  bool ok() const { return degrees >= min_deg && degrees <= max_deg; }
};

// Every measured angle of one pose of builtin_skeleton(), with its range.
std::vector<JointAngle> measure_joint_angles(const Pose& pose);

}  // namespace prep::library
