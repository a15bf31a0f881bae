// Angle constants of the built-in library's generators (their keys are written in degrees). Internal to
// engine/library: one definition, so the generators' .cpp files can share a translation unit (unity build).
#pragma once

namespace prep::library {

inline constexpr float kPi = 3.14159265f;
inline constexpr float kDeg = kPi / 180.0f;  // degrees to radians
// This literal, not kPi / 2: it is the float just below pi/2 (kPi / 2 is the one just above), and the
// clips were tuned with it.
inline constexpr float kHalfPi = 1.5707963f;

}  // namespace prep::library
