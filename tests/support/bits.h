// Bit-for-bit equality of plain values (floats, glm vectors and quaternions), for tests that hold a faster
// path to the exact floats of the one it replaces: 0.0 and -0.0 differ, as do two NaNs with other payloads.
#pragma once

#include <cstring>

namespace prep::test {
template <typename T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}
}  // namespace prep::test
