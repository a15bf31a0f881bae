#include "engine/world/motion_stream.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "engine/graph/player.h"
#include "engine/util/prefetch.h"

namespace prep {

FloorTransform place_frame(const Clip& clip, int frame, glm::vec2 position, float heading) {
  const Pose& p = clip.frames[static_cast<size_t>(std::clamp(frame, 0, clip.frame_count() - 1))];
  FloorTransform t;
  t.angle = heading - heading_of(p.rotations[0]);
  t.offset = {0.0f, 0.0f};
  const glm::vec3 turned = t.apply(glm::vec3(p.root_position.x, 0.0f, p.root_position.z));
  t.offset = position - glm::vec2(turned.x, turned.z);
  return t;
}

MotionStream::MotionStream(const MotionGraph& graph) : graph_(&graph), player_(std::make_unique<Player>(graph)) {
  pieces_.reserve(kHeldPieces);  // what a stream holds at once (forget_played): its queue never allocates
}
MotionStream::~MotionStream() = default;
MotionStream::MotionStream(MotionStream&&) noexcept = default;
MotionStream& MotionStream::operator=(MotionStream&&) noexcept = default;

void MotionStream::start(int node, int frame, glm::vec2 position, float heading) {
  const MotionClip& mc = graph_->set().clips.at(static_cast<size_t>(node));
  const int first = frame >= 0 ? std::min(frame, mc.clip.frame_count() - 1) : (mc.cyclic ? mc.loop_first : 0);
  player_->start(node, first, place_frame(mc.clip, first, position, heading));
  pieces_.assign(1, Piece{0, node, first});
  time_ = 0.0f;
  sample();
}

bool MotionStream::queue(int node) {
  const size_t before = player_->switches().size();
  try {
    player_->push(PlayerAction{node, -1});
  } catch (const std::invalid_argument&) {
    return false;
  }
  pose_sampled_ = false;  // a switch close ahead may change what the time playing reads
  const auto& switches = player_->switches();
  for (size_t k = before; k < switches.size(); ++k) {
    const GraphEdge& e = graph_->edges()[static_cast<size_t>(switches[k].edge)];
    pieces_.push_back(Piece{switches[k].stream_frame, e.to, e.to_frame});
  }
  return true;
}

void MotionStream::switch_to(int node, glm::vec2 position, float heading) {
  const int from = this->node(), from_frame = clip_frame();
  const int best = graph_->best_entry_frame(from, from_frame, node);  // the nearest window (memoized)
  const auto held = [&](int n) { return !graph_->set().clips[static_cast<size_t>(n)].derived_from.empty(); };
  if (held(from) || held(node)) {
    // A held stand (held_stand.h) does not move: the floor alignment of its window with a moving one turns
    // the new clip by whatever fits a still body best, tens of degrees. Start it where and as the body faces.
    start(node, best, position, heading);
    return;
  }
  // Place the new clip as the graph would across an edge: the floor alignment of the two windows (Kovar's
  // closed form) composed with where the playing clip stands now, then moved to `position` (the
  // synthesized root, which Eq. 3-4 keeps behind the raw locomotion). `heading` only places a clip left
  // from or into a held stand.
  const Pose& raw = graph_->set().clips[static_cast<size_t>(from)].clip.frames[static_cast<size_t>(from_frame)];
  FloorTransform now;
  now.angle = heading_of(pose_.rotations[0]) - heading_of(raw.rotations[0]);
  const glm::vec3 turned = now.apply(glm::vec3(raw.root_position.x, 0.0f, raw.root_position.z));
  now.offset = glm::vec2(pose_.root_position.x, pose_.root_position.z) - glm::vec2(turned.x, turned.z);
  FloorTransform place = graph_->align(from, from_frame, node, best, graph_->window_frames()).then(now);
  place.offset += position - glm::vec2(pose_.root_position.x, pose_.root_position.z);
  player_->start(node, best, place);
  pieces_.assign(1, Piece{0, node, best});
  time_ = 0.0f;
  sample();
}

void MotionStream::move(const FloorTransform& outer) {
  player_->move(outer);
  // A move places the segments anew and nothing else: of the pose sampled at this time only the root
  // changes (a steering correction moves most characters' streams every tick).
  if (pose_sampled_) {
    player_->sample_root(time_, pose_);
  } else {
    sample();
  }
}

std::vector<int> MotionStream::available() const { return player_->available(); }

float MotionStream::queued_start() const {
  return pieces_.empty() ? 0.0f : static_cast<float>(pieces_.back().stream_first) / player_->fps();
}

bool MotionStream::needs_next() const { return time_ * player_->fps() >= static_cast<float>(pieces_.back().stream_first); }

bool MotionStream::has_ahead(float seconds) const { return player_->duration() - time_ >= seconds; }

void MotionStream::advance(float dt) {
  time_ += dt;
  forget_played();
  sample();
}

void MotionStream::forget_played() {
  // Time only moves on (start and switch_to begin a new stream): no frame before the one playing is read
  // again, but the pair sampled starts at floor(frame), and node() / clip_frame() round.
  const int frame = static_cast<int>(std::floor(std::max(0.0f, time_ * player_->fps())));
  player_->forget_before(frame);
  if (pieces_.size() >= 3 && frame >= pieces_[2].stream_first) {
    const Piece* playing = &piece_at(frame);
    pieces_.erase(pieces_.begin(), pieces_.begin() + (playing - pieces_.data()));
  }
}

void MotionStream::sample() {
  player_->sample(time_, pose_);
  pose_sampled_ = true;
}

const MotionStream::Piece& MotionStream::piece_at(int stream_frame) const {
  const auto it = std::upper_bound(pieces_.begin(), pieces_.end(), stream_frame,
                                   [](int f, const Piece& p) { return f < p.stream_first; });
  return it == pieces_.begin() ? pieces_.front() : *(it - 1);
}

int MotionStream::node() const { return piece_at(static_cast<int>(std::lround(time_ * player_->fps()))).node; }

int MotionStream::clip_frame() const {
  const int f = static_cast<int>(std::lround(time_ * player_->fps()));
  const Piece& p = piece_at(f);
  const int frames = graph_->set().clips[static_cast<size_t>(p.node)].clip.frame_count();
  return std::clamp(p.first + (f - p.stream_first), 0, frames - 1);
}

FrameContacts MotionStream::contacts() const {
  // node() and clip_frame() at once: the stream frame rounded and its piece found once.
  const int f = static_cast<int>(std::lround(time_ * player_->fps()));
  const Piece& p = piece_at(f);
  const MotionClip& mc = graph_->set().clips[static_cast<size_t>(p.node)];
  if (mc.contacts.empty()) return FrameContacts{};
  const int frame = std::clamp(p.first + (f - p.stream_first), 0, mc.clip.frame_count() - 1);
  return mc.contacts[static_cast<size_t>(std::clamp(frame, 0, static_cast<int>(mc.contacts.size()) - 1))];
}

int MotionStream::queued_node() const { return pieces_.back().node; }

void MotionStream::prefetch(int level) const {
  if (level == 0) {
    prefetch_vector(pieces_);
    prefetch_vector(pose_.rotations);
  }
  player_->prefetch(level);
}

}  // namespace prep
