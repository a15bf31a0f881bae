// pi for the control module's angle arithmetic. Internal to engine/control: defined here once, not per file,
// so that the module's .cpp files can share a translation unit (unity build).
#pragma once

namespace prep::control_angles {

inline constexpr float kPi = 3.14159265358979323846f;

}  // namespace prep::control_angles
