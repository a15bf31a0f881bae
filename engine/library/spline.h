// Smooth interpolation helpers for the built-in library.
#pragma once

#include <vector>

namespace prep::library {

// Cubic Hermite basis: value at s in [0, 1] of the curve from p0 (slope m0) to p1 (slope m1), slopes per unit s.
inline float hermite(float p0, float m0, float p1, float m1, float s) {
  const float s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1;
}

// Quintic smoothstep: 0 -> 1 with zero velocity and acceleration at both ends (a minimum-jerk profile).
inline float smooth5(float s) {
  s = s < 0.0f ? 0.0f : (s > 1.0f ? 1.0f : s);
  return s * s * s * (s * (s * 6.0f - 15.0f) + 10.0f);
}

// A periodic curve given by equally spaced samples over one cycle (samples[0] at phase 0, no repeated end
// sample), read at `phase` (cycles; any real) by uniform periodic Catmull-Rom: C1 everywhere.
float periodic_catmull_rom(const std::vector<float>& samples, float phase);

// Its derivative with respect to the phase (per cycle).
float periodic_catmull_rom_slope(const std::vector<float>& samples, float phase);

}  // namespace prep::library
