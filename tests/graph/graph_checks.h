// Checks shared by the graph tests: the hierarchy's guarantees and a random walk through the player.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/graph/motion_graph.h"
#include "engine/graph/player.h"
#include "engine/motion/kinematics.h"

namespace prep::test {

inline bool in_next(const MotionGraph& g, int a, int b) {
  const auto& n = g.next(a);
  return std::find(n.begin(), n.end(), b) != n.end();
}

// Sec. 4.1: targets launch from walk in one step and return to locomotion; core
// nodes all reach each other.
inline void check_hierarchy(const MotionGraph& g, int min_core) {
  const auto& nodes = g.nodes();
  int core = 0;
  for (const GraphNode& n : nodes) core += n.core ? 1 : 0;
  CHECK(core >= min_core);
  for (size_t t = 0; t < nodes.size(); ++t) {
    if (nodes[t].core) continue;
    CAPTURE(nodes[t].name);
    for (size_t w = 0; w < nodes.size(); ++w)
      if (nodes[w].role == Role::Walk) CHECK(in_next(g, static_cast<int>(w), static_cast<int>(t)));
    bool back = false;
    for (int n : g.next(static_cast<int>(t))) back = back || nodes[static_cast<size_t>(n)].core;
    CHECK(back);
    for (int n : g.next(static_cast<int>(t))) CHECK(nodes[static_cast<size_t>(n)].core);  // no target -> target
  }
  for (size_t a = 0; a < nodes.size(); ++a) {
    if (!nodes[a].core) continue;
    std::vector<bool> seen(nodes.size(), false);
    std::vector<int> stack = {static_cast<int>(a)};
    seen[a] = true;
    while (!stack.empty()) {
      const int u = stack.back();
      stack.pop_back();
      for (int v : g.next(u))
        if (nodes[static_cast<size_t>(v)].core && !seen[static_cast<size_t>(v)]) {
          seen[static_cast<size_t>(v)] = true;
          stack.push_back(v);
        }
    }
    for (size_t b = 0; b < nodes.size(); ++b)
      if (nodes[b].core) {
        CAPTURE(nodes[a].name);
        CAPTURE(nodes[b].name);
        CHECK(seen[b]);
      }
  }
}

struct Speeds {
  float joint = 0;  // largest per-frame joint speed (m/s)
  float root = 0;   // largest per-frame root speed (m/s)
};

// Largest speeds between consecutive poses, every joint of the skeleton.
inline void add_speeds(const Skeleton& sk, const Pose& a, const Pose& b, float fps, Speeds& s) {
  thread_local std::vector<glm::vec3> pa, pb;
  forward_kinematics(sk, a, pa);
  forward_kinematics(sk, b, pb);
  for (size_t j = 0; j < pa.size(); ++j) s.joint = std::max(s.joint, glm::length(pb[j] - pa[j]) * fps);
  s.root = std::max(s.root, glm::length(b.root_position - a.root_position) * fps);
}

inline Speeds clip_speeds(const MotionSet& set) {
  Speeds s;
  for (const MotionClip& mc : set.clips)
    for (int f = 0; f + 1 < mc.clip.frame_count(); ++f)
      add_speeds(*set.skeleton, mc.clip.frames[static_cast<size_t>(f)], mc.clip.frames[static_cast<size_t>(f + 1)], mc.clip.fps, s);
  return s;
}

struct RandomPlay {
  Speeds clips, edges, stream;
  int switches = 0;
  int frames = 0;
};

// Plays `actions` random motions of Next(current) (fixed seed) from the first walk, then measures speeds
// across every switch (the frame before it through the end of its blend) and over the whole stream.
inline RandomPlay random_play(const MotionGraph& g, int actions, std::uint64_t seed) {
  const MotionSet& set = g.set();
  RandomPlay r;
  r.clips = clip_speeds(set);
  int walk = 0;
  for (size_t n = 0; n < g.nodes().size(); ++n)
    if (g.nodes()[n].role == Role::Walk) {
      walk = static_cast<int>(n);
      break;
    }
  Player player(g);
  player.start(walk);
  std::mt19937_64 rng(seed);
  for (int k = 0; k < actions; ++k) {
    const std::vector<int> options = player.available();
    REQUIRE(!options.empty());
    player.push(options[std::uniform_int_distribution<size_t>(0, options.size() - 1)(rng)]);
  }
  r.switches = static_cast<int>(player.switches().size());
  r.frames = player.frame_count();
  std::vector<bool> across(static_cast<size_t>(r.frames), false);
  for (const Player::Switch& s : player.switches())
    for (int f = std::max(0, s.stream_frame - 1); f <= s.stream_frame + s.blend_frames && f < r.frames; ++f)
      across[static_cast<size_t>(f)] = true;
  Pose a, b;
  player.pose_at(0, a);
  for (int f = 0; f + 1 < r.frames; ++f) {
    player.pose_at(f + 1, b);
    Speeds one;
    add_speeds(*set.skeleton, a, b, player.fps(), one);
    if (across[static_cast<size_t>(f)]) {
      r.edges.joint = std::max(r.edges.joint, one.joint);
      r.edges.root = std::max(r.edges.root, one.root);
    }
    r.stream.joint = std::max(r.stream.joint, one.joint);
    r.stream.root = std::max(r.stream.root, one.root);
    std::swap(a, b);
  }
  return r;
}

inline void check_random_play(const MotionGraph& g, std::uint64_t seed) {
  const RandomPlay r = random_play(g, 200, seed);
  MESSAGE(g.set().name << ": " << r.switches << " switches, " << r.frames << " frames; joint speed max clips "
                       << r.clips.joint << " edges " << r.edges.joint << " stream " << r.stream.joint << " m/s; root clips "
                       << r.clips.root << " edges " << r.edges.root << " stream " << r.stream.root << " m/s");
  CHECK(r.switches >= 200);
  CHECK(r.edges.joint <= 1.5f * r.clips.joint);
  CHECK(r.edges.root <= 1.5f * r.clips.root);
  CHECK(r.stream.joint <= 1.5f * r.clips.joint);
  CHECK(r.stream.root <= 1.5f * r.clips.root);
}

}  // namespace prep::test
