// pi for the tests' angles. Defined here once, not per test file, so that an area's test files can share a
// translation unit (unity build).
#pragma once

namespace prep::test {

inline constexpr float kPi = 3.14159265358979f;

}  // namespace prep::test
