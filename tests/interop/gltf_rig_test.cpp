// Import of a rig as other tools write it: joints with rest rotations under an "Armature" node that
// rotates and scales (centimetres to metres), Mixamo-style names, a skinned triangle. The expected world
// positions are computed here from glTF's own definitions (node matrices, joint matrix * inverse bind).
#include <doctest/doctest.h>
#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <sstream>

#include "engine/interop/gltf_io.h"
#include "engine/motion/kinematics.h"

namespace prep {
namespace {

template <typename T>
int add_data(tinygltf::Model& m, const std::vector<T>& values, int type, int component, size_t count) {
  tinygltf::Buffer& b = m.buffers[0];
  while (b.data.size() % 4) b.data.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = b.data.size();
  view.byteLength = values.size() * sizeof(T);
  const auto* p = reinterpret_cast<const unsigned char*>(values.data());
  b.data.insert(b.data.end(), p, p + view.byteLength);
  m.bufferViews.push_back(view);
  tinygltf::Accessor a;
  a.bufferView = static_cast<int>(m.bufferViews.size() - 1);
  a.byteOffset = 0;
  a.componentType = component;
  a.type = type;
  a.count = count;
  a.normalized = false;
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size() - 1);
}

glm::dmat4 trs(const glm::dvec3& t, const glm::dquat& r, const glm::dvec3& s) {
  return glm::translate(glm::dmat4(1.0), t) * glm::mat4_cast(r) * glm::scale(glm::dmat4(1.0), s);
}

TEST_CASE("A Mixamo-like rig (rest rotations, scaled armature) imports with the same world joints and skinning") {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.buffers.resize(1);
  // Nodes: 0 Armature (rotated -90 deg about X, scale 0.01), 1 Hips, 2 Spine, 3 Head, 4 HeadTop_End, 5 mesh.
  const glm::dquat armature_rot = glm::angleAxis(-glm::half_pi<double>(), glm::dvec3(1, 0, 0));
  const glm::dvec3 t_hips(0, 0, 95), t_spine(0, 10, 2), t_head(0, 40, -3), t_end(0, 20, 0);  // centimetres
  const glm::dquat r_hips = glm::angleAxis(0.5 * glm::half_pi<double>(), glm::dvec3(1, 0, 0));
  const glm::dquat r_spine = glm::angleAxis(0.3, glm::normalize(glm::dvec3(0, 1, 1)));
  const glm::dquat r_head = glm::angleAxis(-0.4, glm::dvec3(0, 0, 1));
  auto node = [&](const char* name, glm::dvec3 t, glm::dquat r, std::vector<int> children) {
    tinygltf::Node n;
    n.name = name;
    n.translation = {t.x, t.y, t.z};
    n.rotation = {r.x, r.y, r.z, r.w};
    n.children = std::move(children);
    m.nodes.push_back(n);
  };
  node("Armature", glm::dvec3(0), armature_rot, {1});
  m.nodes[0].scale = {0.01, 0.01, 0.01};
  node("mixamorig:Hips", t_hips, r_hips, {2});
  node("mixamorig:Spine", t_spine, r_spine, {3});
  node("mixamorig:Head", t_head, r_head, {4});
  node("mixamorig:HeadTop_End", t_end, glm::dquat(1, 0, 0, 0), {});
  // Rest world matrices by glTF's definition.
  const glm::dmat4 W0 = trs(glm::dvec3(0), armature_rot, glm::dvec3(0.01));
  const glm::dmat4 W1 = W0 * trs(t_hips, r_hips, glm::dvec3(1));
  const glm::dmat4 W2 = W1 * trs(t_spine, r_spine, glm::dvec3(1));
  const glm::dmat4 W3 = W2 * trs(t_head, r_head, glm::dvec3(1));
  // Skin: joints Hips, Spine, Head, HeadTop_End; inverse binds of the rest pose.
  std::vector<float> ibm;
  for (const glm::dmat4& w : {W1, W2, W3, W3 * trs(t_end, glm::dquat(1, 0, 0, 0), glm::dvec3(1))}) {
    const glm::mat4 inv(glm::inverse(w));
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) ibm.push_back(inv[c][r]);
  }
  tinygltf::Skin skin;
  skin.joints = {1, 2, 3, 4};
  skin.inverseBindMatrices = add_data(m, ibm, TINYGLTF_TYPE_MAT4, TINYGLTF_COMPONENT_TYPE_FLOAT, 4);
  m.skins.push_back(skin);
  // A triangle near the head, weighted to Spine and Head (vertex positions in bind = world space).
  const std::vector<glm::vec3> tri = {{0.1f, 1.5f, 0.0f}, {-0.1f, 1.5f, 0.0f}, {0.0f, 1.6f, 0.1f}};
  std::vector<float> pos;
  for (const glm::vec3& v : tri) pos.insert(pos.end(), {v.x, v.y, v.z});
  const std::vector<uint16_t> joints = {1, 2, 0, 0, 2, 0, 0, 0, 1, 2, 0, 0};
  const std::vector<float> weights = {0.25f, 0.75f, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0};
  const std::vector<uint16_t> indices = {0, 1, 2};
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = add_data(m, pos, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT, 3);
  prim.attributes["JOINTS_0"] = add_data(m, joints, TINYGLTF_TYPE_VEC4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, 3);
  prim.attributes["WEIGHTS_0"] = add_data(m, weights, TINYGLTF_TYPE_VEC4, TINYGLTF_COMPONENT_TYPE_FLOAT, 3);
  prim.indices = add_data(m, indices, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, 3);
  tinygltf::Mesh mesh;
  mesh.primitives.push_back(prim);
  m.meshes.push_back(mesh);
  tinygltf::Node mesh_node;
  mesh_node.name = "Body";
  mesh_node.mesh = 0;
  mesh_node.skin = 0;
  m.nodes.push_back(mesh_node);
  m.nodes[0].children.push_back(5);
  // Animation: 3 keys at 30 fps rotating Spine and Head, moving Hips.
  const std::vector<float> times = {0.0f, 1.0f / 30.0f, 2.0f / 30.0f};
  std::vector<glm::dquat> spine_keys, head_keys;
  std::vector<glm::dvec3> hips_keys;
  std::vector<float> spine_out, head_out, hips_out;
  for (int k = 0; k < 3; ++k) {
    spine_keys.push_back(glm::normalize(glm::angleAxis(0.2 * k, glm::dvec3(1, 0, 0)) * r_spine));
    head_keys.push_back(glm::normalize(r_head * glm::angleAxis(0.3 * k, glm::dvec3(0, 1, 0))));
    hips_keys.push_back(t_hips + glm::dvec3(5.0 * k, 0, 0));
    spine_out.insert(spine_out.end(), {float(spine_keys[k].x), float(spine_keys[k].y), float(spine_keys[k].z), float(spine_keys[k].w)});
    head_out.insert(head_out.end(), {float(head_keys[k].x), float(head_keys[k].y), float(head_keys[k].z), float(head_keys[k].w)});
    hips_out.insert(hips_out.end(), {float(hips_keys[k].x), float(hips_keys[k].y), float(hips_keys[k].z)});
  }
  const int input = add_data(m, times, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_FLOAT, 3);
  m.accessors[static_cast<size_t>(input)].minValues = {0.0};
  m.accessors[static_cast<size_t>(input)].maxValues = {times.back()};
  tinygltf::Animation anim;
  anim.name = "wave";
  auto channel = [&](int node, const char* path, int output) {
    tinygltf::AnimationSampler s;
    s.input = input;
    s.output = output;
    anim.samplers.push_back(s);
    tinygltf::AnimationChannel c;
    c.sampler = static_cast<int>(anim.samplers.size() - 1);
    c.target_node = node;
    c.target_path = path;
    anim.channels.push_back(c);
  };
  channel(2, "rotation", add_data(m, spine_out, TINYGLTF_TYPE_VEC4, TINYGLTF_COMPONENT_TYPE_FLOAT, 3));
  channel(3, "rotation", add_data(m, head_out, TINYGLTF_TYPE_VEC4, TINYGLTF_COMPONENT_TYPE_FLOAT, 3));
  channel(1, "translation", add_data(m, hips_out, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT, 3));
  m.animations.push_back(anim);
  tinygltf::Scene scene;
  scene.nodes = {0};
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  REQUIRE(writer.WriteGltfSceneToStream(&m, out, false, true));

  const std::vector<GltfCharacter> characters = parse_gltf(out.str(), "rig.glb");
  REQUIRE(characters.size() == 1);
  const GltfCharacter& c = characters[0];
  REQUIRE(c.skeleton->size() == 3);  // HeadTop_End became the head's End Site
  CHECK(c.skeleton->joints[0].name == "mixamorig:Hips");
  CHECK(c.skeleton->joints[2].has_end_site);
  REQUIRE(c.clips.size() == 1);
  REQUIRE(c.clips[0].frame_count() == 3);
  CHECK(c.clips[0].fps == doctest::Approx(30.0f));
  std::vector<glm::vec3> p, skinned;
  std::vector<glm::quat> q;
  std::vector<glm::mat4> S;
  for (int k = 0; k < 3; ++k) {
    CAPTURE(k);
    const glm::dmat4 A1 = W0 * trs(hips_keys[k], r_hips, glm::dvec3(1));
    const glm::dmat4 A2 = A1 * trs(t_spine, spine_keys[k], glm::dvec3(1));
    const glm::dmat4 A3 = A2 * trs(t_head, head_keys[k], glm::dvec3(1));
    const glm::dmat4 A4 = A3 * trs(t_end, glm::dquat(1, 0, 0, 0), glm::dvec3(1));
    forward_kinematics(*c.skeleton, c.clips[0].frames[static_cast<size_t>(k)], p, &q);
    const std::vector<glm::dmat4> expected = {A1, A2, A3};
    for (size_t j = 0; j < 3; ++j) CHECK(glm::length(glm::dvec3(p[j]) - glm::dvec3(expected[j][3])) < 1e-4);
    CHECK(glm::length(glm::dvec3(end_site_position(*c.skeleton, 2, p, q)) - glm::dvec3(A4[3])) < 1e-4);
    // Skinning by glTF's definition: sum of w * joint world * inverse bind.
    skinning_matrices(c.mesh, p, q, S);
    skin_vertices(c.mesh, S, skinned);
    const glm::dmat4 J[3] = {A1 * glm::inverse(W1), A2 * glm::inverse(W2), A3 * glm::inverse(W3)};
    for (size_t v = 0; v < 3; ++v) {
      glm::dmat4 M(0.0);
      for (int i = 0; i < 4; ++i) {
        const double w = weights[v * 4 + static_cast<size_t>(i)];
        if (w > 0) M += J[joints[v * 4 + static_cast<size_t>(i)]] * w;
      }
      const glm::dvec3 want(M * glm::dvec4(glm::dvec3(tri[v]), 1.0));
      CHECK(glm::length(glm::dvec3(skinned[v]) - want) < 1e-4);
    }
  }
}

}  // namespace
}  // namespace prep
