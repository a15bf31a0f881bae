// A crowd's world allocates nothing as it plays: every buffer a tick fills is sized when the world is made
// or the first time it is needed, and kept. Counted by replacing the global operator new of this test
// executable: each allocation on a thread adds one to that thread's count (World::step runs on the thread
// that calls it).
#include <cstdlib>
#include <new>
#include <vector>

#include <doctest/doctest.h>

#include "engine/world/motion_stream.h"
#include "tests/support/paths.h"
#include "tests/world/builtin_assets.h"

// Every form of new and delete but the over-aligned ones is replaced, so that each block is taken and given
// back by the same pair, malloc and free (AddressSanitizer checks the pairing).
namespace {
thread_local long allocations_here = 0;
void* counted_malloc(std::size_t size) noexcept {
  ++allocations_here;
  return std::malloc(size == 0 ? 1 : size);
}
void* counted_new(std::size_t size) {
  if (void* p = counted_malloc(size)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t size) { return counted_new(size); }
void* operator new[](std::size_t size) { return counted_new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return counted_malloc(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return counted_malloc(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace prep {
namespace {

using test::builtin_assets;

// The world as a crowd keeps it (Crowd, the crowd benchmark): no alpha history, no balance view, no stage
// clock.
void as_in_a_crowd(World& world) {
  world.set_alpha_history(false);
  world.set_balance_view(false);
  world.set_stage_timing(false);
}

TEST_CASE("the counter sees an allocation") {
  const long before = allocations_here;
  std::vector<int>* v = new std::vector<int>(100);
  CHECK(allocations_here - before == 2);  // the vector and its buffer
  delete v;
}

TEST_CASE("a stream that plays on allocates nothing from its first switches on: segments and sign tables go round") {
  const auto assets = builtin_assets();
  const MotionGraph& graph = *assets->graph;
  // Walks, turns and steps one after another: every switch a cross-fade between two clips or a loop.
  std::vector<int> sequence;
  for (const char* name : {"walk", "walk", "turn_left", "walk_slow", "step_right", "walk", "turn_right", "idle", "walk"}) {
    sequence.push_back(graph.find(name));
    REQUIRE(sequence.back() >= 0);
  }
  MotionStream stream(graph);
  stream.start(graph.find("idle"), -1, {0.0f, 0.0f}, 0.0f);
  size_t queued = 0;
  const auto play = [&](int ticks) {
    for (int t = 0; t < ticks; ++t) {
      if (stream.needs_next()) {
        REQUIRE(stream.queue(sequence[queued % sequence.size()]));
        ++queued;
      }
      stream.advance(1.0f / 60.0f);
    }
  };
  while (queued <= sequence.size()) play(1);  // once through the sequence: the thread's sampling buffers sized
  const long before = allocations_here;
  const size_t queued_before = queued;
  play(3600);  // a minute
  CHECK(allocations_here - before == 0);
  CHECK(queued - queued_before >= 20);
  // And likewise after a restart (the world restarts the stream when a decision changes the motion).
  stream.switch_to(graph.find("walk"), {1.0f, 2.0f}, 0.5f);
  const long before_restart = allocations_here;
  play(600);
  CHECK(allocations_here - before_restart == 0);
}

TEST_CASE("a crowd's world allocates nothing as it walks to its ball and stands prepared, but its body's capsules once") {
  // As the crowd benchmark's worlds: the kick scenario, the ball as goal and source, launches off.
  const auto make = [] {
    auto world = std::make_unique<World>(load_scenario(test::repo() + "/assets/scenarios/kick.json"), builtin_assets());
    as_in_a_crowd(*world);
    world->set_auto(false);
    return world;
  };
  // A first world sizes this thread's scratch buffers (the graph player's cross-fade poses, the obstacle
  // test's framed capsules), as the first worlds of a crowd do on each of its threads.
  make()->run(15.0f);
  const auto world = make();
  world->step();  // the first tick sizes the world's own buffers
  std::vector<int> allocating_ticks;
  allocating_ticks.reserve(900);
  for (int t = 1; t < 900; ++t) {  // 15 s: the approach, then standing at the ball
    const long before = allocations_here;
    world->step();
    if (allocations_here != before) allocating_ticks.push_back(world->ticks());
  }
  const WorldCharacter& c = world->characters()[0];
  CHECK(glm::distance(c.position, world->scenario().objects[0].position) < 1.0f);  // it got there
  CHECK(c.alpha > 0.5f);                                                           // prepared
  // The one allocation left: the body's capsules, placed (and their buffer made) only once its floor box
  // first comes near the ball (a body clear of every object by its joints alone needs none).
  CHECK(allocating_ticks.size() <= 1);
}

}  // namespace
}  // namespace prep
