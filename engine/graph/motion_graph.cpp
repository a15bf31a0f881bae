#include "engine/graph/motion_graph.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "engine/motion/kinematics.h"

namespace prep {

glm::vec3 FloorTransform::apply(glm::vec3 p) const { return apply(p, std::cos(angle), std::sin(angle)); }

glm::vec3 FloorTransform::apply(glm::vec3 p, float c, float s) const {
  // Rotation about +Y by `angle` (as glm::angleAxis(angle, Y)): (x, z) -> (x c + z s, -x s + z c).
  return {p.x * c + p.z * s + offset.x, p.y, -p.x * s + p.z * c + offset.y};
}

glm::quat FloorTransform::rotation() const { return glm::angleAxis(angle, glm::vec3(0.0f, 1.0f, 0.0f)); }

FloorTransform FloorTransform::then(const FloorTransform& outer) const {
  FloorTransform out;
  out.angle = angle + outer.angle;
  const glm::vec3 t = outer.apply(glm::vec3(offset.x, 0.0f, offset.y));
  out.offset = {t.x, t.z};
  return out;
}

namespace {

// Candidate frames are compared at about this rate whatever the capture rate (Kovar et al. sample too):
// a 120 fps clip is searched every 4th frame. Windows still span GraphParams::window_s.
constexpr float kSearchRate = 30.0f;
// Local minima kept per ordered pair of clips (the best ones): enough choice of where to switch.
constexpr int kMaxEdgesPerPair = 8;

// Sums over the points of one frame (per-frame statistics of a cloud).
struct FrameStats {
  float sxz = 0;  // sum of x^2 + z^2
  float sy = 0;   // sum of y^2
  float cx = 0, cz = 0;  // sums of x and z
};

// Sums over the points of a pair of frames p (of clip a) and q (of clip b).
struct PairStats {
  float a = 0;   // sum of px qx + pz qz
  float b = 0;   // sum of px qz - pz qx
  float yy = 0;  // sum of py qy
  PairStats& operator+=(const PairStats& o) {
    a += o.a;
    b += o.b;
    yy += o.yy;
    return *this;
  }
};

struct WindowSums {
  PairStats pair;
  FrameStats p, q;
  int count = 0;  // points x frames
};

// Kovar et al.'s closed form: the rotation about Y and floor translation that best map q onto p, and the
// remaining squared distance. Heights are compared as they are (both clips stand on y = 0).
void solve(const WindowSums& w, FloorTransform* align, float* squared) {
  const float n = static_cast<float>(w.count);
  const float pcx = w.p.cx / n, pcz = w.p.cz / n, qcx = w.q.cx / n, qcz = w.q.cz / n;
  const float a = w.pair.a - n * (pcx * qcx + pcz * qcz);  // centred sums
  const float b = w.pair.b - n * (pcx * qcz - pcz * qcx);
  const float angle = std::atan2(b, a);
  if (align) {
    align->angle = angle;
    const float c = std::cos(angle), s = std::sin(angle);
    align->offset = {pcx - (qcx * c + qcz * s), pcz - (-qcx * s + qcz * c)};
  }
  if (squared) {
    const float pp = w.p.sxz - n * (pcx * pcx + pcz * pcz);
    const float qq = w.q.sxz - n * (qcx * qcx + qcz * qcz);
    const float xz = pp + qq - 2.0f * std::sqrt(a * a + b * b);
    const float y = w.p.sy + w.q.sy - 2.0f * w.pair.yy;
    *squared = std::max(0.0f, xz + y);
  }
}

FrameStats frame_stats(const glm::vec3* p, int n) {
  FrameStats s;
  for (int k = 0; k < n; ++k) {
    s.sxz += p[k].x * p[k].x + p[k].z * p[k].z;
    s.sy += p[k].y * p[k].y;
    s.cx += p[k].x;
    s.cz += p[k].z;
  }
  return s;
}

PairStats pair_stats(const glm::vec3* p, const glm::vec3* q, int n) {
  PairStats s;
  for (int k = 0; k < n; ++k) {
    s.a += p[k].x * q[k].x + p[k].z * q[k].z;
    s.b += p[k].x * q[k].z - p[k].z * q[k].x;
    s.yy += p[k].y * q[k].y;
  }
  return s;
}

void add(FrameStats& s, const FrameStats& o) {
  s.sxz += o.sxz;
  s.sy += o.sy;
  s.cx += o.cx;
  s.cz += o.cz;
}

// Frames of a clip where a transition may enter it and where one may leave it (inclusive; empty if
// first > last). Windows of `span` frames must fit after a candidate.
struct Ranges {
  int enter_first = 0, enter_last = -1;
  int exit_first = 0, exit_last = -1;
};

Ranges ranges_of(const MotionClip& mc, int span) {
  const int n = mc.clip.frame_count();
  const int last_start = n - span;  // a window starting here still fits in the clip
  Ranges r;
  if (last_start < 0) return r;
  if (is_locomotion(mc.role) && mc.cyclic) {
    // Inside the loop: enter so that the blend ends by loop_last (the loop can then wrap), leave anywhere
    // in the loop while the blend's frames exist.
    r.enter_first = mc.loop_first;
    r.enter_last = std::min(mc.loop_last + 1 - span, last_start);
    r.exit_first = mc.loop_first;
    r.exit_last = std::min(mc.loop_last, last_start);
  } else if (is_locomotion(mc.role)) {
    // A clip that plays once (a turn): enter in its first third, leave in its last, so that the action
    // happens and a way out always lies ahead of the way in.
    r.enter_first = 0;
    r.enter_last = std::min((n - 1) / 3, last_start);
    r.exit_first = std::min(2 * (n - 1) / 3, last_start);
    r.exit_last = last_start;
  } else {
    // A target motion (Fig. 4): enter in part (i), so that the blend is over before the target movement
    // starts at T_t; leave in part (iii), the last third of what follows T_t (after landing, recovery).
    const int t = std::clamp(mc.target_frame, 0, n - 1);
    r.enter_first = 0;
    r.enter_last = std::min(std::max(0, t - span), last_start);
    r.exit_first = std::min(t + 2 * (n - 1 - t) / 3, last_start);
    r.exit_last = last_start;
  }
  return r;
}

struct Candidate {
  int i = 0, j = 0;
  float distance = std::numeric_limits<float>::infinity();
  FloorTransform align;
};

}  // namespace

int MotionGraph::find(const std::string& name) const {
  for (size_t i = 0; i < nodes_.size(); ++i)
    if (nodes_[i].name == name) return static_cast<int>(i);
  return -1;
}

FloorTransform MotionGraph::align(int a, int i, int b, int j, int n) const {
  const auto& ca = clouds_[static_cast<size_t>(a)];
  const auto& cb = clouds_[static_cast<size_t>(b)];
  const int fa = static_cast<int>(ca.size()) / points_, fb = static_cast<int>(cb.size()) / points_;
  i = std::clamp(i, 0, fa - 1);
  j = std::clamp(j, 0, fb - 1);
  n = std::max(1, std::min({n, fa - i, fb - j}));
  WindowSums w;
  for (int d = 0; d < n; ++d) {
    const glm::vec3* p = &ca[static_cast<size_t>((i + d) * points_)];
    const glm::vec3* q = &cb[static_cast<size_t>((j + d) * points_)];
    w.pair += pair_stats(p, q, points_);
    add(w.p, frame_stats(p, points_));
    add(w.q, frame_stats(q, points_));
    w.count += points_;
  }
  FloorTransform t;
  solve(w, &t, nullptr);
  return t;
}

FloorTransform MotionGraph::align_roots(int a, int i, int b, int j) const {
  // Facing from the pelvis: perpendicular to the hip joints' axis on the floor. Unlike the root
  // rotation's forward axis it stays level when the trunk pitches (crawling, ducking).
  const auto pelvis = [&](int clip, int frame, glm::vec2& position) {
    const auto& cloud = clouds_[static_cast<size_t>(clip)];
    const int frames = static_cast<int>(cloud.size()) / points_;
    const glm::vec3* p = &cloud[static_cast<size_t>(std::clamp(frame, 0, frames - 1) * points_)];
    position = {p[0].x, p[0].z};
    const glm::vec3 across = p[hip_points_[kLeft]] - p[hip_points_[kRight]];
    return std::atan2(-across.z, across.x);  // facing = across x up, i.e. (-across.z, 0, across.x)
  };
  glm::vec2 pa, pb;
  FloorTransform t;
  t.angle = pelvis(a, i, pa) - pelvis(b, j, pb);
  const glm::vec3 rotated = t.apply(glm::vec3(pb.x, 0.0f, pb.y));
  t.offset = pa - glm::vec2(rotated.x, rotated.z);
  return t;
}

float MotionGraph::distance(int a, int i, int b, int j, int n) const {
  const FloorTransform t = align(a, i, b, j, n);
  const auto& ca = clouds_[static_cast<size_t>(a)];
  const auto& cb = clouds_[static_cast<size_t>(b)];
  const int fa = static_cast<int>(ca.size()) / points_, fb = static_cast<int>(cb.size()) / points_;
  i = std::clamp(i, 0, fa - 1);
  j = std::clamp(j, 0, fb - 1);
  n = std::max(1, std::min({n, fa - i, fb - j}));
  float sum = 0;
  for (int d = 0; d < n; ++d)
    for (int k = 0; k < points_; ++k) {
      const glm::vec3 diff = ca[static_cast<size_t>((i + d) * points_ + k)] - t.apply(cb[static_cast<size_t>((j + d) * points_ + k)]);
      sum += glm::dot(diff, diff);
    }
  return std::sqrt(sum / static_cast<float>(n * points_));
}

// best_entry_frame's table: one entry per (clip frame, target node), -1 until computed.
struct MotionGraph::EntryMemo {
  explicit EntryMemo(const MotionSet& set) : nodes(set.clips.size()) {
    size_t frames = 0;
    for (const MotionClip& mc : set.clips) {
      first.push_back(frames);
      frames += static_cast<size_t>(mc.clip.frame_count());
    }
    best.reset(new std::atomic<int>[frames * nodes]);
    for (size_t k = 0; k < frames * nodes; ++k) best[k].store(-1, std::memory_order_relaxed);
  }
  size_t nodes;
  std::vector<size_t> first;                 // per clip: its frame 0's row
  std::unique_ptr<std::atomic<int>[]> best;  // [(first[from] + from_frame) * nodes + to]
};

bool MotionGraph::entry_frame_known(int from, int from_frame, int to) const {
  const int frames = set_->clips.at(static_cast<size_t>(from)).clip.frame_count();
  if (!entry_memo_ || from_frame < 0 || from_frame >= frames || to < 0 || static_cast<size_t>(to) >= entry_memo_->nodes) return false;
  return entry_memo_->best[(entry_memo_->first[static_cast<size_t>(from)] + static_cast<size_t>(from_frame)) * entry_memo_->nodes +
                           static_cast<size_t>(to)].load(std::memory_order_relaxed) >= 0;
}

int MotionGraph::best_entry_frame(int from, int from_frame, int to) const {
  const MotionClip& mc = set_->clips.at(static_cast<size_t>(to));
  const int frames = set_->clips.at(static_cast<size_t>(from)).clip.frame_count();
  std::atomic<int>* slot = nullptr;
  if (entry_memo_ && from_frame >= 0 && from_frame < frames) {
    slot = &entry_memo_->best[(entry_memo_->first[static_cast<size_t>(from)] + static_cast<size_t>(from_frame)) *
                                  entry_memo_->nodes + static_cast<size_t>(to)];
    const int known = slot->load(std::memory_order_relaxed);
    if (known >= 0) return known;
  }
  const int first = mc.cyclic ? mc.loop_first : 0, last = mc.cyclic ? mc.loop_last : mc.clip.frame_count() - 1;
  int best = first;
  float best_distance = std::numeric_limits<float>::infinity();
  for (int j = first; j <= last; ++j) {
    const float d = distance(from, from_frame, to, j, window_frames_);
    if (d < best_distance) {
      best_distance = d;
      best = j;
    }
  }
  if (slot) slot->store(best, std::memory_order_relaxed);
  return best;
}

void MotionGraph::fill_entry_frames(const std::vector<int>& from, const std::vector<int>& to, int part, int parts) const {
  int row = 0;
  for (int node : from) {
    const int frames = set_->clips.at(static_cast<size_t>(node)).clip.frame_count();
    for (int frame = 0; frame < frames; ++frame, ++row) {
      if (row % parts != part) continue;
      for (int target : to) best_entry_frame(node, frame, target);
    }
  }
}

MotionGraph MotionGraph::build(const MotionSet& set, const GraphParams& params) {
  const auto start = std::chrono::steady_clock::now();
  MotionGraph g;
  g.set_ = &set;
  if (set.clips.empty() || !set.skeleton) throw std::invalid_argument("motion graph: the motion set '" + set.name + "' has no clips");
  const float fps = set.clips.front().clip.fps;
  for (const MotionClip& mc : set.clips)
    if (std::abs(mc.clip.fps - fps) > 1e-3f)
      throw std::invalid_argument("motion graph: clip '" + mc.clip.name + "' is not at the set's frame rate");

  for (size_t c = 0; c < set.clips.size(); ++c) {
    GraphNode node;
    node.clip = static_cast<int>(c);
    node.name = set.clips[c].clip.name;
    node.role = set.clips[c].role;
    node.core = is_locomotion(node.role);
    g.nodes_.push_back(node);
  }
  const int node_count = static_cast<int>(g.nodes_.size());
  g.next_.assign(static_cast<size_t>(node_count), {});
  g.out_.assign(static_cast<size_t>(node_count), {});

  // The point cloud of a frame: the joints that carry the body's shape (pelvis, spine, neck, head,
  // shoulders, elbows, wrists, hips, knees, ankles) and the toe tips; fingers and eyes are left out.
  const Skeleton& sk = *set.skeleton;
  const BodyMap& body = set.body;
  std::vector<int> joints = {body.root};
  joints.insert(joints.end(), body.spine.begin(), body.spine.end());
  for (int j : {body.neck, body.head})
    if (j >= 0) joints.push_back(j);
  for (const ArmChain& arm : body.arms) joints.insert(joints.end(), {arm.shoulder, arm.elbow, arm.wrist});
  for (const LegChain& leg : body.legs) {
    g.hip_points_[leg.hip == body.legs[kLeft].hip ? kLeft : kRight] = static_cast<int>(joints.size());
    joints.insert(joints.end(), {leg.hip, leg.knee, leg.ankle});
  }
  g.points_ = static_cast<int>(joints.size()) + 2;
  g.clouds_.resize(set.clips.size());
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  for (size_t c = 0; c < set.clips.size(); ++c) {
    const Clip& clip = set.clips[c].clip;
    auto& cloud = g.clouds_[c];
    cloud.resize(static_cast<size_t>(clip.frame_count() * g.points_));
    for (int f = 0; f < clip.frame_count(); ++f) {
      forward_kinematics(sk, clip.frames[static_cast<size_t>(f)], positions, &rotations);
      glm::vec3* out = &cloud[static_cast<size_t>(f * g.points_)];
      for (size_t k = 0; k < joints.size(); ++k) out[k] = positions[static_cast<size_t>(joints[k])];
      const FootPoints feet = foot_points(sk, body, positions, rotations);
      out[joints.size()] = feet.toe[kLeft];
      out[joints.size() + 1] = feet.toe[kRight];
    }
  }

  // The window: window_s of frames, compared every `step` frames.
  const int step = std::max(1, static_cast<int>(std::lround(fps / kSearchRate)));
  const int window_samples = std::max(2, static_cast<int>(std::lround(params.window_s * fps / static_cast<float>(step))) + 1);
  const int window_span = (window_samples - 1) * step + 1;
  const int blend_frames = std::max(1, static_cast<int>(std::lround(params.blend_s * fps)));
  const int span = std::max(window_span, blend_frames);
  g.window_frames_ = window_span;

  std::vector<Ranges> ranges;
  std::vector<std::vector<FrameStats>> frame_sums(set.clips.size());
  for (size_t c = 0; c < set.clips.size(); ++c) {
    ranges.push_back(ranges_of(set.clips[c], span));
    const int n = set.clips[c].clip.frame_count();
    frame_sums[c].resize(static_cast<size_t>(n));
    for (int f = 0; f < n; ++f) frame_sums[c][static_cast<size_t>(f)] = frame_stats(&g.clouds_[c][static_cast<size_t>(f * g.points_)], g.points_);
  }

  // The blend of an edge lasts blend_s, longer in proportion for a forced edge above the threshold (so
  // that joint speeds across it stay those of the clips), within the frames both clips hold.
  const auto edge_blend = [&](int a, int i, int b, int j, float distance) {
    const MotionClip& mb = set.clips[static_cast<size_t>(b)];
    const float scale = params.threshold > 0 ? std::max(1.0f, distance / params.threshold) : 1.0f;
    int frames = static_cast<int>(std::lround(static_cast<float>(blend_frames) * scale));
    frames = std::min(frames, set.clips[static_cast<size_t>(a)].clip.frame_count() - i);
    frames = std::min(frames, mb.cyclic ? mb.loop_last + 1 - j : mb.clip.frame_count() - 1 - j);
    return std::max(1, frames);
  };

  // Best candidate of every allowed ordered pair, for the edges forced below.
  std::vector<std::vector<Candidate>> best(static_cast<size_t>(node_count), std::vector<Candidate>(static_cast<size_t>(node_count)));
  const auto allowed = [&](int a, int b) {
    if (a == b) return false;  // a clip's own loop is added separately
    return g.nodes_[static_cast<size_t>(a)].core || g.nodes_[static_cast<size_t>(b)].core;  // no target -> target
  };

  std::vector<PairStats> diag;  // diagonal prefix sums over the extended sample grid
  for (int a = 0; a < node_count; ++a) {
    const Ranges& ra = ranges[static_cast<size_t>(a)];
    if (ra.exit_last < ra.exit_first) continue;
    const auto& cloud_a = g.clouds_[static_cast<size_t>(a)];
    const int na = (ra.exit_last - ra.exit_first) / step + 1;
    for (int b = 0; b < node_count; ++b) {
      if (!allowed(a, b)) continue;
      const Ranges& rb = ranges[static_cast<size_t>(b)];
      if (rb.enter_last < rb.enter_first) continue;
      const auto& cloud_b = g.clouds_[static_cast<size_t>(b)];
      const int nb = (rb.enter_last - rb.enter_first) / step + 1;
      // Grid of samples extended by the window so that every candidate's window is summed from it.
      const int ea = na + window_samples - 1, eb = nb + window_samples - 1;
      diag.assign(static_cast<size_t>((ea + 1) * (eb + 1)), PairStats{});
      const auto at = [&](int s, int t) -> PairStats& { return diag[static_cast<size_t>(s * (eb + 1) + t)]; };
      for (int s = 0; s < ea; ++s) {
        const glm::vec3* p = &cloud_a[static_cast<size_t>((ra.exit_first + s * step) * g.points_)];
        for (int t = 0; t < eb; ++t) {
          const glm::vec3* q = &cloud_b[static_cast<size_t>((rb.enter_first + t * step) * g.points_)];
          PairStats ps = pair_stats(p, q, g.points_);
          ps += at(s, t);
          at(s + 1, t + 1) = ps;
        }
      }
      g.candidate_pairs_ += ea * eb;
      // Windowed distances at every candidate.
      std::vector<float> dist(static_cast<size_t>(na * nb));
      std::vector<FrameStats> wa(static_cast<size_t>(na)), wb(static_cast<size_t>(nb));
      for (int s = 0; s < na; ++s)
        for (int d = 0; d < window_samples; ++d)
          add(wa[static_cast<size_t>(s)], frame_sums[static_cast<size_t>(a)][static_cast<size_t>(ra.exit_first + (s + d) * step)]);
      for (int t = 0; t < nb; ++t)
        for (int d = 0; d < window_samples; ++d)
          add(wb[static_cast<size_t>(t)], frame_sums[static_cast<size_t>(b)][static_cast<size_t>(rb.enter_first + (t + d) * step)]);
      Candidate& top = best[static_cast<size_t>(a)][static_cast<size_t>(b)];
      for (int s = 0; s < na; ++s)
        for (int t = 0; t < nb; ++t) {
          WindowSums w;
          w.pair = at(s + window_samples, t + window_samples);
          const PairStats& before = at(s, t);
          w.pair.a -= before.a;
          w.pair.b -= before.b;
          w.pair.yy -= before.yy;
          w.p = wa[static_cast<size_t>(s)];
          w.q = wb[static_cast<size_t>(t)];
          w.count = window_samples * g.points_;
          float squared = 0;
          solve(w, nullptr, &squared);
          const float d = std::sqrt(squared / static_cast<float>(w.count));
          dist[static_cast<size_t>(s * nb + t)] = d;
          if (d < top.distance) {
            top.distance = d;
            top.i = ra.exit_first + s * step;
            top.j = rb.enter_first + t * step;
          }
        }
      // Local minima (no neighbour in the 3x3 block smaller) under the threshold.
      std::vector<Candidate> minima;
      for (int s = 0; s < na; ++s)
        for (int t = 0; t < nb; ++t) {
          const float d = dist[static_cast<size_t>(s * nb + t)];
          if (d >= params.threshold) continue;
          bool minimum = true;
          for (int ds = -1; ds <= 1 && minimum; ++ds)
            for (int dt = -1; dt <= 1; ++dt) {
              const int s2 = s + ds, t2 = t + dt;
              if ((ds == 0 && dt == 0) || s2 < 0 || t2 < 0 || s2 >= na || t2 >= nb) continue;
              const float d2 = dist[static_cast<size_t>(s2 * nb + t2)];
              // Ties go to the earlier candidate so that a flat valley gives one edge.
              if (d2 < d || (d2 == d && (ds < 0 || (ds == 0 && dt < 0)))) {
                minimum = false;
                break;
              }
            }
          if (minimum) minima.push_back({ra.exit_first + s * step, rb.enter_first + t * step, d, {}});
        }
      std::sort(minima.begin(), minima.end(), [](const Candidate& x, const Candidate& y) { return x.distance < y.distance; });
      if (static_cast<int>(minima.size()) > kMaxEdgesPerPair) minima.resize(kMaxEdgesPerPair);
      for (const Candidate& m : minima) {
        GraphEdge e;
        e.from = a;
        e.to = b;
        e.from_frame = m.i;
        e.to_frame = m.j;
        e.distance = m.distance;
        e.align = g.align(a, m.i, b, m.j, window_span);
        g.edges_.push_back(e);
      }
    }
  }

  const auto has_edge = [&](int a, int b) {
    for (const GraphEdge& e : g.edges_)
      if (e.from == a && e.to == b) return true;
    return false;
  };
  const auto force = [&](int a, int b) {
    const Candidate& c = best[static_cast<size_t>(a)][static_cast<size_t>(b)];
    if (!std::isfinite(c.distance)) return false;
    GraphEdge e;
    e.from = a;
    e.to = b;
    e.from_frame = c.i;
    e.to_frame = c.j;
    e.distance = c.distance;
    e.forced = true;
    // Poses this far apart can fit best turned any way (a crawl against a walk); the pelvis decides.
    e.align = g.align_roots(a, c.i, b, c.j);
    g.edges_.push_back(e);
    return true;
  };

  // The hierarchy's guarantees (Sec. 4.1): every target can be launched from every walk and returns to
  // locomotion; every core node reaches every other. Where no local minimum is under the threshold the
  // best candidate is kept (marked forced, blended for longer).
  for (int t = 0; t < node_count; ++t) {
    if (g.nodes_[static_cast<size_t>(t)].core) continue;
    for (int w = 0; w < node_count; ++w)
      if (g.nodes_[static_cast<size_t>(w)].role == Role::Walk && !has_edge(w, t)) force(w, t);
    bool back = false;
    for (int c = 0; c < node_count; ++c) back = back || (g.nodes_[static_cast<size_t>(c)].core && has_edge(t, c));
    if (!back) {
      int pick = -1;
      for (int c = 0; c < node_count; ++c)
        if (g.nodes_[static_cast<size_t>(c)].core &&
            (pick < 0 || best[static_cast<size_t>(t)][static_cast<size_t>(c)].distance < best[static_cast<size_t>(t)][static_cast<size_t>(pick)].distance))
          pick = c;
      if (pick >= 0) force(t, pick);
    }
  }
  for (int a = 0; a < node_count; ++a) {
    if (!g.nodes_[static_cast<size_t>(a)].core) continue;
    std::vector<bool> seen(static_cast<size_t>(node_count), false);
    std::vector<int> stack = {a};
    seen[static_cast<size_t>(a)] = true;
    while (!stack.empty()) {
      const int u = stack.back();
      stack.pop_back();
      for (const GraphEdge& e : g.edges_)
        if (e.from == u && g.nodes_[static_cast<size_t>(e.to)].core && !seen[static_cast<size_t>(e.to)]) {
          seen[static_cast<size_t>(e.to)] = true;
          stack.push_back(e.to);
        }
    }
    for (int b = 0; b < node_count; ++b)
      if (g.nodes_[static_cast<size_t>(b)].core && !seen[static_cast<size_t>(b)]) force(a, b);
  }

  // Each cyclic clip's own loop: loop_last is followed by loop_first. The alignment places loop_first
  // where the frame after loop_last would be: matched against the frames after loop_last when the clip
  // holds them, else frame loop_first - 1 is matched onto loop_last.
  for (int c = 0; c < node_count; ++c) {
    const MotionClip& mc = set.clips[static_cast<size_t>(c)];
    if (!mc.cyclic || mc.loop_last <= mc.loop_first) continue;
    GraphEdge e;
    e.from = c;
    e.to = c;
    e.loop = true;
    e.from_frame = mc.loop_last + 1;
    e.to_frame = mc.loop_first;
    const int after = mc.clip.frame_count() - 1 - mc.loop_last;
    if (after >= 1) {
      e.align = g.align(c, mc.loop_last + 1, c, mc.loop_first, std::min(after, window_span));
      e.distance = g.distance(c, mc.loop_last + 1, c, mc.loop_first, std::min(after, window_span));
    } else if (mc.loop_first >= 1) {
      e.align = g.align(c, mc.loop_last, c, mc.loop_first - 1, 1);
      e.distance = g.distance(c, mc.loop_last, c, mc.loop_first - 1, 1);
    } else {
      // The loop is the whole clip: put loop_first on loop_last, then one frame of its own root motion
      // further on, so that the root does not stand still for a frame at the wrap.
      e.align = g.align(c, mc.loop_last, c, mc.loop_first, 1);
      e.distance = g.distance(c, mc.loop_last, c, mc.loop_first, 1);
      if (mc.loop_first + 1 < mc.clip.frame_count()) {
        const auto& cloud = g.clouds_[static_cast<size_t>(c)];
        const glm::vec3 step = e.align.apply(cloud[static_cast<size_t>((mc.loop_first + 1) * g.points_)]) -
                               e.align.apply(cloud[static_cast<size_t>(mc.loop_first * g.points_)]);
        e.align.offset += glm::vec2(step.x, step.z);
      }
    }
    g.edges_.push_back(e);
  }

  for (size_t k = 0; k < g.edges_.size(); ++k) {
    GraphEdge& e = g.edges_[k];
    if (e.loop) {
      const MotionClip& mc = set.clips[static_cast<size_t>(e.from)];
      e.blend_frames = std::clamp(std::min(blend_frames, mc.clip.frame_count() - e.from_frame), 0,
                                  std::max(0, mc.loop_last - mc.loop_first));
    } else {
      e.blend_frames = edge_blend(e.from, e.from_frame, e.to, e.to_frame, e.distance);
    }
    g.out_[static_cast<size_t>(e.from)].push_back(static_cast<int>(k));
    auto& next = g.next_[static_cast<size_t>(e.from)];
    if (std::find(next.begin(), next.end(), e.to) == next.end()) next.push_back(e.to);
  }
  for (auto& next : g.next_) std::sort(next.begin(), next.end());
  g.entry_memo_ = std::make_shared<EntryMemo>(set);
  g.build_seconds_ = std::chrono::duration<float>(std::chrono::steady_clock::now() - start).count();
  return g;
}

std::string MotionGraph::to_dot() const {
  std::ostringstream out;
  out << "digraph \"" << (set_ ? set_->name : std::string("motions")) << "\" {\n  rankdir=LR;\n";
  for (size_t i = 0; i < nodes_.size(); ++i)
    out << "  n" << i << " [label=\"" << nodes_[i].name << "\\n" << role_name(nodes_[i].role) << "\", shape="
        << (nodes_[i].core ? "box, style=bold" : "ellipse") << "];\n";
  for (size_t a = 0; a < nodes_.size(); ++a)
    for (int b : next_[a]) {
      int count = 0, forced = 0;
      float best = std::numeric_limits<float>::infinity();
      for (int k : out_[a]) {
        const GraphEdge& e = edges_[static_cast<size_t>(k)];
        if (e.to != b) continue;
        ++count;
        forced += e.forced ? 1 : 0;
        best = std::min(best, e.distance);
      }
      char label[96];
      std::snprintf(label, sizeof label, "%d (%.3f m)", count, best);
      out << "  n" << a << " -> n" << b << " [label=\"" << label << "\"" << (forced == count ? ", style=dashed" : "") << "];\n";
    }
  out << "}\n";
  return out.str();
}

}  // namespace prep
