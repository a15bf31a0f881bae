#include "engine/graph/player.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "engine/motion/slerp.h"
#include "engine/util/prefetch.h"

namespace prep {

Player::Player(const MotionGraph& graph) : graph_(&graph) {
  if (!graph.set().clips.empty()) fps_ = graph.set().clips.front().clip.fps;
  // Room for what a stream holds at once (forget_before keeps a few segments), and sign tables ready to
  // fill: a stream allocates nothing as it plays.
  segments_.reserve(kHeldSegments);
  switches_.reserve(kHeldSegments);
  const size_t joints = graph.set().skeleton ? static_cast<size_t>(graph.set().skeleton->size()) : 0;
  spare_signs_.resize(kSpareSignTables);
  for (std::vector<std::int8_t>& table : spare_signs_) table.reserve(joints);
}

int Player::natural_last(const Segment& s) const {
  const MotionClip& mc = graph_->set().clips[static_cast<size_t>(s.node)];
  if (mc.cyclic && s.first <= mc.loop_last) return mc.loop_last;
  return std::max(s.first, mc.clip.frame_count() - 1);
}

int Player::earliest_exit(const Segment& s) const { return s.first + std::max(1, s.blend); }

void Player::move(const FloorTransform& outer) {
  for (Segment& s : segments_) s.set_place(s.place.then(outer));
}

void Player::start(int node, int frame, FloorTransform place) {
  if (node < 0 || node >= static_cast<int>(graph_->nodes().size()))
    throw std::invalid_argument("player: no motion " + std::to_string(node));
  const MotionClip& mc = graph_->set().clips[static_cast<size_t>(node)];
  if (mc.clip.frame_count() == 0) throw std::invalid_argument("player: motion '" + mc.clip.name + "' has no frames");
  Segment s;
  s.node = node;
  s.first = frame >= 0 ? std::min(frame, mc.clip.frame_count() - 1) : (mc.cyclic ? mc.loop_first : 0);
  s.set_place(place);
  s.last = natural_last(s);
  recycle_signs(0, segments_.size());
  segments_.assign(1, s);
  switches_.clear();
}

int Player::choose_edge(const Segment& s, const PlayerAction& action, bool* wrap_first) const {
  const MotionClip& mc = graph_->set().clips[static_cast<size_t>(s.node)];
  const bool loops = mc.cyclic && s.first <= mc.loop_last;
  const int earliest = earliest_exit(s);
  int loop_edge = -1;
  for (int k : graph_->out_edges(s.node))
    if (graph_->edges()[static_cast<size_t>(k)].loop) loop_edge = k;
  // Frames from the earliest exit to loop_last, then from the wrapped segment's earliest exit.
  const int wrapped_earliest =
      loop_edge >= 0 ? mc.loop_first + std::max(1, graph_->edges()[static_cast<size_t>(loop_edge)].blend_frames) : 0;

  int best = -1;
  bool best_wrap = false;
  long best_miss = std::numeric_limits<long>::max(), best_cost = std::numeric_limits<long>::max();
  for (int k : graph_->out_edges(s.node)) {
    const GraphEdge& e = graph_->edges()[static_cast<size_t>(k)];
    if (e.to != action.node) continue;
    long cost = -1;
    bool wrap = false;
    if (e.loop) {
      if (loops && earliest <= e.from_frame) cost = e.from_frame - earliest;
    } else if (e.from_frame >= earliest && e.from_frame <= s.last) {
      cost = e.from_frame - earliest;
    } else if (loops && loop_edge >= 0 && e.from_frame >= wrapped_earliest && e.from_frame <= mc.loop_last) {
      cost = (mc.loop_last + 1 - earliest) + (e.from_frame - mc.loop_first);
      wrap = true;
    }
    if (cost < 0) continue;
    const long miss = action.enter_frame >= 0 ? std::labs(static_cast<long>(e.to_frame - action.enter_frame)) : 0;
    if (miss < best_miss || (miss == best_miss && cost < best_cost)) {
      best = k;
      best_wrap = wrap;
      best_miss = miss;
      best_cost = cost;
    }
  }
  if (wrap_first) *wrap_first = best_wrap;
  return best;
}

void Player::follow(int edge) {
  const GraphEdge& e = graph_->edges()[static_cast<size_t>(edge)];
  Segment& cur = segments_.back();
  cur.last = e.from_frame - 1;
  Segment next;
  next.node = e.to;
  next.first = e.to_frame;
  next.stream_first = cur.stream_first + (cur.last - cur.first + 1);
  next.set_place(e.align.then(cur.place));  // the next clip -> the current clip's coordinates -> world
  next.blend = e.blend_frames;
  next.blend_from = e.from_frame;
  next.last = natural_last(next);
  // Each joint's cross-fade takes the shorter arc as it stands at the switch and keeps that arc for the
  // whole blend: choosing it anew each frame would jump to the other arc when two rotations about half
  // a turn apart (a crawling leg against a walking one) cross the quarter-turn mark. The two frames are
  // read where the clips hold them (pose_at's rotations: the root placed, every other joint as recorded),
  // and the signs go into the table of a segment let go of (forget_before, start): a stream that plays on
  // allocates nothing.
  const std::vector<glm::quat>& a = clip_frame(cur, e.from_frame).rotations;
  const std::vector<glm::quat>& b = clip_frame(next, next.first).rotations;
  if (!spare_signs_.empty()) {
    next.blend_sign = std::move(spare_signs_.back());
    spare_signs_.pop_back();
  }
  const auto sign = [](float d) { return static_cast<std::int8_t>(d < 0.0f ? -1 : 1); };
  next.blend_sign.resize(a.size());
  for (size_t j = 1; j < a.size(); ++j) next.blend_sign[j] = sign(glm::dot(a[j], b[j]));
  if (!a.empty()) next.blend_sign[0] = sign(glm::dot(cur.placed(a[0]), next.placed(b[0])));  // the roots as placed
  switches_.push_back({next.stream_first, next.blend, edge});
  segments_.push_back(std::move(next));
}

void Player::push(const PlayerAction& action) {
  if (segments_.empty()) {
    start(action.node, action.enter_frame);
    return;
  }
  bool wrap = false;
  const int edge = choose_edge(segments_.back(), action, &wrap);
  if (edge < 0) {
    const auto& nodes = graph_->nodes();
    const std::string to = action.node >= 0 && action.node < static_cast<int>(nodes.size()) ? nodes[static_cast<size_t>(action.node)].name
                                                                                            : std::to_string(action.node);
    throw std::invalid_argument("player: '" + to + "' cannot follow '" + nodes[static_cast<size_t>(current_node())].name +
                                "' from frame " + std::to_string(segments_.back().first));
  }
  if (wrap) {
    for (int k : graph_->out_edges(current_node()))
      if (graph_->edges()[static_cast<size_t>(k)].loop) {
        follow(k);
        break;
      }
  }
  follow(edge);
}

std::vector<int> Player::available() const {
  std::vector<int> out;
  if (segments_.empty()) return out;
  for (int n : graph_->next(current_node()))
    if (choose_edge(segments_.back(), PlayerAction{n, -1}, nullptr) >= 0) out.push_back(n);
  return out;
}

int Player::current_node() const { return segments_.empty() ? -1 : segments_.back().node; }

int Player::frame_count() const {
  if (segments_.empty()) return 0;
  const Segment& s = segments_.back();
  return s.stream_first + (s.last - s.first + 1);
}

float Player::duration() const { return frame_count() > 0 ? static_cast<float>(frame_count() - 1) / fps_ : 0.0f; }

const Pose& Player::clip_frame(const Segment& s, int frame) const {
  const Clip& clip = graph_->set().clips[static_cast<size_t>(s.node)].clip;
  return clip.frames[static_cast<size_t>(std::clamp(frame, 0, clip.frame_count() - 1))];
}

size_t Player::segment_of(int frame) const {
  const auto it = std::upper_bound(segments_.begin(), segments_.end(), frame,
                                   [](int f, const Segment& s) { return f < s.stream_first; });
  // A frame before the segments held (let go of by forget_before) reads the oldest one held.
  return it == segments_.begin() ? 0 : static_cast<size_t>(it - segments_.begin()) - 1;
}

void Player::recycle_signs(size_t from, size_t to) {
  for (size_t i = from; i < to && spare_signs_.size() < kSpareSignTables; ++i)
    if (segments_[i].blend_sign.capacity() > 0) spare_signs_.push_back(std::move(segments_[i].blend_sign));
}

void Player::forget_before(int frame) {
  if (segments_.size() < 3 || frame < segments_[2].stream_first) return;
  const size_t keep_from = segment_of(frame) - 1;
  const int first_kept = segments_[keep_from].stream_first;
  recycle_signs(0, keep_from);
  segments_.erase(segments_.begin(), segments_.begin() + static_cast<std::ptrdiff_t>(keep_from));
  const auto played = std::find_if(switches_.begin(), switches_.end(), [&](const Switch& s) { return s.stream_frame >= first_kept; });
  switches_.erase(switches_.begin(), played);
}

void Player::pose_at(int frame, Pose& out) const {
  if (segments_.empty()) {
    out = Pose();
    return;
  }
  frame = std::clamp(frame, 0, frame_count() - 1);
  const size_t index = segment_of(frame);
  const Segment& s = segments_[index];
  const int d = frame - s.stream_first;
  out = clip_frame(s, s.first + d);
  root_of(index, d, out.root_position, out.rotations[0]);
  if (d < s.blend && index > 0) {
    // The other joints cross-fade as the root does (root_of), each as its clip records it.
    const Pose& previous = clip_frame(segments_[index - 1], s.blend_from + d);
    const float w = crossfade_weight(s, d);
    for (size_t j = 1; j < out.rotations.size(); ++j)  // glm::mix: slerp along the arc the signs give
      out.rotations[j] = glm::normalize(glm::mix(previous.rotations[j], out.rotations[j] * static_cast<float>(s.blend_sign[j]), w));
  }
}

void Player::sample(float t, Pose& out) const {
  const float f = std::max(0.0f, t * fps_);
  const int i0 = static_cast<int>(std::floor(f));
  const float w = f - static_cast<float>(i0);
  if (sample_within_segment(i0, w, out, false)) return;
  thread_local Pose a, b;
  pose_at(i0, a);
  pose_at(i0 + 1, b);
  interpolate(a, b, w, out);
}

void Player::sample_root(float t, Pose& out) const {
  if (segments_.empty() || out.rotations.empty()) {
    sample(t, out);
    return;
  }
  // sample()'s arithmetic for the root alone: interpolate() slerps each rotation alone or in a group of
  // four to the same bits (slerp.h), so the root's slerp on its own is the one sample() takes.
  const float f = std::max(0.0f, t * fps_);
  const int i0 = static_cast<int>(std::floor(f));
  const float w = f - static_cast<float>(i0);
  if (sample_within_segment(i0, w, out, true)) return;
  glm::vec3 position_a, position_b;
  glm::quat rotation_a, rotation_b;
  root_at(i0, position_a, rotation_a);
  root_at(i0 + 1, position_b, rotation_b);
  out.root_position = position_a + (position_b - position_a) * w;
  out.rotations[0] = slerp_shorter(rotation_a, rotation_b, w);
}

void Player::root_at(int frame, glm::vec3& position, glm::quat& rotation) const {
  frame = std::clamp(frame, 0, frame_count() - 1);
  const size_t index = segment_of(frame);
  root_of(index, frame - segments_[index].stream_first, position, rotation);
}

void Player::root_of(size_t index, int d, glm::vec3& position, glm::quat& rotation) const {
  const Segment& s = segments_[index];
  const Pose& own = clip_frame(s, s.first + d);
  position = s.placed(own.root_position);
  rotation = s.placed(own.rotations[0]);
  if (d < s.blend && index > 0) {
    // Cross-fade: the previous clip keeps playing past the switch while the next one fades in along a
    // smoothstep, so both positions and velocities carry over.
    const Segment& before = segments_[index - 1];
    const Pose& previous = clip_frame(before, s.blend_from + d);
    const glm::vec3 previous_position = before.placed(previous.root_position);
    const glm::quat previous_rotation = before.placed(previous.rotations[0]);
    const float w = crossfade_weight(s, d);
    position = previous_position + (position - previous_position) * w;
    rotation = glm::normalize(glm::mix(previous_rotation, rotation * static_cast<float>(s.blend_sign[0]), w));
  }
}

bool Player::sample_within_segment(int i0, float w, Pose& out, bool root_only) const {
  if (segments_.empty()) return false;
  const int f0 = std::clamp(i0, 0, frame_count() - 1), f1 = std::clamp(i0 + 1, 0, frame_count() - 1);
  const size_t index = segment_of(f0);
  const Segment& s = segments_[index];
  const int d0 = f0 - s.stream_first;
  if (d0 < s.blend && index > 0) return false;                                                // cross-fading
  if (index + 1 < segments_.size() && f1 >= segments_[index + 1].stream_first) return false;  // the next clip
  // interpolate(pose_at(i0), pose_at(i0 + 1), w) without the two copies: only the root is placed, every
  // other joint is the clip's. Each rotation's slerp is the same alone as in a group of four
  // (engine/motion/slerp.h), so the root can be taken apart from the rest.
  const Clip& clip = graph_->set().clips[static_cast<size_t>(s.node)].clip;
  const int last = clip.frame_count() - 1;
  const Pose& a = clip.frames[static_cast<size_t>(std::clamp(s.first + d0, 0, last))];
  const Pose& b = clip.frames[static_cast<size_t>(std::clamp(s.first + f1 - s.stream_first, 0, last))];
  const glm::vec3 root_a = s.placed(a.root_position), root_b = s.placed(b.root_position);
  out.root_position = root_a + (root_b - root_a) * w;
  const size_t n = a.rotations.size();
  if (!root_only) out.rotations.resize(n);
  if (n == 0) return true;
  out.rotations[0] = slerp_shorter(s.placed(a.rotations[0]), s.placed(b.rotations[0]), w);
  if (!root_only) slerp_shorter(a.rotations.data() + 1, b.rotations.data() + 1, w, out.rotations.data() + 1, n - 1);
  return true;
}

void Player::prefetch(int level) const {
  if (level == 0) prefetch_object(*this);
  if (level == 1) prefetch_vector(segments_);
  if (level == 2)  // a stream holds only a few segments (forget_before)
    for (const Segment& s : segments_) prefetch_vector(s.blend_sign);
}

}  // namespace prep
