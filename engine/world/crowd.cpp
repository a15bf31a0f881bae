#include "engine/world/crowd.h"

#include <algorithm>
#include <cmath>

#include "engine/util/error.h"
#include "engine/util/huge_pages.h"

namespace prep {
namespace {

// The scenario's contents on the floor: characters, objects (with their half extent) and goal points.
void contents_box(const Scenario& s, glm::vec2& low, glm::vec2& high) {
  low = glm::vec2(1e9f);
  high = glm::vec2(-1e9f);
  auto add = [&](glm::vec2 p, float r) {
    low = glm::min(low, p - glm::vec2(r));
    high = glm::max(high, p + glm::vec2(r));
  };
  for (const ScenarioCharacter& c : s.characters) add(c.position, 0.5f);
  for (const ScenarioObject& o : s.objects) add(o.position, 0.5f * std::max(o.size.x, o.size.z));
  for (const glm::vec2& g : s.goal) add(g, 0.5f);
}

}  // namespace

Crowd::Crowd(const Scenario& lane, std::shared_ptr<const WorldAssets> assets, const CrowdOptions& options)
    : scenario_(lane), assets_(std::move(assets)), options_(options), workers_(std::max(1, options.threads)) {
  const std::string where = lane.file.empty() ? lane.name : lane.file;
  if (options.lanes < 1) throw InputError(where, "a crowd needs at least one lane");
  if (lane.user() < 0) throw InputError(where, "a crowd's lane needs a user character");
  glm::vec2 box_low, box_high;
  contents_box(lane, box_low, box_high);
  const glm::vec2 cell = box_high - box_low + glm::vec2(kLaneMargin + options.start_jitter);
  // About as many lanes across as make the grid square.
  const int n = options.lanes;
  const int columns = std::clamp(static_cast<int>(std::lround(std::sqrt(n * cell.y / cell.x))), 1, n);
  const int rows = (n + columns - 1) / columns;
  const glm::vec2 extent(static_cast<float>(columns) * cell.x, static_cast<float>(rows) * cell.y);
  for (int i = 0; i < n; ++i) {
    const glm::vec2 at(static_cast<float>(i % columns) * cell.x, static_cast<float>(i / columns) * cell.y);
    origins_.push_back(at - 0.5f * extent + 0.5f * cell - 0.5f * (box_low + box_high));
  }
  low_ = -0.5f * extent;
  high_ = 0.5f * extent;
  started_.assign(static_cast<size_t>(n), 0.0f);
  done_for_.assign(static_cast<size_t>(n), 0.0f);
  for (int i = 0; i < n; ++i) random_.emplace_back(options.seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(i));
  fill_entry_frames(*assets_, workers_);
  for (int i = 0; i < n; ++i) worlds_.push_back(make_lane(i));
  back_heap_with_huge_pages();  // every tick walks all lanes' memory (huge_pages.h)
  step_lanes_ = [this](size_t first, size_t last, int) {
    for (size_t i = first; i < last; ++i) {
      prefetch_ahead(worlds_, i, last);
      worlds_[i]->step();
    }
  };
}

void fill_entry_frames(const WorldAssets& assets, FrameWorkers& workers) {
  std::vector<int> from(assets.graph->nodes().size());
  for (size_t n = 0; n < from.size(); ++n) from[n] = static_cast<int>(n);
  const MotionGraph& graph = *assets.graph;
  const int parts = workers.blocks();
  workers.run([&](int part) { graph.fill_entry_frames(from, assets.core_nodes, part, parts); });
}

std::unique_ptr<World> Crowd::make_lane(int i) {
  std::mt19937_64& rng = random_[static_cast<size_t>(i)];
  std::uniform_real_distribution<float> symmetric(-1.0f, 1.0f);
  Scenario s = scenario_;
  const glm::vec2 o = origins_[static_cast<size_t>(i)];
  for (ScenarioCharacter& c : s.characters) c.position += o;
  for (ScenarioObject& ob : s.objects) ob.position += o;
  for (glm::vec2& g : s.goal) g += o;
  ScenarioCharacter& user = s.characters[static_cast<size_t>(s.user())];
  // Along the user's heading (0 faces +z) and across it.
  const glm::vec2 along(std::sin(user.heading), std::cos(user.heading)), across(along.y, -along.x);
  // One draw per statement: the operands of one expression are unsequenced, and compilers differ in the
  // order they evaluate them (the same seed must give the same crowd everywhere).
  const float sideways = symmetric(rng);
  const float forward = symmetric(rng);
  user.position += options_.start_jitter * (forward * along + 0.5f * sideways * across);
  user.heading += options_.heading_jitter * symmetric(rng);
  auto world = std::make_unique<World>(s, assets_);
  world->set_auto(true);
  world->set_stage_timing(false);
  world->set_alpha_history(false);
  world->set_balance_view(false);
  world->hold_decisions(i % kDecisionPhases);
  started_[static_cast<size_t>(i)] = time_;
  done_for_[static_cast<size_t>(i)] = 0.0f;
  return world;
}

void Crowd::step() {
  workers_.run_chunks(worlds_.size(), FrameWorkers::chunk_for(worlds_.size(), workers_.blocks()), step_lanes_);
  const float dt = assets_->params.runtime.fixed_dt;
  time_ += dt;
  for (int i = 0; i < lanes(); ++i) {
    const size_t k = static_cast<size_t>(i);
    done_for_[k] = worlds_[k]->done() ? done_for_[k] + dt : 0.0f;
    if (done_for_[k] >= kLaneRest || time_ - started_[k] >= kLaneTimeout) {
      worlds_[k] = make_lane(i);
      ++restarts_;
    }
  }
}

}  // namespace prep
