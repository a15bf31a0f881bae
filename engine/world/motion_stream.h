// One character's motion as it plays: the graph player's stream (Sec. 4.1: clips joined through graph
// edges, root aligned, cross-faded) read at the engine's fixed step, with the clip and frame each moment
// comes from, so that the foot contacts of the played frame are known for synthesis.
//
// The world queues the next motion as soon as the previous queued one has begun (needs_next()): the
// player takes the first edge of the playing clip from its earliest exit on, so queuing early never asks
// for an edge that lies in the past.
//
// The player stays behind this class (its header is not included by world.h), so that the world's users
// see the stream only through the engine tick.
#pragma once

#include <memory>
#include <vector>

#include <glm/vec2.hpp>

#include "engine/graph/motion_graph.h"
#include "engine/motion/contacts.h"
#include "engine/motion/pose.h"

namespace prep {

class Player;

class MotionStream {
 public:
  explicit MotionStream(const MotionGraph& graph);
  ~MotionStream();
  MotionStream(MotionStream&&) noexcept;
  MotionStream& operator=(MotionStream&&) noexcept;

  // Restarts at `node`, clip frame `frame` (-1: its loop start, or 0), placed so that this frame's root
  // stands at `position` (x, z) facing `heading`. Time restarts at 0.
  void start(int node, int frame, glm::vec2 position, float heading);
  // Queues the motion to follow the last queued one; false (and nothing changes) if the graph has no
  // edge for it from there.
  bool queue(int node);
  // Switches to `node` now, at the frame of its loop that best matches the frame playing (the graph's
  // point-cloud distance over its window), placed where `position`/`heading` say; time restarts at 0.
  void switch_to(int node, glm::vec2 position, float heading);
  // Moves the stream on the floor (Player::move) and brings the pose up to the current time's sample
  // (its root; the whole pose if something was queued since it was sampled).
  void move(const FloorTransform& outer);
  // The motions queue() would accept now.
  std::vector<int> available() const;
  // The last queued motion has begun (or none is pending): time to queue the next.
  bool needs_next() const;
  // Whether the stream still holds `seconds` of motion beyond the current time.
  bool has_ahead(float seconds) const;

  void advance(float dt);  // moves the time on and samples the pose there
  // Asks the processor for the memory the next tick reads, one level of pointers at a time
  // (World::prefetch): 0 what the stream points to, 1 and on the player's levels 0 and on.
  void prefetch(int level) const;
  float time() const { return time_; }
  const Pose& pose() const { return pose_; }
  FrameContacts contacts() const;  // of the clip frame playing now (the incoming clip during a blend)
  int node() const;                // the motion playing now
  int clip_frame() const;          // its frame playing now
  int queued_node() const;         // the last motion queued (or started)
  // Stream time at which the last queued motion begins.
  float queued_start() const;

 private:
  struct Piece {
    int stream_first = 0, node = -1, first = 0;
  };
  const Piece& piece_at(int stream_frame) const;
  void sample();
  void forget_played();  // lets go of the pieces and player segments behind the time playing

  static constexpr size_t kHeldPieces = 4;
  const MotionGraph* graph_;
  std::unique_ptr<Player> player_;
  std::vector<Piece> pieces_;
  float time_ = 0.0f;
  Pose pose_;
  bool pose_sampled_ = false;  // pose_ is the player's sample at time_ but for the segments' placement
};

// The floor transform that puts clip frame `frame` of `clip` at `position` facing `heading`.
FloorTransform place_frame(const Clip& clip, int frame, glm::vec2 position, float heading);

}  // namespace prep
