// The renderer's colours, chosen so that a screenshot test can tell what a pixel shows by its hue alone:
// lighting and shadows scale all three channels alike (white light, neutral ambient), so the hue and the
// ratio of the channels survive; only brightness changes.
//
//   what                      albedo (display RGB)     hue      class
//   sky (clear colour)        0.64 0.72 0.80           ~210°    low saturation, bright
//   ground + grid             0.60 0.60 0.58 / 0.42    neutral  grey (saturation < 0.15)
//   character (player)        0.92 0.46 0.16           ~24°     orange
//   character (others)        0.56 0.30 0.78           ~272°    violet
//   obstacles (bar/beam/...)  0.18 0.42 0.86           ~218°    blue, saturated
//   ball                      0.95 0.84 0.12           ~52°     yellow
//   goal marker               0.16 0.78 0.30           ~134°    green
//   source of influence       0.95 0.18 0.72           ~316°    magenta (ring on the floor and rim glow)
//   support polygon (overlay) 0.10 0.78 0.86           ~186°    cyan, translucent fill, opaque outline
//   centre of mass (overlay)  white inside the support polygon, red (0.95 0.16 0.12, ~2°) outside
//   clearance view            0.92 0.06 0.10           ~357°    red: body capsules too deep in something
//                                                              (shares its class with the COM marker
//                                                              outside the support: both say "wrong")
//   ImGui windows             ImGui's dark style: window background (0.06, 0.06, 0.06, 0.94)
#pragma once

#include <glm/vec3.hpp>

namespace prep::render::palette {

inline const glm::vec3 kSky{0.64f, 0.72f, 0.80f};
inline const glm::vec3 kGround{0.60f, 0.60f, 0.58f};
inline const glm::vec3 kGridLine{0.42f, 0.42f, 0.41f};
inline const glm::vec3 kCharacter{0.92f, 0.46f, 0.16f};
inline const glm::vec3 kOtherCharacter{0.56f, 0.30f, 0.78f};
inline const glm::vec3 kObstacle{0.18f, 0.42f, 0.86f};
inline const glm::vec3 kBall{0.95f, 0.84f, 0.12f};
inline const glm::vec3 kGoal{0.16f, 0.78f, 0.30f};
inline const glm::vec3 kSource{0.95f, 0.18f, 0.72f};
inline const glm::vec3 kSupport{0.10f, 0.78f, 0.86f};
inline const glm::vec3 kComInside{1.0f, 1.0f, 1.0f};
inline const glm::vec3 kComOutside{0.95f, 0.16f, 0.12f};
inline const glm::vec3 kClearance{0.92f, 0.06f, 0.10f};

enum class PixelClass { Sky, Ground, Character, OtherCharacter, Obstacle, Ball, Goal, Source, Support, Clearance, Dark, Unknown };
const char* pixel_class_name(PixelClass c);

// What a rendered pixel (0-255 RGB) most likely shows, from its hue, saturation and brightness.
PixelClass classify(int r, int g, int b);

}  // namespace prep::render::palette
