// MotionGraph::best_entry_frame: the memoized phase match of a core switch gives what the full scan gives.
#include <doctest/doctest.h>

#include <limits>
#include <thread>
#include <vector>

#include "engine/graph/motion_graph.h"
#include "engine/library/builtin.h"

using namespace prep;

namespace {

int scan(const MotionGraph& g, int from, int frame, int to) {
  const MotionClip& mc = g.set().clips[static_cast<size_t>(to)];
  const int first = mc.cyclic ? mc.loop_first : 0, last = mc.cyclic ? mc.loop_last : mc.clip.frame_count() - 1;
  int best = first;
  float best_d = std::numeric_limits<float>::infinity();
  for (int j = first; j <= last; ++j) {
    const float d = g.distance(from, frame, to, j, g.window_frames());
    if (d < best_d) best_d = d, best = j;
  }
  return best;
}

}  // namespace

TEST_CASE("best_entry_frame equals the full scan, the first time and from the table, from two threads at once") {
  const MotionSet set = make_builtin_motion_set(Params{});
  const MotionGraph g = MotionGraph::build(set, Params{}.graph);
  std::vector<int> core;
  for (const GraphNode& n : g.nodes())
    if (n.core) core.push_back(n.clip);
  REQUIRE(core.size() >= 3);
  struct Query {
    int from, frame, to, expected;
  };
  std::vector<Query> queries;
  for (int from : core)
    for (int to : core)
      for (int frame = 0; frame < set.clips[static_cast<size_t>(from)].clip.frame_count(); frame += 29)
        queries.push_back({from, frame, to, scan(g, from, frame, to)});
  // Two threads fill the table concurrently (each query twice), then it is read back.
  std::vector<int> a(queries.size()), b(queries.size());
  std::thread other([&] {
    for (size_t k = 0; k < queries.size(); ++k) b[k] = g.best_entry_frame(queries[k].from, queries[k].frame, queries[k].to);
  });
  for (size_t k = 0; k < queries.size(); ++k) a[k] = g.best_entry_frame(queries[k].from, queries[k].frame, queries[k].to);
  other.join();
  const MotionGraph copy = g;  // copies share the table
  for (size_t k = 0; k < queries.size(); ++k) {
    CAPTURE(k);
    CHECK(a[k] == queries[k].expected);
    CHECK(b[k] == queries[k].expected);
    CHECK(copy.best_entry_frame(queries[k].from, queries[k].frame, queries[k].to) == queries[k].expected);
  }
}

TEST_CASE("fill_entry_frames: two parts fill every row ahead, with what the full scan gives") {
  const MotionSet set = make_builtin_motion_set(Params{});
  const MotionGraph g = MotionGraph::build(set, Params{}.graph);
  std::vector<int> core, all;
  for (const GraphNode& n : g.nodes()) {
    all.push_back(n.clip);
    if (n.core) core.push_back(n.clip);
  }
  std::thread other([&] { g.fill_entry_frames(all, core, 1, 2); });
  g.fill_entry_frames(all, core, 0, 2);
  other.join();
  // Every answer is in the table before anyone asks, in rows of both parts.
  int known = 0, unknown = 0;
  for (int from : all)
    for (int frame = 0; frame < set.clips[static_cast<size_t>(from)].clip.frame_count(); ++frame)
      for (int to : core) (g.entry_frame_known(from, frame, to) ? known : unknown)++;
  CHECK(known > 1000);
  CHECK(unknown == 0);
  const MotionGraph fresh = MotionGraph::build(set, Params{}.graph);  // its own table: nothing known yet
  CHECK_FALSE(fresh.entry_frame_known(all.back(), 0, core.front()));
  // And they are the full scan's, sampled across rows both parts filled.
  for (int from : all)
    for (int frame = 0; frame < set.clips[static_cast<size_t>(from)].clip.frame_count(); frame += 37)
      for (int to : core) {
        CAPTURE(from);
        CAPTURE(frame);
        CHECK(g.best_entry_frame(from, frame, to) == scan(g, from, frame, to));
      }
}
