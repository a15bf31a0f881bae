// The bridge from the engine's read-only world scene (engine/world, GL-free) to the renderer's Scene.
#pragma once

#include <glm/vec2.hpp>
#include <optional>

#include "app/render/scene.h"
#include "engine/world/world.h"

namespace prep::demo {

// How a world object is drawn (opponents: as characters, not as objects).
std::optional<render::ObjectType> render_type(ObjectType t);

// Characters (the user in palette::kCharacter, the others in kOtherCharacter), obstacles and balls (opponent
// objects are characters), the goal waypoints, the source ring; the focus on the user's root. With
// `balance`, every character's COM and support polygon as well (render::Overlay draws them).
render::Scene to_render_scene(const WorldScene& world, bool balance = false);

// A scenario before its world runs (the motions load, the controller trains): its obstacles and balls
// where the file puts them and the goal; with assets, every character standing in the first frame of the
// idle clip (or the walk) at its position and heading.
render::Scene preview_scene(const Scenario& scenario, const WorldAssets* assets, const std::vector<glm::vec2>& goal);

}  // namespace prep::demo
