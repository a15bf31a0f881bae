#include "engine/interop/character_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>
#include <utility>
#include <vector>

#include "engine/motion/kinematics.h"

namespace prep {

namespace {

constexpr float kPi = 3.14159265358979f;

float smoothstep01(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}

// Up to four (joint, weight) pairs.
struct Influence {
  std::vector<std::pair<int, float>> parts;
  void add(int joint, float w) {
    if (joint < 0 || w <= 0.0f) return;
    for (auto& p : parts)
      if (p.first == joint) {
        p.second += w;
        return;
      }
    parts.emplace_back(joint, w);
  }
};

// A ring of the surface: an ellipse with half-axes a (along u) and b (along v) around `center`.
struct Ring {
  glm::vec3 center;
  glm::vec3 u, v;
  float a, b;
  Influence influence;
};

// A closed piece: rings in order plus a pole beyond each end.
struct Piece {
  std::vector<Ring> rings;
  glm::vec3 pole_start, pole_end;
  Influence influence_start, influence_end;
  int segments = 16;
};

// u across the bone, v completing a right-handed frame; `ref` chosen away from the bone direction.
void frame_for(const glm::vec3& d, glm::vec3& u, glm::vec3& v) {
  const glm::vec3 ref = std::fabs(d.z) < 0.7f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  u = glm::normalize(glm::cross(d, ref));
  v = glm::normalize(glm::cross(u, d));
}

// Adds rounded caps (quarter-ellipse profiles) to both ends of a piece of rings.
void cap_piece(Piece& piece, float start_length, float end_length, int cap_rings = 3) {
  const Ring first = piece.rings.front(), last = piece.rings.back();
  const glm::vec3 d0 = glm::normalize(piece.rings[1].center - first.center);
  const glm::vec3 d1 = glm::normalize(last.center - piece.rings[piece.rings.size() - 2].center);
  std::vector<Ring> start, end;
  for (int k = cap_rings; k >= 1; --k) {
    const float phi = 0.5f * kPi * static_cast<float>(k) / static_cast<float>(cap_rings + 1);
    Ring r = first;
    r.center = first.center - d0 * (start_length * std::sin(phi));
    r.a *= std::cos(phi);
    r.b *= std::cos(phi);
    start.push_back(r);
  }
  for (int k = 1; k <= cap_rings; ++k) {
    const float phi = 0.5f * kPi * static_cast<float>(k) / static_cast<float>(cap_rings + 1);
    Ring r = last;
    r.center = last.center + d1 * (end_length * std::sin(phi));
    r.a *= std::cos(phi);
    r.b *= std::cos(phi);
    end.push_back(r);
  }
  piece.pole_start = first.center - d0 * start_length;
  piece.pole_end = last.center + d1 * end_length;
  piece.influence_start = first.influence;
  piece.influence_end = last.influence;
  piece.rings.insert(piece.rings.begin(), start.begin(), start.end());
  piece.rings.insert(piece.rings.end(), end.begin(), end.end());
}

class MeshBuilder {
 public:
  MeshBuilder(SkinnedMesh& mesh, const glm::vec3& shift) : mesh_(mesh), shift_(shift) {}

  void add(const Piece& piece) {
    const auto base = static_cast<uint32_t>(mesh_.positions.size());
    const size_t first_index = mesh_.indices.size();
    const int n = piece.segments;
    for (const Ring& r : piece.rings)
      for (int k = 0; k < n; ++k) {
        const float t = 2.0f * kPi * static_cast<float>(k) / static_cast<float>(n);
        vertex(r.center + r.u * (r.a * std::cos(t)) + r.v * (r.b * std::sin(t)), r.influence);
      }
    const auto pole0 = static_cast<uint32_t>(mesh_.positions.size());
    vertex(piece.pole_start, piece.influence_start);
    const auto pole1 = static_cast<uint32_t>(mesh_.positions.size());
    vertex(piece.pole_end, piece.influence_end);
    const auto rings = static_cast<uint32_t>(piece.rings.size());
    const auto un = static_cast<uint32_t>(n);
    for (uint32_t i = 0; i + 1 < rings; ++i)
      for (uint32_t k = 0; k < un; ++k) {
        const uint32_t a = base + i * un + k, b = base + i * un + (k + 1) % un;
        const uint32_t c = a + un, d = b + un;
        tri(a, b, d);
        tri(a, d, c);
      }
    for (uint32_t k = 0; k < un; ++k) {
      tri(pole0, base + (k + 1) % un, base + k);
      const uint32_t last = base + (rings - 1) * un;
      tri(pole1, last + k, last + (k + 1) % un);
    }
    // Outward winding: the signed volume of a closed surface is positive when its triangles face out.
    double volume = 0.0;
    for (size_t i = first_index; i < mesh_.indices.size(); i += 3) {
      const glm::dvec3 p0 = mesh_.positions[mesh_.indices[i]], p1 = mesh_.positions[mesh_.indices[i + 1]],
                       p2 = mesh_.positions[mesh_.indices[i + 2]];
      volume += glm::dot(p0, glm::cross(p1, p2));
    }
    if (volume < 0.0)
      for (size_t i = first_index; i < mesh_.indices.size(); i += 3) std::swap(mesh_.indices[i + 1], mesh_.indices[i + 2]);
    // Smooth normals within the piece (area-weighted face normals).
    for (size_t i = first_index; i < mesh_.indices.size(); i += 3) {
      const uint32_t i0 = mesh_.indices[i], i1 = mesh_.indices[i + 1], i2 = mesh_.indices[i + 2];
      const glm::vec3 fn = glm::cross(mesh_.positions[i1] - mesh_.positions[i0], mesh_.positions[i2] - mesh_.positions[i0]);
      mesh_.normals[i0] += fn;
      mesh_.normals[i1] += fn;
      mesh_.normals[i2] += fn;
    }
    for (size_t v = base; v < mesh_.positions.size(); ++v) {
      const float len = glm::length(mesh_.normals[v]);
      mesh_.normals[v] = len > 0.0f ? mesh_.normals[v] / len : glm::vec3(0, 1, 0);
    }
  }

 private:
  void vertex(const glm::vec3& p, const Influence& influence) {
    mesh_.positions.push_back(p + shift_);
    mesh_.normals.emplace_back(0.0f);
    auto parts = influence.parts;
    std::sort(parts.begin(), parts.end(), [](auto& x, auto& y) { return x.second > y.second; });
    if (parts.size() > 4) parts.resize(4);
    float sum = 0.0f;
    for (auto& p2 : parts) sum += p2.second;
    glm::ivec4 joints(0);
    glm::vec4 weights(0.0f);
    float assigned = 0.0f;
    for (size_t k = 0; k < parts.size(); ++k) {
      joints[static_cast<int>(k)] = parts[k].first;
      // The last weight takes the remainder so that the sum is 1 in float arithmetic.
      weights[static_cast<int>(k)] = k + 1 == parts.size() ? 1.0f - assigned : parts[k].second / sum;
      assigned += weights[static_cast<int>(k)];
    }
    mesh_.joints.push_back(joints);
    mesh_.weights.push_back(weights);
  }
  void tri(uint32_t a, uint32_t b, uint32_t c) {
    mesh_.indices.push_back(a);
    mesh_.indices.push_back(b);
    mesh_.indices.push_back(c);
  }
  SkinnedMesh& mesh_;
  glm::vec3 shift_;
};

// Weights of a point at fraction t along the bone moved by `joint` (from its position to its child's):
// half-and-half with the previous bone's joint at t = 0 and with the next bone's joint at t = 1, blending
// over `blend` of the length (smoothstep), so that the skin bends smoothly at every joint.
Influence bone_influence(int joint, int previous, int next, float t, float blend) {
  Influence inf;
  float w_prev = previous >= 0 ? 0.5f * (1.0f - smoothstep01(t / blend)) : 0.0f;
  float w_next = next >= 0 ? 0.5f * smoothstep01((t - (1.0f - blend)) / blend) : 0.0f;
  inf.add(previous, w_prev);
  inf.add(next, w_next);
  inf.add(joint, 1.0f - w_prev - w_next);
  return inf;
}

struct Limb {
  glm::vec3 from, to;
  int joint, previous, next;
  float a0, b0, a1, b1;  // half-axes at both ends
  float bulge = 0.0f;    // extra girth mid-bone (muscle), as a fraction of the start half-axes
};

Piece limb_piece(const Limb& limb, const CharacterShape& shape, int segments, int rings = 8) {
  Piece piece;
  piece.segments = segments;
  glm::vec3 d = limb.to - limb.from;
  const float length = glm::length(d);
  d = length > 1e-6f ? d / length : glm::vec3(0, -1, 0);
  glm::vec3 u, v;
  frame_for(d, u, v);
  for (int i = 0; i <= rings; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(rings);
    const float swell = 1.0f + limb.bulge * std::sin(kPi * t);
    Ring r;
    r.center = limb.from + d * (length * t);
    r.u = u;
    r.v = v;
    r.a = (limb.a0 + (limb.a1 - limb.a0) * t) * swell;
    r.b = (limb.b0 + (limb.b1 - limb.b0) * t) * swell;
    r.influence = bone_influence(limb.joint, limb.previous, limb.next, t, shape.blend);
    piece.rings.push_back(r);
  }
  cap_piece(piece, 0.8f * std::min(limb.a0, limb.b0), 0.8f * std::min(limb.a1, limb.b1));
  return piece;
}

// Piecewise-smooth interpolation of a profile given at increasing stations.
float profile(const std::vector<std::pair<float, float>>& stations, float h) {
  if (h <= stations.front().first) return stations.front().second;
  for (size_t i = 1; i < stations.size(); ++i)
    if (h <= stations[i].first) {
      const float s = smoothstep01((h - stations[i - 1].first) / (stations[i].first - stations[i - 1].first));
      return stations[i - 1].second + (stations[i].second - stations[i - 1].second) * s;
    }
  return stations.back().second;
}

struct Rest {
  std::vector<glm::vec3> p;
  std::vector<glm::quat> q;
  float stature = 0, sole = 0;
};

glm::vec3 end_point(const Skeleton& sk, const Rest& rest, int joint) {
  return rest.p[static_cast<size_t>(joint)] + sk.joints[static_cast<size_t>(joint)].end_site;
}

Rest rest_pose(const Skeleton& skeleton, const BodyMap& body, const CharacterShape& shape) {
  if (body.legs[0].hip < 0 || body.legs[0].ankle < 0 || body.legs[1].hip < 0 || body.legs[1].ankle < 0)
    throw std::invalid_argument("character mesh: the body map has no legs");
  Rest rest;
  Pose pose(skeleton.size());
  forward_kinematics(skeleton, pose, rest.p, &rest.q);
  float hip_minus_ankle = 0.0f, ankle_y = 0.0f;
  for (int s = 0; s < 2; ++s) {
    hip_minus_ankle += 0.5f * (rest.p[static_cast<size_t>(body.legs[s].hip)].y - rest.p[static_cast<size_t>(body.legs[s].ankle)].y);
    ankle_y += 0.5f * rest.p[static_cast<size_t>(body.legs[s].ankle)].y;
  }
  if (!(hip_minus_ankle > 0.0f)) throw std::invalid_argument("character mesh: the rest pose's hips are not above its ankles");
  rest.stature = hip_minus_ankle / (shape.hip_height - shape.ankle_height);
  rest.sole = ankle_y - shape.ankle_height * rest.stature;
  return rest;
}

int parent_of(const Skeleton& sk, int j) { return j < 0 ? -1 : sk.joints[static_cast<size_t>(j)].parent; }

// The hand's far end: the wrist's End Site, else the farthest descendant point along the forearm, kept
// within the anthropometric hand length.
glm::vec3 hand_tip(const Skeleton& sk, const Rest& rest, int wrist, const glm::vec3& forearm_dir, float hand_length) {
  const glm::vec3 w = rest.p[static_cast<size_t>(wrist)];
  float reach = 0.0f;
  if (sk.joints[static_cast<size_t>(wrist)].has_end_site) reach = glm::dot(sk.joints[static_cast<size_t>(wrist)].end_site, forearm_dir);
  for (int j = wrist + 1; j < sk.size(); ++j) {
    int a = j;
    while (a > wrist) a = parent_of(sk, a);
    if (a != wrist) continue;
    reach = std::max(reach, glm::dot(rest.p[static_cast<size_t>(j)] - w, forearm_dir));
    if (sk.joints[static_cast<size_t>(j)].has_end_site)
      reach = std::max(reach, glm::dot(end_point(sk, rest, j) - w, forearm_dir));
  }
  reach = std::clamp(reach, 0.6f * hand_length, hand_length);
  return w + forearm_dir * reach;
}

}  // namespace

glm::vec3 character_bind_root(const Skeleton& skeleton, const BodyMap& body, const CharacterShape& shape) {
  const Rest rest = rest_pose(skeleton, body, shape);
  return glm::vec3(0.0f, -rest.sole, 0.0f);
}

SkinnedMesh build_character_mesh(const Skeleton& skeleton, const BodyMap& body, const CharacterShape& shape) {
  const Rest rest = rest_pose(skeleton, body, shape);
  const float H = rest.stature;
  const glm::vec3 shift(0.0f, -rest.sole, 0.0f);  // rest pose (root at the origin) -> bind pose (soles on the floor)
  auto P = [&](int j) { return rest.p[static_cast<size_t>(j)]; };
  SkinnedMesh mesh;
  MeshBuilder builder(mesh, shift);
  const int n_limb = shape.ring_vertices;
  const int n_body = shape.ring_vertices * 3 / 2;

  // Legs and feet.
  for (int s = 0; s < 2; ++s) {
    const LegChain& leg = body.legs[static_cast<size_t>(s)];
    if (leg.knee < 0) throw std::invalid_argument("character mesh: a leg has no knee");
    const float* tr = shape.thigh_radius;
    const float* sr = shape.shin_radius;
    builder.add(limb_piece({P(leg.hip), P(leg.knee), leg.hip, parent_of(skeleton, leg.hip), leg.knee, tr[0] * H,
                            tr[0] * 1.05f * H, tr[1] * H, tr[1] * 1.05f * H, 0.05f},
                           shape, n_limb));
    builder.add(limb_piece({P(leg.knee), P(leg.ankle), leg.knee, leg.hip, leg.ankle, sr[0] * H, sr[0] * 1.08f * H,
                            sr[1] * H, sr[1] * 1.1f * H, 0.12f},
                           shape, n_limb));
    // Foot: from behind the heel to the toe tip, sitting on the sole.
    const glm::vec3 ankle = P(leg.ankle);
    glm::vec3 tip = ankle + glm::vec3(0, 0, 0.15f * H);
    if (leg.toe_tip_joint >= 0 && skeleton.joints[static_cast<size_t>(leg.toe_tip_joint)].has_end_site)
      tip = end_point(skeleton, rest, leg.toe_tip_joint);
    glm::vec3 forward(tip.x - ankle.x, 0.0f, tip.z - ankle.z);
    const float reach = glm::length(forward);
    forward = reach > 1e-4f ? forward / reach : glm::vec3(0, 0, 1);
    const float heel_back = std::max(0.25f * reach, 0.025f * H);
    const float length = heel_back + std::max(reach, 0.08f * H);
    const glm::vec3 heel(ankle.x - forward.x * heel_back, 0.0f, ankle.z - forward.z * heel_back);
    const glm::vec3 up(0, 1, 0);
    const glm::vec3 lateral = glm::normalize(glm::cross(forward, up));
    const float ankle_top = ankle.y - rest.sole + 0.02f * H;  // height of the foot's top at the ankle
    const float fw = shape.foot_half_width * H;
    // (station along the foot, half-width, height of the top above the sole)
    const std::vector<std::array<float, 3>> stations = {
        {0.0f, 0.62f * fw, 0.050f * H},  {0.12f, 0.70f * fw, 0.060f * H}, {heel_back / length, 0.74f * fw, ankle_top},
        {0.55f, 0.95f * fw, 0.045f * H}, {0.75f, 1.0f * fw, 0.032f * H},  {1.0f, 0.70f * fw, 0.022f * H}};
    float toe_station = 2.0f;
    if (leg.toe >= 0) toe_station = (heel_back + glm::dot(P(leg.toe) - ankle, forward)) / length;
    Piece foot;
    foot.segments = n_limb;
    for (const auto& st : stations) {
      Ring r;
      const float half_h = 0.5f * st[2];
      r.center = heel + forward * (st[0] * length) + up * (rest.sole + half_h);
      r.u = lateral;
      r.v = up;
      r.a = st[1];
      r.b = half_h;
      if (leg.toe >= 0) {
        const float w = smoothstep01((st[0] - toe_station) / (shape.blend * (1.0f - std::min(toe_station, 0.9f))) + 0.5f);
        r.influence.add(leg.toe, w);
        r.influence.add(leg.ankle, 1.0f - w);
      } else {
        r.influence.add(leg.ankle, 1.0f);
      }
      foot.rings.push_back(r);
    }
    cap_piece(foot, 0.6f * fw, 0.6f * fw);
    builder.add(foot);
  }

  // Arms and hands.
  for (int s = 0; s < 2; ++s) {
    const ArmChain& arm = body.arms[static_cast<size_t>(s)];
    if (arm.shoulder < 0 || arm.elbow < 0 || arm.wrist < 0) continue;
    const float* ur = shape.upper_arm_radius;
    const float* fr = shape.forearm_radius;
    builder.add(limb_piece({P(arm.shoulder), P(arm.elbow), arm.shoulder, parent_of(skeleton, arm.shoulder), arm.elbow,
                            ur[0] * H, ur[0] * H, ur[1] * H, ur[1] * H, 0.08f},
                           shape, n_limb));
    // The forearm is flatter (radius and ulna side by side).
    builder.add(limb_piece({P(arm.elbow), P(arm.wrist), arm.elbow, arm.shoulder, arm.wrist, fr[0] * 0.9f * H,
                            fr[0] * 1.1f * H, fr[1] * 0.75f * H, fr[1] * 1.25f * H, 0.08f},
                           shape, n_limb));
    glm::vec3 dir = P(arm.wrist) - P(arm.elbow);
    dir = glm::length(dir) > 1e-6f ? glm::normalize(dir) : glm::vec3(1, 0, 0);
    const glm::vec3 tip = hand_tip(skeleton, rest, arm.wrist, dir, shape.hand_length * H);
    Piece hand;
    hand.segments = n_limb;
    glm::vec3 u, v;
    frame_for(dir, u, v);
    const float hw = shape.hand_half_width * H, ht = shape.hand_half_thickness * H;
    const std::vector<std::array<float, 3>> stations = {
        {0.0f, 0.65f * hw, 0.95f * ht}, {0.45f, 1.0f * hw, 1.0f * ht}, {0.75f, 0.95f * hw, 0.8f * ht}, {1.0f, 0.75f * hw, 0.55f * ht}};
    for (const auto& st : stations) {
      Ring r;
      r.center = P(arm.wrist) + (tip - P(arm.wrist)) * st[0];
      r.u = u;
      r.v = v;
      r.a = st[2];  // thickness across the palm
      r.b = st[1];  // width of the palm
      r.influence = bone_influence(arm.wrist, arm.elbow, -1, st[0], shape.blend);
      hand.rings.push_back(r);
    }
    cap_piece(hand, 0.8f * ht, 0.5f * hw);
    builder.add(hand);
  }

  // Torso: along the spine from below the hips to the base of the neck.
  std::vector<int> chain{body.root};
  for (int j : body.spine)
    if (j != body.root) chain.push_back(j);
  const int top = body.neck >= 0 ? body.neck : body.head;
  if (top >= 0) chain.push_back(top);
  const glm::vec3 hips_mid = 0.5f * (P(body.legs[0].hip) + P(body.legs[1].hip));
  const float hip_half = 0.5f * glm::length(P(body.legs[0].hip) - P(body.legs[1].hip)) + shape.thigh_radius[0] * H;
  float shoulder_half = hip_half;
  if (body.arms[0].shoulder >= 0 && body.arms[1].shoulder >= 0)
    shoulder_half = 0.5f * glm::length(P(body.arms[0].shoulder) - P(body.arms[1].shoulder));
  std::vector<glm::vec3> spine_points{glm::vec3(hips_mid.x, hips_mid.y - 0.06f * H, hips_mid.z)};
  std::vector<float> joint_arc;  // arc position of each chain joint
  float arc = 0.0f;
  for (int j : chain) {
    arc += glm::length(P(j) - spine_points.back());
    spine_points.push_back(P(j));
    joint_arc.push_back(arc);
  }
  const float total = arc;
  if (total > 1e-4f && chain.size() >= 2) {
    Piece torso;
    torso.segments = n_body;
    const float* depth = shape.torso_depth;
    const float waist = shape.waist_half_width * H;
    // Stations by height fraction h along the spine (0 below the hips, 1 at the neck).
    const float h_hips = joint_arc[0] / total;
    const std::vector<std::pair<float, float>> width = {
        {0.0f, 0.82f * hip_half}, {h_hips, hip_half}, {0.5f * (h_hips + 1.0f) - 0.08f, waist},
        {0.78f, 0.88f * shoulder_half}, {0.92f, 0.80f * shoulder_half}, {1.0f, 0.45f * shoulder_half}};
    const std::vector<std::pair<float, float>> deep = {
        {0.0f, depth[0] * H}, {h_hips, depth[1] * H}, {0.5f * (h_hips + 1.0f) - 0.08f, depth[2] * H},
        {0.74f, depth[3] * H}, {1.0f, depth[4] * H}};
    const int rings = 16;
    for (int i = 0; i <= rings; ++i) {
      const float s = total * static_cast<float>(i) / static_cast<float>(rings);
      // Point on the polyline at arc length s.
      size_t k = 1;
      float acc = 0.0f;
      while (k + 1 < spine_points.size() && acc + glm::length(spine_points[k] - spine_points[k - 1]) < s) {
        acc += glm::length(spine_points[k] - spine_points[k - 1]);
        ++k;
      }
      const glm::vec3 seg = spine_points[k] - spine_points[k - 1];
      const float seg_len = std::max(glm::length(seg), 1e-6f);
      Ring r;
      r.center = spine_points[k - 1] + seg * std::clamp((s - acc) / seg_len, 0.0f, 1.0f);
      frame_for(seg / seg_len, r.u, r.v);
      const float h = s / total;
      r.a = profile(width, h);
      r.b = profile(deep, h);
      // Weights along the chain of spine joints.
      if (s <= joint_arc[0]) {
        r.influence.add(chain[0], 1.0f);
      } else {
        size_t c = 0;
        while (c + 2 < chain.size() && s > joint_arc[c + 1]) ++c;
        const float t = (s - joint_arc[c]) / std::max(joint_arc[c + 1] - joint_arc[c], 1e-6f);
        const int previous = c > 0 ? chain[c - 1] : -1;
        r.influence = bone_influence(chain[c], previous, chain[c + 1], t, 0.35f);
      }
      torso.rings.push_back(r);
    }
    cap_piece(torso, 0.5f * depth[0] * H, 0.5f * depth[4] * H);
    builder.add(torso);
  }

  // Neck and head.
  if (body.neck >= 0 && body.head >= 0) {
    const float r = shape.neck_radius * H;
    const int before = body.spine.empty() ? body.root : body.spine.back();
    builder.add(limb_piece({P(body.neck), P(body.head), body.neck, before, body.head, r, r, 0.95f * r, 0.95f * r, 0.0f},
                           shape, n_limb, 4));
  }
  if (body.head >= 0) {
    const glm::vec3 base = P(body.head);
    const float crown = std::max(rest.sole + H, base.y + 0.08f * H);  // top of the head
    const float* hs = shape.head_half_size;
    // The head has its anthropometric height (2 hs[1] H) and sits on the head joint (the base of the
    // skull): its centre half a head above the joint, or lower so that its top is the crown of the
    // stature. Stretching it from the joint to the crown instead makes a tall egg on skeletons whose head
    // joint sits low (the CMU conversions put it at 0.85 H).
    const float half_h = hs[1] * H;
    const glm::vec3 center(base.x, std::min(crown - half_h, base.y + half_h), base.z + 0.012f * H);
    Piece head;
    head.segments = n_body;
    const int rings = 10;
    for (int i = 1; i < rings; ++i) {
      const float z = -1.0f + 2.0f * static_cast<float>(i) / static_cast<float>(rings);
      const float k = std::sqrt(1.0f - z * z);
      Ring r;
      r.center = center + glm::vec3(0, z * half_h, 0);
      r.u = glm::vec3(1, 0, 0);
      r.v = glm::vec3(0, 0, 1);
      // The jaw is narrower than the cranium.
      const float narrow = z < 0.0f ? 1.0f + 0.25f * z : 1.0f;
      r.a = hs[0] * H * k * narrow;
      r.b = hs[2] * H * k;
      r.influence.add(body.head, 1.0f);
      head.rings.push_back(r);
    }
    head.pole_start = center - glm::vec3(0, half_h, 0);
    head.pole_end = center + glm::vec3(0, half_h, 0);
    head.influence_start.add(body.head, 1.0f);
    head.influence_end.add(body.head, 1.0f);
    builder.add(head);
  }

  mesh.inverse_bind.resize(static_cast<size_t>(skeleton.size()));
  for (int j = 0; j < skeleton.size(); ++j)
    mesh.inverse_bind[static_cast<size_t>(j)] = rigid_inverse(rest.p[static_cast<size_t>(j)] + shift, rest.q[static_cast<size_t>(j)]);
  mesh.validate(skeleton);
  return mesh;
}

}  // namespace prep
