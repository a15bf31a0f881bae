// Sec. 4.1: the hierarchical motion graph. Core nodes are the locomotion clips (idle, walk, turns,
// side-steps); target motions (crawl, duck, jump, punches, kick) hang off them: an edge enters a target
// from a core node before its target movement (T_t) and leaves it back to a core node after it. Core
// nodes join each other. Edges are where the switch is kinematically smooth: Kovar et al.'s point-cloud
// distance over a short window of frames, after the best rigid alignment on the floor plane, at local
// minima under GraphParams::threshold.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/motion/motion_set.h"
#include "engine/params/params.h"

namespace prep {

// A rigid motion of the floor plane: rotation by `angle` about +Y, then translation by (x, z).
struct FloorTransform {
  float angle = 0.0f;
  glm::vec2 offset{0.0f};  // (x, z)

  glm::vec3 apply(glm::vec3 p) const;        // a point
  // apply() with the angle's cosine and sine given, taken once for many points: the same arithmetic.
  glm::vec3 apply(glm::vec3 p, float cos_angle, float sin_angle) const;
  glm::quat rotation() const;                 // the rotation, to pre-multiply root rotations by
  FloorTransform then(const FloorTransform& outer) const;  // outer ∘ this
  static FloorTransform identity() { return {}; }
};

struct GraphNode {
  int clip = -1;       // index into MotionSet::clips (node i is clip i)
  std::string name;
  Role role = Role::Walk;
  bool core = false;   // locomotion
};

struct GraphEdge {
  int from = -1, to = -1;   // nodes
  int from_frame = 0;       // leave `from` here: the blend plays from[from_frame ..] against to[to_frame ..]
  int to_frame = 0;
  float distance = 0.0f;    // point-cloud distance over the window (m, RMS over points and frames)
  bool loop = false;        // the cyclic clip's own loop (loop_last + 1 -> loop_first)
  bool forced = false;      // the best candidate, kept above the threshold so that a target stays reachable
  int blend_frames = 0;     // frames of the cross-fade (blend_s; longer for forced edges, in proportion)
  FloorTransform align;     // maps `to`'s clip coordinates onto `from`'s at the transition
};

class MotionGraph {
 public:
  // Builds the graph of a finalized motion set. The set must outlive the graph (it is referred to).
  static MotionGraph build(const MotionSet& set, const GraphParams& params);

  const std::vector<GraphNode>& nodes() const { return nodes_; }
  const std::vector<GraphEdge>& edges() const { return edges_; }
  int find(const std::string& name) const;  // node index or -1

  // Next(m): the motions that may follow m (sorted node indices; m itself when m loops).
  const std::vector<int>& next(int node) const { return next_[static_cast<size_t>(node)]; }
  // Edges leaving `node` (indices into edges()).
  const std::vector<int>& out_edges(int node) const { return out_[static_cast<size_t>(node)]; }

  // The floor-plane alignment that maps clip b's frames [j, j+n) onto clip a's frames [i, i+n) (Kovar's
  // closed form over the point clouds), with n shrunk to what both clips hold (at least one frame).
  FloorTransform align(int a, int i, int b, int j, int n) const;
  // The floor-plane alignment that puts clip b's root at frame j on clip a's root at frame i, facing
  // the same way (facing from the hip joints). Used for edges whose poses differ too much to align well.
  FloorTransform align_roots(int a, int i, int b, int j) const;
  // Distance (m, RMS) of the same windows after the point-cloud alignment.
  float distance(int a, int i, int b, int j, int n) const;
  // The frame of clip `to` (within its loop when cyclic, else any) whose window is nearest by distance()
  // to the window of clip `from` at `from_frame` (the first such frame on ties): where a phase-matched
  // switch enters `to` (MotionStream::switch_to). The scan costs a few hundred thousand operations, so the
  // answer is kept per (from, from_frame, to) in a table shared by all users of the graph (and its copies);
  // several threads may fill it at once, each entry being computed the same way whoever computes it.
  int best_entry_frame(int from, int from_frame, int to) const;
  // best_entry_frame for every frame of every node in `from` into every node in `to`, done ahead: a crowd
  // that meets them for the first time while it runs pays 0.2 ms for each on the frame it happens. Part
  // `part` of `parts` takes every parts-th (from, frame) row, so that threads can share the work.
  void fill_entry_frames(const std::vector<int>& from, const std::vector<int>& to, int part = 0, int parts = 1) const;
  // Whether best_entry_frame's answer for these is in the table already (a look-up, no scan).
  bool entry_frame_known(int from, int from_frame, int to) const;

  float build_seconds() const { return build_seconds_; }
  int candidate_pairs() const { return candidate_pairs_; }  // frame pairs compared while building
  int window_frames() const { return window_frames_; }      // the distance window, in clip frames
  const MotionSet& set() const { return *set_; }

  // Graphviz text: core nodes as boxes, targets as ellipses, one arrow per (from, to) with its edge count.
  std::string to_dot() const;

 private:
  const MotionSet* set_ = nullptr;
  std::vector<GraphNode> nodes_;
  std::vector<GraphEdge> edges_;
  std::vector<std::vector<int>> next_, out_;
  // Point clouds: clouds_[clip][frame * points_ + k], positions of the tracked joints in the clip's space.
  std::vector<std::vector<glm::vec3>> clouds_;
  int points_ = 0;
  int hip_points_[2] = {0, 0};  // where the left and right hip joints are in each frame's cloud
  int window_frames_ = 1;
  int candidate_pairs_ = 0;
  float build_seconds_ = 0.0f;
  struct EntryMemo;
  std::shared_ptr<EntryMemo> entry_memo_;  // best_entry_frame's answers
};

}  // namespace prep
