#include "app/demo/world_scene.h"

#include <cmath>

#include "app/render/palette.h"

namespace prep::demo {

namespace {

glm::vec3 focus_of(const glm::vec3& root) { return {root.x, 0.9f, root.z}; }

}  // namespace

std::optional<render::ObjectType> render_type(ObjectType t) {
  switch (t) {
    case ObjectType::Ball: return render::ObjectType::Ball;
    case ObjectType::Bar: return render::ObjectType::Bar;
    case ObjectType::Beam: return render::ObjectType::Beam;
    case ObjectType::Hurdle: return render::ObjectType::Hurdle;
    case ObjectType::Opponent: return std::nullopt;  // drawn as a character
  }
  return std::nullopt;
}

render::Scene to_render_scene(const WorldScene& world, bool balance) {
  render::Scene s;
  for (const WorldScene::Character& c : world.characters) {
    render::SceneCharacter rc = render::make_scene_character(
        c.skeleton, *c.pose, c.user ? render::palette::kCharacter : render::palette::kOtherCharacter);
    rc.is_source = c.is_source;
    s.characters.push_back(std::move(rc));
    if (c.user) s.focus = focus_of(c.pose->root_position);
    if (balance) {
      render::BalanceView b;
      b.com = c.com;
      if (c.support) {
        b.support = c.support->hull;
        b.com_inside = !c.support->empty() && c.support->contains({c.com.x, c.com.z});
      }
      s.balance.push_back(std::move(b));
    }
  }
  for (const WorldScene::Object& o : world.objects) {
    const auto type = render_type(o.type);
    if (!type) continue;
    render::SceneObject ro;
    ro.type = *type;
    ro.position = o.position;
    ro.heading = o.heading;
    ro.size = o.size;
    ro.is_source = o.is_source;
    s.objects.push_back(ro);
  }
  s.goal = world.goal;
  s.goal_radius = world.goal_radius;
  s.source = world.source;
  s.source_radius = world.source_radius;
  return s;
}

render::Scene preview_scene(const Scenario& scenario, const WorldAssets* assets, const std::vector<glm::vec2>& goal) {
  render::Scene s;
  for (const ScenarioObject& o : scenario.objects) {
    const auto type = render_type(o.type);
    if (!type) continue;
    render::SceneObject ro;
    ro.type = *type;
    ro.position = {o.position.x, 0.0f, o.position.y};
    ro.heading = o.heading;
    ro.size = o.size;
    s.objects.push_back(ro);
  }
  for (const glm::vec2& g : goal) s.goal.push_back({g.x, 0.0f, g.y});
  const int user = scenario.user();
  if (user >= 0) s.focus = focus_of({scenario.characters[user].position.x, 0.0f, scenario.characters[user].position.y});
  if (!assets || !assets->set || assets->idle_node < 0) return s;
  s.goal_radius = assets->params.reward.goal_radius;
  const Clip& idle = assets->set->clips[static_cast<size_t>(assets->idle_node)].clip;
  if (idle.frames.empty()) return s;
  const Pose& first = idle.frames.front();
  auto stand = [&](glm::vec2 at, float heading, const glm::vec3& colour) {
    Pose p = first;
    // Turn the clip's root about +Y so that it faces `heading`, and put it at `at` (height kept).
    const float turn = heading - heading_of(first.rotations[0]);
    p.rotations[0] = glm::angleAxis(turn, glm::vec3(0.0f, 1.0f, 0.0f)) * first.rotations[0];
    p.root_position = {at.x, first.root_position.y, at.y};
    s.characters.push_back(render::make_scene_character(assets->set->skeleton, p, colour));
  };
  for (int i = 0; i < static_cast<int>(scenario.characters.size()); ++i) {
    const ScenarioCharacter& c = scenario.characters[static_cast<size_t>(i)];
    stand(c.position, c.heading, i == user ? render::palette::kCharacter : render::palette::kOtherCharacter);
  }
  for (const ScenarioObject& o : scenario.objects)
    if (o.type == ObjectType::Opponent) stand(o.position, o.heading, render::palette::kOtherCharacter);
  return s;
}

}  // namespace prep::demo
