// A character's motion stream (engine/world/motion_stream.h) as the world drives it.
#include <cstring>
#include <vector>

#include <doctest/doctest.h>

#include "engine/world/motion_stream.h"
#include "tests/world/builtin_assets.h"

using namespace prep;
using prep::test::builtin_assets;

TEST_CASE("a stream moved on the floor holds the pose a whole sample at its time gives, to the bit") {
  // As the world steers: each tick the stream advances, then a correction moves it (turning and sliding)
  // and only the root is sampled again. A twin stream, given the same ticks, samples its whole pose again
  // after each move (advance by no time). Some moves follow a queue with no advance between, where the
  // moved stream must sample its whole pose too.
  const auto assets = builtin_assets();
  const MotionGraph& graph = *assets->graph;
  std::vector<int> sequence;
  for (const char* name : {"walk", "turn_left", "walk", "step_right", "idle", "walk_slow", "turn_right", "walk"}) {
    sequence.push_back(graph.find(name));
    REQUIRE(sequence.back() >= 0);
  }
  MotionStream moved(graph), whole(graph);
  for (MotionStream* s : {&moved, &whole}) s->start(graph.find("idle"), -1, {0.5f, -1.0f}, 0.3f);
  size_t queued = 0;
  int moves = 0, moves_after_queue = 0;
  const float dt = 1.0f / 60.0f;
  for (int tick = 0; tick < 1800; ++tick) {
    CAPTURE(tick);
    const bool queue_now = moved.needs_next();
    const bool move_before_advance = queue_now && queued % 3 == 1;  // queued, then moved with no sample between
    if (queue_now) {
      for (MotionStream* s : {&moved, &whole}) REQUIRE(s->queue(sequence[queued % sequence.size()]));
      ++queued;
    }
    FloorTransform correction;
    correction.angle = 0.01f * static_cast<float>(tick % 5 - 2);
    correction.offset = glm::vec2(0.002f * static_cast<float>(tick % 3), -0.001f);
    if (move_before_advance) {
      moved.move(correction);
      whole.move(correction);
      whole.advance(0.0f);
      ++moves_after_queue;
    }
    for (MotionStream* s : {&moved, &whole}) s->advance(dt);
    if (tick % 4 != 3) {
      moved.move(correction);
      whole.move(correction);
      whole.advance(0.0f);
      ++moves;
    }
    const Pose& a = moved.pose();
    const Pose& b = whole.pose();
    REQUIRE(a.rotations.size() == b.rotations.size());
    REQUIRE(std::memcmp(&a.root_position, &b.root_position, sizeof(glm::vec3)) == 0);
    REQUIRE(std::memcmp(a.rotations.data(), b.rotations.data(), sizeof(glm::quat) * a.rotations.size()) == 0);
  }
  CHECK(queued >= 12);
  CHECK(moves > 1000);
  CHECK(moves_after_queue >= 4);
}

TEST_CASE("a stream moved right after a queue whose switch comes next frame samples its whole pose") {
  // A switch queued to begin at the next clip frame changes what the time playing reads (the frame pair
  // sampled spans the switch), so a move after it cannot keep the joints it sampled before.
  const auto assets = builtin_assets();
  const MotionGraph& graph = *assets->graph;
  const int walk = graph.find("walk"), idle = graph.find("idle");
  REQUIRE(walk >= 0);
  REQUIRE(idle >= 0);
  const float dt = 1.0f / 60.0f;
  int changed_by_queue = 0;
  for (int start_frame = 0; start_frame < 40; ++start_frame) {
    for (int ticks = 1; ticks < 40; ++ticks) {
      CAPTURE(start_frame);
      CAPTURE(ticks);
      MotionStream moved(graph), whole(graph);
      for (MotionStream* s : {&moved, &whole}) {
        s->start(walk, start_frame, {0.0f, 0.0f}, 0.0f);
        for (int t = 0; t < ticks; ++t) s->advance(dt);
      }
      const Pose before = moved.pose();
      for (MotionStream* s : {&moved, &whole}) {
        if (!s->queue(idle)) break;
        s->move(FloorTransform{0.05f, glm::vec2(0.01f, 0.0f)});
      }
      whole.advance(0.0f);
      changed_by_queue += std::memcmp(before.rotations.data() + 1, whole.pose().rotations.data() + 1,
                                      sizeof(glm::quat) * (before.rotations.size() - 1)) != 0;
      REQUIRE(std::memcmp(moved.pose().rotations.data(), whole.pose().rotations.data(),
                          sizeof(glm::quat) * whole.pose().rotations.size()) == 0);
    }
  }
  CHECK(changed_by_queue > 0);
}
