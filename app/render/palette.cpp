#include "app/render/palette.h"

#include <algorithm>
#include <cmath>

namespace prep::render::palette {

const char* pixel_class_name(PixelClass c) {
  switch (c) {
    case PixelClass::Sky: return "sky";
    case PixelClass::Ground: return "ground";
    case PixelClass::Character: return "character";
    case PixelClass::OtherCharacter: return "other character";
    case PixelClass::Obstacle: return "obstacle";
    case PixelClass::Ball: return "ball";
    case PixelClass::Goal: return "goal";
    case PixelClass::Source: return "source";
    case PixelClass::Support: return "support polygon";
    case PixelClass::Clearance: return "clearance";
    case PixelClass::Dark: return "dark";
    case PixelClass::Unknown: return "unknown";
  }
  return "unknown";
}

namespace {
// Hue in degrees [0, 360) and saturation (max - min) / max of an RGB colour.
void hue_saturation(float r, float g, float b, float& hue, float& saturation, float& value) {
  const float hi = std::max({r, g, b}), lo = std::min({r, g, b});
  value = hi;
  saturation = hi > 0.0f ? (hi - lo) / hi : 0.0f;
  const float d = hi - lo;
  if (d <= 0.0f) {
    hue = 0.0f;
    return;
  }
  if (hi == r) hue = 60.0f * std::fmod((g - b) / d, 6.0f);
  else if (hi == g) hue = 60.0f * ((b - r) / d + 2.0f);
  else hue = 60.0f * ((r - g) / d + 4.0f);
  if (hue < 0.0f) hue += 360.0f;
}

bool within(float hue, float centre, float half_width) {
  float d = std::fabs(hue - centre);
  d = std::min(d, 360.0f - d);
  return d <= half_width;
}
}  // namespace

PixelClass classify(int r8, int g8, int b8) {
  float hue, sat, value;
  hue_saturation(r8 / 255.0f, g8 / 255.0f, b8 / 255.0f, hue, sat, value);
  if (value < 0.12f) return PixelClass::Dark;
  if (sat < 0.15f) return PixelClass::Ground;
  if (sat < 0.30f) return within(hue, 210.0f, 30.0f) && value > 0.6f ? PixelClass::Sky : PixelClass::Unknown;
  if (within(hue, 24.0f, 14.0f)) return PixelClass::Character;
  if (within(hue, 272.0f, 18.0f)) return PixelClass::OtherCharacter;
  if (within(hue, 218.0f, 16.0f)) return PixelClass::Obstacle;
  if (within(hue, 52.0f, 10.0f)) return PixelClass::Ball;
  if (within(hue, 134.0f, 20.0f)) return PixelClass::Goal;
  if (within(hue, 316.0f, 16.0f)) return PixelClass::Source;
  if (within(hue, 186.0f, 12.0f)) return PixelClass::Support;
  // Red, kept apart from the player's orange (24°) by a few degrees of hue nothing is drawn in.
  if (within(hue, 358.0f, 8.0f)) return PixelClass::Clearance;
  return PixelClass::Unknown;
}

}  // namespace prep::render::palette
