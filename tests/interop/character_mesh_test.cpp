#include "engine/interop/character_mesh.h"

#include <doctest/doctest.h>

#include "engine/library/builtin.h"
#include "engine/motion/kinematics.h"
#include "tests/interop/interop_support.h"

namespace prep {
namespace {

struct Bounds {
  glm::vec3 lo{1e9f}, hi{-1e9f};
};
Bounds bounds(const std::vector<glm::vec3>& p) {
  Bounds b;
  for (const glm::vec3& v : p) {
    b.lo = glm::min(b.lo, v);
    b.hi = glm::max(b.hi, v);
  }
  return b;
}

// Skinned positions and normals of a mesh for a pose.
void skin(const Skeleton& sk, const SkinnedMesh& mesh, const Pose& pose, std::vector<glm::vec3>& pos,
          std::vector<glm::vec3>& nrm) {
  std::vector<glm::vec3> p;
  std::vector<glm::quat> q;
  std::vector<glm::mat4> s;
  forward_kinematics(sk, pose, p, &q);
  skinning_matrices(mesh, p, q, s);
  skin_vertices(mesh, s, pos, &nrm);
}

// Every triangle's vertex normals agree with its winding, and the whole surface encloses a positive volume:
// the triangles face outward.
void check_outward(const SkinnedMesh& mesh) {
  double volume = 0.0;
  int disagree = 0;
  for (size_t i = 0; i < mesh.indices.size(); i += 3) {
    const glm::vec3 a = mesh.positions[mesh.indices[i]], b = mesh.positions[mesh.indices[i + 1]],
                    c = mesh.positions[mesh.indices[i + 2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    volume += glm::dot(glm::dvec3(a), glm::cross(glm::dvec3(b), glm::dvec3(c))) / 6.0;
    const glm::vec3 vn = mesh.normals[mesh.indices[i]] + mesh.normals[mesh.indices[i + 1]] + mesh.normals[mesh.indices[i + 2]];
    if (glm::dot(n, vn) < 0.0f) ++disagree;
  }
  CHECK(disagree == 0);
  // A human body is about 0.06-0.09 m^3; overlapping pieces count twice where they overlap.
  CHECK(volume > 0.04);
  CHECK(volume < 0.2);
}

void check_body(const Skeleton& sk, const BodyMap& body, float min_stature, float max_stature) {
  const SkinnedMesh mesh = build_character_mesh(sk, body);
  CHECK_NOTHROW(mesh.validate(sk));
  CHECK(mesh.vertex_count() > 1000);
  check_outward(mesh);
  // Bound in the bind pose: skinning the bind pose changes nothing.
  Pose bind(sk.size());
  bind.root_position = character_bind_root(sk, body);
  std::vector<glm::vec3> pos, nrm;
  skin(sk, mesh, bind, pos, nrm);
  float worst = 0.0f;
  for (size_t v = 0; v < pos.size(); ++v) worst = std::max(worst, glm::length(pos[v] - mesh.positions[v]));
  CHECK(worst < 1e-5f);
  // Soles on the floor, the head at a human stature.
  const Bounds b = bounds(mesh.positions);
  CHECK(std::fabs(b.lo.y) < 0.01f);
  CHECK(b.hi.y > min_stature);
  CHECK(b.hi.y < max_stature);
}

TEST_CASE("The built-in skeleton's body: closed outward surfaces, soles on the floor, 1.75 m tall") {
  const auto sk = builtin_skeleton();
  check_body(*sk, BodyMap::detect(*sk), 1.70f, 1.80f);
}

TEST_CASE("The same code dresses the daz43 and cmu31 skeletons") {
  for (const Clip& clip : {test::daz43_clip("walk_02_01.bvh", 1, 2), test::cmu31_clip("walk_69_01.bvh")}) {
    CAPTURE(clip.skeleton->joints[0].name);
    check_body(*clip.skeleton, BodyMap::detect(*clip.skeleton), 1.45f, 2.0f);
  }
}

TEST_CASE("Skin weights blend across the knee, and bending the knee moves the shin but not the hip") {
  const auto sk = builtin_skeleton();
  const BodyMap body = BodyMap::detect(*sk);
  const SkinnedMesh mesh = build_character_mesh(*sk, body);
  const int hip = body.legs[kLeft].hip, knee = body.legs[kLeft].knee;
  auto weight_of = [&](size_t v, int joint) {
    float w = 0.0f;
    for (int k = 0; k < 4; ++k)
      if (mesh.joints[v][k] == joint) w += mesh.weights[v][k];
    return w;
  };
  int blended = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    if (weight_of(v, hip) > 0.2f && weight_of(v, knee) > 0.2f) ++blended;
  CHECK(blended >= 2 * 16);  // at least two rings of the limb share the knee
  Pose bind(sk->size());
  bind.root_position = character_bind_root(*sk, body);
  Pose bent = bind;
  bent.rotations[static_cast<size_t>(knee)] = glm::angleAxis(1.5f, glm::vec3(1, 0, 0));
  std::vector<glm::vec3> p0, p1, n;
  skin(*sk, mesh, bind, p0, n);
  skin(*sk, mesh, bent, p1, n);
  std::vector<glm::vec3> jp;
  forward_kinematics(*sk, bind, jp);
  int shin_moved = 0, shin = 0, hip_moved = 0;
  for (size_t v = 0; v < p0.size(); ++v) {
    const bool only_knee = weight_of(v, knee) > 0.999f;
    const bool only_hip = weight_of(v, hip) > 0.999f;
    if (only_knee) {
      ++shin;
      if (glm::length(p1[v] - p0[v]) > 0.05f) ++shin_moved;
    }
    if (only_hip && glm::length(p1[v] - p0[v]) > 1e-6f) ++hip_moved;
  }
  CHECK(shin > 50);
  CHECK(shin_moved > shin / 2);
  CHECK(hip_moved == 0);
}

}  // namespace
}  // namespace prep
