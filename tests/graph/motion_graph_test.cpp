#include "engine/graph/motion_graph.h"

#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <string>

#include "engine/graph/player.h"
#include "tests/graph/graph_checks.h"
#include "tests/support/paths.h"

using namespace prep;

namespace {

const MotionSet& manifest(const std::string& name) {
  static std::map<std::string, MotionSet> sets;
  auto it = sets.find(name);
  if (it == sets.end()) it = sets.emplace(name, load_motion_set(test::repo() + "/assets/manifests/" + name + ".json", Params())).first;
  return it->second;
}

}  // namespace

TEST_CASE("floor transform: composition and rotation agree with glm") {
  const FloorTransform inner{0.4f, {1.0f, -2.0f}}, outer{-1.1f, {0.5f, 3.0f}};
  const glm::vec3 p(0.3f, 1.2f, -0.7f);
  const glm::vec3 twice = outer.apply(inner.apply(p));
  const glm::vec3 once = inner.then(outer).apply(p);
  CHECK(once.x == doctest::Approx(twice.x));
  CHECK(once.y == doctest::Approx(twice.y));
  CHECK(once.z == doctest::Approx(twice.z));
  const glm::vec3 by_quat = inner.rotation() * p;
  const glm::vec3 by_apply = inner.apply(p) - glm::vec3(inner.offset.x, 0.0f, inner.offset.y);
  CHECK(by_quat.x == doctest::Approx(by_apply.x));
  CHECK(by_quat.z == doctest::Approx(by_apply.z));
}

TEST_CASE("motion graph: the alignment recovers a clip moved on the floor, at distance zero") {
  // A copy of the cmu31 walk turned by 1 rad and moved: aligning copy onto original gives that motion back.
  MotionSet set = manifest("cmu31");
  const FloorTransform moved{1.0f, {2.0f, -3.0f}};
  MotionClip copy = set.clips[0];
  copy.clip.name = "moved";
  for (Pose& p : copy.clip.frames) {
    p.root_position = moved.apply(p.root_position);
    p.rotations[0] = moved.rotation() * p.rotations[0];
  }
  set.clips.push_back(copy);
  const MotionGraph g = MotionGraph::build(set, Params().graph);
  const int b = static_cast<int>(set.clips.size()) - 1;
  const FloorTransform back = g.align(0, 20, b, 20, 6);  // maps the moved copy onto the original
  const glm::vec3 p(0.4f, 1.0f, 0.9f);
  const glm::vec3 round_trip = back.apply(moved.apply(p));
  CHECK(round_trip.x == doctest::Approx(p.x).epsilon(1e-4));
  CHECK(round_trip.z == doctest::Approx(p.z).epsilon(1e-4));
  CHECK(g.distance(0, 20, b, 20, 6) < 1e-3f);
  // A different frame of the walk (half a cycle on: the other foot forward) is far.
  CHECK(g.distance(0, 20, b, 37, 6) > 0.05f);
}

TEST_CASE("motion graph: cmu31 hierarchy (core: the walk, the two turns steered from it, the recorded left turn)") {
  const MotionSet& set = manifest("cmu31");
  const MotionGraph g = MotionGraph::build(set, Params().graph);
  MESSAGE("cmu31 graph: " << g.nodes().size() << " nodes, " << g.edges().size() << " edges in " << g.build_seconds() << " s");
  test::check_hierarchy(g, 4);
  const int walk = g.find("walk_69_01");
  REQUIRE(walk >= 0);
  CHECK(test::in_next(g, walk, walk));  // the walk loops
  // The steered turns loop, and the walk and they lead into one another (the same poses, turned).
  for (const char* turn : {"turn_left_69_01", "turn_right_69_01"}) {
    CAPTURE(turn);
    const int t = g.find(turn);
    REQUIRE(t >= 0);
    CHECK(test::in_next(g, t, t));
    CHECK(test::in_next(g, walk, t));
    CHECK(test::in_next(g, t, walk));
  }
  // Edges enter a target before T_t and leave it after.
  for (const GraphEdge& e : g.edges()) {
    const MotionClip& to = set.clips[static_cast<size_t>(e.to)];
    const MotionClip& from = set.clips[static_cast<size_t>(e.from)];
    if (!is_locomotion(to.role)) CHECK(e.to_frame <= to.target_frame);
    if (!is_locomotion(from.role)) CHECK(e.from_frame > from.target_frame);
    CHECK(e.blend_frames >= 1);
  }
}

TEST_CASE("motion graph: daz43 hierarchy, at least four core nodes") {
  const MotionSet& set = manifest("daz43");
  const MotionGraph g = MotionGraph::build(set, Params().graph);
  MESSAGE("daz43 graph: " << g.nodes().size() << " nodes, " << g.edges().size() << " edges in " << g.build_seconds() << " s");
  test::check_hierarchy(g, 4);
}

TEST_CASE("motion graph: edges are local minima under the threshold unless forced") {
  const MotionSet& set = manifest("daz43");
  const GraphParams params = Params().graph;
  const MotionGraph g = MotionGraph::build(set, params);
  int forced = 0;
  for (const GraphEdge& e : g.edges()) {
    if (e.loop) continue;
    if (e.forced) {
      ++forced;
      continue;
    }
    CHECK(e.distance < params.threshold);
    // Recomputed at full frame rate over the same window, the distance agrees with the sampled search.
    CHECK(g.distance(e.from, e.from_frame, e.to, e.to_frame, g.window_frames()) == doctest::Approx(e.distance).epsilon(0.3));
  }
  CHECK(forced < static_cast<int>(g.edges().size()) / 10);
  // A lower threshold keeps fewer edges (and the guarantees, through forced ones).
  GraphParams strict = params;
  strict.threshold = 0.5f * params.threshold;
  const MotionGraph h = MotionGraph::build(set, strict);
  CHECK(h.edges().size() < g.edges().size());
  test::check_hierarchy(h, 4);
}

TEST_CASE("player: 200 random actions on the CMU manifests: no pops, no root jumps") {
  for (const char* name : {"cmu31", "daz43"}) {
    CAPTURE(name);
    const MotionGraph g = MotionGraph::build(manifest(name), Params().graph);
    test::check_random_play(g, 20261122);
  }
}

TEST_CASE("graphviz: one node per clip, core nodes as boxes") {
  const MotionGraph g = MotionGraph::build(manifest("cmu31"), Params().graph);
  const std::string dot = g.to_dot();
  CHECK(dot.rfind("digraph", 0) == 0);
  for (const GraphNode& n : g.nodes()) CHECK(dot.find(n.name) != std::string::npos);
  size_t boxes = 0;
  for (size_t at = dot.find("shape=box"); at != std::string::npos; at = dot.find("shape=box", at + 1)) ++boxes;
  CHECK(boxes == 5);  // core: the walk, the two turns steered from it, the recorded left turn, the held stand
}
