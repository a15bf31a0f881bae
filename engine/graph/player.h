// Plays a sequence of actions through the motion graph as one continuous stream of poses with root motion,
// at the clip frame rate, sampled at any time. Each action plays a motion of Next(current); the switch
// follows a graph edge: the next clip is aligned on the floor plane to where the current one is (so root
// position and facing carry on), and the two cross-fade over the edge's blend so that no joint pops.
// Cyclic clips loop over their loop range, root motion accumulating from one cycle to the next.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/graph/motion_graph.h"

namespace prep {

struct PlayerAction {
  int node = -1;         // the motion to play next
  int enter_frame = -1;  // where to enter it (a frame of its clip): the edge entering nearest there is
                         // taken; -1: the edge reached soonest
};

class Player {
 public:
  // The graph (and its motion set) must outlive the player.
  explicit Player(const MotionGraph& graph);

  // Starts a new stream at `node`, at `frame` (-1: its loop start, or frame 0), placed on the floor by
  // `place` (applied to the clip's own coordinates).
  void start(int node, int frame = -1, FloorTransform place = {});

  // Appends an action. Throws std::invalid_argument when the motion cannot follow from where the stream
  // is (not in Next(current), or, in a clip that plays once, no edge left ahead).
  void push(const PlayerAction& action);
  void push(int node) { push(PlayerAction{node, -1}); }
  // The motions push() would accept now: Next(current) minus those whose edges all lie behind.
  std::vector<int> available() const;

  int current_node() const;
  // Moves the whole stream (what played, what plays and what is queued) on the floor by `outer`, applied
  // after each segment's own placement: a steering correction on top of the clips.
  void move(const FloorTransform& outer);
  // Frames in the stream: through the natural end of the last action (its loop end for a cyclic clip).
  int frame_count() const;
  float fps() const { return fps_; }
  float duration() const;

  // The pose at stream frame `frame` (clamped), in world space, and at time t (seconds, interpolated).
  // After forget_before(f), frames before f read as they did while they lie in a segment still held;
  // earlier ones read the oldest segment held (its frames before its start, clamped to the clip).
  void pose_at(int frame, Pose& out) const;
  void sample(float t, Pose& out) const;
  // sample(t, out) of the root alone (out.root_position and out.rotations[0]); the other joints are left
  // as they are. Only the segments' placements act on the root, so after move() this brings a pose that
  // sample(t) gave before the move to the bits sample(t) gives after it, without slerping every joint again.
  void sample_root(float t, Pose& out) const;

  // Stream frames where a switch starts and how long its blend lasts (for tests and displays).
  struct Switch {
    int stream_frame = 0;
    int blend_frames = 0;
    int edge = -1;  // index into the graph's edges
  };
  const std::vector<Switch>& switches() const { return switches_; }
  // Lets go of what no frame from `frame` on reads: the segments before the one playing `frame`, except
  // the one just before it (a cross-fade at the start of a segment reads its predecessor), and their
  // switches. A stream that plays on (a walk looping for minutes) then holds a few segments, not one per
  // cycle, and move() costs the same at any age. Frame numbers and every pose read later are unchanged.
  void forget_before(int frame);
  int segment_count() const { return static_cast<int>(segments_.size()); }
  // Asks the processor for the memory the next sample() reads, one level of pointers at a time
  // (World::prefetch): 0 the player itself, 1 its segments, 2 their sign tables.
  void prefetch(int level) const;

 private:
  struct Segment {
    int node = -1;
    int first = 0;          // clip frames first..last are played
    int last = 0;           // for the open (last) segment: its natural end
    int stream_first = 0;   // stream frame of `first`
    FloorTransform place;   // clip coordinates -> world (set_place)
    // place's cosine, sine and root rotation, taken when it is set rather than for every frame sampled.
    float place_cos = 1.0f, place_sin = 0.0f;
    glm::quat place_rotation{1.0f, 0.0f, 0.0f, 0.0f};
    int blend = 0;          // frames at the start cross-faded with the previous clip ...
    int blend_from = 0;     // ... whose frames blend_from, blend_from + 1, ... keep playing meanwhile
    std::vector<std::int8_t> blend_sign;  // per joint: +-1 so that each rotation's path is fixed at the switch

    void set_place(const FloorTransform& p) {
      place = p;
      place_cos = std::cos(p.angle);
      place_sin = std::sin(p.angle);
      place_rotation = p.rotation();
    }
    glm::vec3 placed(glm::vec3 point) const { return place.apply(point, place_cos, place_sin); }
    glm::quat placed(const glm::quat& root_rotation) const { return glm::normalize(place_rotation * root_rotation); }
  };
  int natural_last(const Segment& s) const;
  int earliest_exit(const Segment& s) const;
  // The edge to take from the open segment to `action`, and whether a loop wrap comes first; -1 if none.
  int choose_edge(const Segment& s, const PlayerAction& action, bool* wrap_first) const;
  void follow(int edge);
  const Pose& clip_frame(const Segment& s, int frame) const;  // the clip's own frame (clamped), not placed
  void recycle_signs(size_t from, size_t to);  // segments [from, to)'s sign tables to spare_signs_
  size_t segment_of(int frame) const;  // the segment playing stream frame `frame` (segments_ not empty, frame >= 0)
  // sample() when stream frames i0 and i0 + 1 lie in one segment past its cross-fade, read from the clip
  // in place; false (nothing written) otherwise.
  // With `root_only`, only out.root_position and out.rotations[0] are written (sample_root).
  bool sample_within_segment(int i0, float w, Pose& out, bool root_only) const;
  // pose_at(frame)'s root position and rotation, without the other joints.
  void root_at(int frame, glm::vec3& position, glm::quat& rotation) const;
  // The same for frame `d` of segment `index` (past its start): placed, and cross-faded from the segment
  // before while its blend lasts.
  void root_of(size_t index, int d, glm::vec3& position, glm::quat& rotation) const;
  // A cross-fade's weight of the incoming segment `s` at its frame `d` (d < s.blend): a smoothstep, so
  // that positions and velocities carry over.
  static float crossfade_weight(const Segment& s, int d) {
    const float x = static_cast<float>(d + 1) / static_cast<float>(s.blend + 1);
    return x * x * (3.0f - 2.0f * x);
  }

  const MotionGraph* graph_;
  float fps_ = 30.0f;
  // Room for the segments and switches a stream holds at once (forget_before keeps a few), reserved up front.
  static constexpr size_t kHeldSegments = 4;
  std::vector<Segment> segments_;
  std::vector<Switch> switches_;
  // Sign tables of segments let go of, for the next switches to fill: a few go round.
  static constexpr size_t kSpareSignTables = 4;
  std::vector<std::vector<std::int8_t>> spare_signs_;
};

}  // namespace prep
