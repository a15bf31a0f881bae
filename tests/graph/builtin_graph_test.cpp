// The motion graph and player on the built-in library (engine/library).
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "engine/graph/motion_graph.h"
#include "engine/graph/player.h"
#include "engine/motion/pose.h"
#include "engine/library/builtin.h"
#include "tests/graph/builtin_set.h"
#include "tests/graph/graph_checks.h"

using namespace prep;

namespace {
using test::builtin;

// A walk, the walk again, an idle and a walk, placed off the origin: a loop, switches and cross-fades to
// sample across.
Player walk_walk_idle_walk(const MotionGraph& g) {
  const int walk = g.find("walk"), idle = g.find("idle");
  REQUIRE(walk >= 0);
  REQUIRE(idle >= 0);
  Player player(g);
  player.start(walk, -1, FloorTransform{0.7f, glm::vec2(1.5f, -2.0f)});
  player.push(walk);
  player.push(idle);
  player.push(walk);
  REQUIRE(player.switches().size() == 3);
  int faded = 0;
  for (const Player::Switch& s : player.switches()) faded += s.blend_frames > 0;
  REQUIRE(faded > 0);
  return player;
}

void require_same_bits(const Pose& a, const Pose& b) {
  REQUIRE(a.rotations.size() == b.rotations.size());
  REQUIRE(std::memcmp(&a.root_position, &b.root_position, sizeof(glm::vec3)) == 0);
  REQUIRE(std::memcmp(a.rotations.data(), b.rotations.data(), sizeof(glm::quat) * a.rotations.size()) == 0);
}
}  // namespace

TEST_CASE("motion graph: built-in library hierarchy, at least four core nodes") {
  const MotionGraph g = MotionGraph::build(builtin(), Params().graph);
  MESSAGE("built-in graph: " << g.nodes().size() << " nodes, " << g.edges().size() << " edges in " << g.build_seconds() << " s");
  test::check_hierarchy(g, 4);
  // Every core role the controller plays is there.
  for (Role role : {Role::Idle, Role::Walk, Role::TurnLeft, Role::TurnRight}) {
    bool found = false;
    for (const GraphNode& n : g.nodes()) found = found || (n.role == role && n.core);
    CHECK(found);
  }
}

TEST_CASE("player: 200 random actions on the built-in library: no pops, no root jumps") {
  const MotionGraph g = MotionGraph::build(builtin(), Params().graph);
  test::check_random_play(g, 20261122);
}

TEST_CASE("player: a looping walk accumulates its root motion, continuously") {
  const MotionSet& set = builtin();
  const MotionGraph g = MotionGraph::build(set, Params().graph);
  const int walk = g.find("walk");
  REQUIRE(walk >= 0);
  const MotionClip& mc = set.clips[static_cast<size_t>(walk)];
  REQUIRE(mc.cyclic);
  Player player(g);
  player.start(walk);
  for (int k = 0; k < 4; ++k) player.push(walk);  // four more loops
  CHECK(player.switches().size() == 4);
  // Distance per cycle in the clip itself, against the stream's: the stream walks five cycles' worth.
  const float cycle = glm::length(glm::vec2(mc.clip.frames[static_cast<size_t>(mc.loop_last)].root_position.x -
                                                mc.clip.frames[static_cast<size_t>(mc.loop_first)].root_position.x,
                                            mc.clip.frames[static_cast<size_t>(mc.loop_last)].root_position.z -
                                                mc.clip.frames[static_cast<size_t>(mc.loop_first)].root_position.z));
  Pose first, last;
  player.pose_at(0, first);
  player.pose_at(player.frame_count() - 1, last);
  const float travelled = glm::length(glm::vec2(last.root_position.x - first.root_position.x, last.root_position.z - first.root_position.z));
  CHECK(travelled > 4.5f * cycle);
  CHECK(travelled < 5.5f * cycle);
  // Sampling between frames interpolates: halfway between two frames lies between their roots.
  Pose a, b, mid;
  player.pose_at(10, a);
  player.pose_at(11, b);
  player.sample(10.5f / player.fps(), mid);
  CHECK(mid.root_position.z == doctest::Approx(0.5f * (a.root_position.z + b.root_position.z)).epsilon(1e-4));
}

TEST_CASE("player: an action that cannot follow is refused") {
  const MotionGraph g = MotionGraph::build(builtin(), Params().graph);
  Player player(g);
  const int jump = g.find("jump"), kick = g.find("kick");
  REQUIRE(jump >= 0);
  REQUIRE(kick >= 0);
  player.start(jump);
  CHECK_THROWS_AS(player.push(kick), std::invalid_argument);  // no target -> target edges
  for (int n : player.available()) CHECK(g.nodes()[static_cast<size_t>(n)].core);
}

TEST_CASE("player: the root keeps moving through a loop wrap") {
  const MotionSet& set = builtin();
  const MotionGraph g = MotionGraph::build(set, Params().graph);
  const int walk = g.find("walk");
  REQUIRE(walk >= 0);
  Player player(g);
  player.start(walk);
  player.push(walk);
  REQUIRE(player.switches().size() == 1);
  const int wrap = player.switches()[0].stream_frame;
  // Root speed (horizontal) on the frames around the wrap stays within 30% of the clip's mean speed.
  const MotionClip& mc = set.clips[static_cast<size_t>(walk)];
  const glm::vec3 span = mc.clip.frames.back().root_position - mc.clip.frames.front().root_position;
  const float mean = glm::length(glm::vec2(span.x, span.z)) / static_cast<float>(mc.clip.frame_count() - 1);
  Pose a, b;
  for (int f = wrap - 3; f <= wrap + 3; ++f) {
    CAPTURE(f);
    player.pose_at(f, a);
    player.pose_at(f + 1, b);
    const float step = glm::length(glm::vec2(b.root_position.x - a.root_position.x, b.root_position.z - a.root_position.z));
    CHECK(step > 0.7f * mean);
    CHECK(step < 1.3f * mean);
  }
}

TEST_CASE("player: moved on the floor, every segment's samples move with it, the one cross-fading in too") {
  const MotionGraph g = MotionGraph::build(builtin(), Params().graph);
  const int walk = g.find("walk"), idle = g.find("idle");
  REQUIRE(walk >= 0);
  REQUIRE(idle >= 0);
  Player player(g);
  player.start(walk, -1, FloorTransform{0.3f, glm::vec2(-1.0f, 2.0f)});
  player.push(idle);
  REQUIRE(player.switches().size() == 1);
  const float fade = static_cast<float>(player.switches()[0].stream_frame + 1) / player.fps();
  const FloorTransform outer{0.7f, glm::vec2(1.5f, -2.0f)};
  Pose before, after;
  for (float t : {0.1f, 0.45f, fade, fade + 2.0f}) {  // the walk, the fade into the idle, the idle
    CAPTURE(t);
    Player moved = player;
    player.sample(t, before);
    moved.move(outer);
    moved.sample(t, after);
    const glm::vec3 expected = outer.apply(before.root_position);
    CHECK(glm::length(after.root_position - expected) < 1e-5f);
    const glm::quat turned = outer.rotation() * before.rotations[0];
    CHECK(std::abs(glm::dot(after.rotations[0], turned)) > 1.0f - 1e-6f);
    for (size_t j = 1; j < before.rotations.size(); ++j) CHECK(after.rotations[j] == before.rotations[j]);
  }
}

TEST_CASE("player: sampling between two frames is the interpolation of the frames to the bit, across switches and fades") {
  // sample() reads a frame pair inside one clip in place; across a switch or in a cross-fade it goes
  // through pose_at. Either way it must be interpolate(pose_at(i), pose_at(i + 1), w), bit for bit.
  const MotionGraph g = MotionGraph::build(builtin(), Params().graph);
  const Player player = walk_walk_idle_walk(g);
  Pose a, b, expected, sampled;
  for (int frame = 0; frame <= player.frame_count() + 1; ++frame) {
    for (float fraction : {0.0f, 0.25f, 0.5f, 0.999f}) {
      const float t = (static_cast<float>(frame) + fraction) / player.fps();
      const float f = t * player.fps();
      const int i = static_cast<int>(std::floor(f));
      CAPTURE(frame);
      CAPTURE(fraction);
      player.pose_at(i, a);
      player.pose_at(i + 1, b);
      interpolate(a, b, f - static_cast<float>(i), expected);
      player.sample(t, sampled);
      require_same_bits(sampled, expected);
    }
  }
}

TEST_CASE("player: after a move, the root sampled again makes the pose a whole sample gives, to the bit") {
  // A move places the segments anew; sample_root brings a pose sampled before it up to date. At every
  // time, within a clip, across switches and in cross-fades, the result must be sample() after the move.
  const MotionGraph g = MotionGraph::build(builtin(), Params().graph);
  const Player player = walk_walk_idle_walk(g);
  const FloorTransform outer{-0.4f, glm::vec2(0.25f, 0.6f)};
  Pose updated, whole;
  int root_changed = 0;
  for (int frame = 0; frame <= player.frame_count() + 1; ++frame) {
    for (float fraction : {0.0f, 0.3f, 0.999f}) {
      const float t = (static_cast<float>(frame) + fraction) / player.fps();
      CAPTURE(frame);
      CAPTURE(fraction);
      Player moved = player;
      player.sample(t, updated);
      const glm::vec3 root_before = updated.root_position;
      moved.move(outer);
      moved.sample_root(t, updated);
      moved.sample(t, whole);
      root_changed += updated.root_position != root_before;
      require_same_bits(updated, whole);
    }
  }
  CHECK(root_changed > 0);
}

TEST_CASE("player: letting go of what played keeps a few segments and changes no pose") {
  // Two players, the same actions: one forgets what lies behind the time sampled (as a character's stream
  // does every tick), the other keeps everything. Their poses agree to the bit at every tick, moved on the
  // floor along the way, across loop wraps, switches and cross-fades; the forgetful one holds at most a
  // few segments and switches.
  const MotionGraph g = MotionGraph::build(builtin(), Params().graph);
  const int walk = g.find("walk"), idle = g.find("idle");
  REQUIRE(walk >= 0);
  REQUIRE(idle >= 0);
  // Each action is queued once the one before has begun, as the world queues them.
  Player keeping(g), forgetting(g);
  for (Player* p : {&keeping, &forgetting}) p->start(walk, -1, FloorTransform{0.3f, glm::vec2(-1.0f, 2.0f)});
  int queued = 0;
  const FloorTransform nudge{0.002f, glm::vec2(0.001f, -0.0005f)};
  Pose kept, forgot;
  int largest = 0, faded_ticks = 0;
  const float dt = 1.0f / 60.0f;
  int ticks = 0;
  for (int tick = 0; queued < 40 || static_cast<float>(tick) * dt < keeping.duration() - dt; ++tick, ticks = tick) {
    const float t = static_cast<float>(tick) * dt;
    const int frame = static_cast<int>(std::floor(t * keeping.fps()));
    if (queued < 40 && (keeping.switches().empty() || frame >= keeping.switches().back().stream_frame)) {
      for (Player* p : {&keeping, &forgetting}) p->push(queued % 10 == 9 ? idle : walk);
      ++queued;
    }
    forgetting.forget_before(frame);
    if (tick % 7 == 0) {
      keeping.move(nudge);
      forgetting.move(nudge);
    }
    keeping.sample(t, kept);
    forgetting.sample(t, forgot);
    CAPTURE(tick);
    require_same_bits(kept, forgot);
    largest = std::max(largest, forgetting.segment_count());
    for (const Player::Switch& s : keeping.switches()) {
      const int f = static_cast<int>(std::floor(t * keeping.fps()));
      faded_ticks += s.blend_frames > 0 && f >= s.stream_frame && f < s.stream_frame + s.blend_frames;
    }
  }
  REQUIRE(keeping.segment_count() > 40);
  CHECK(faded_ticks > 0);  // cross-fades were sampled after their predecessors' predecessors were let go
  CHECK(largest <= 4);
  CHECK(forgetting.switches().size() <= 4);
  CHECK(forgetting.frame_count() == keeping.frame_count());
  // Frames let go of still read as a pose (the oldest segment held), never out of bounds; those from the
  // last frame forgotten on read as before.
  const int last_forgotten = static_cast<int>(std::floor((static_cast<float>(ticks) - 1.0f) * dt * keeping.fps()));
  for (int frame = 0; frame < keeping.frame_count(); ++frame) {
    CAPTURE(frame);
    forgetting.pose_at(frame, forgot);
    for (const glm::quat& q : forgot.rotations) REQUIRE(std::abs(glm::length(q) - 1.0f) < 1e-5f);
    REQUIRE(std::isfinite(forgot.root_position.x + forgot.root_position.y + forgot.root_position.z));
    if (frame < last_forgotten) continue;
    keeping.pose_at(frame, kept);
    REQUIRE(std::memcmp(kept.rotations.data(), forgot.rotations.data(), sizeof(glm::quat) * kept.rotations.size()) == 0);
  }
}
