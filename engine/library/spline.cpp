#include "engine/library/spline.h"

#include <cmath>

namespace prep::library {
namespace {
struct Segment {
  float p0, p1, m0, m1, s;
};
Segment locate(const std::vector<float>& samples, float phase) {
  const int n = static_cast<int>(samples.size());
  const float x = (phase - std::floor(phase)) * static_cast<float>(n);
  int i = static_cast<int>(std::floor(x));
  if (i >= n) i = n - 1;
  auto at = [&](int k) { return samples[static_cast<size_t>(((k % n) + n) % n)]; };
  // Catmull-Rom tangents per sample interval.
  return {at(i), at(i + 1), 0.5f * (at(i + 1) - at(i - 1)), 0.5f * (at(i + 2) - at(i)), x - static_cast<float>(i)};
}
}  // namespace

float periodic_catmull_rom(const std::vector<float>& samples, float phase) {
  if (samples.empty()) return 0.0f;
  const Segment g = locate(samples, phase);
  return hermite(g.p0, g.m0, g.p1, g.m1, g.s);
}

float periodic_catmull_rom_slope(const std::vector<float>& samples, float phase) {
  if (samples.empty()) return 0.0f;
  const Segment g = locate(samples, phase);
  const float s = g.s, s2 = s * s;
  const float d = (6 * s2 - 6 * s) * g.p0 + (3 * s2 - 4 * s + 1) * g.m0 + (-6 * s2 + 6 * s) * g.p1 + (3 * s2 - 2 * s) * g.m1;
  return d * static_cast<float>(samples.size());  // per sample interval -> per cycle
}

}  // namespace prep::library
