#include "engine/interop/gltf_io.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>

#include "engine/interop/character_mesh.h"
#include "engine/library/builtin.h"
#include "engine/motion/body_map.h"
#include "engine/util/error.h"
#include "engine/util/files.h"
#include "tests/interop/gltf_validator.h"
#include "tests/interop/interop_support.h"

namespace prep {
namespace {

using test::clip_difference;
using test::scratch;

TEST_CASE("glTF export of a real clip passes the Khronos validator and imports with the same joint transforms") {
  const Clip clip = test::daz43_clip("walk_02_01.bvh", 1, 120);
  for (const char* name : {"walk_daz43.glb", "walk_daz43.gltf"}) {
    CAPTURE(name);
    const std::string path = scratch(name);
    GltfScene scene;
    scene.characters = {clip};
    write_gltf(scene, path);
    test::check_gltf_valid(path);
    const std::vector<GltfCharacter> back = read_gltf(path);
    REQUIRE(back.size() == 1);
    REQUIRE(back[0].clips.size() == 1);
    const Clip& imported = back[0].clips[0];
    CHECK(imported.fps == doctest::Approx(clip.fps));
    CHECK(imported.skeleton->size() == clip.skeleton->size());
    // Bone offsets and End Sites survive.
    for (int j = 1; j < clip.skeleton->size(); ++j) {
      const Joint& a = clip.skeleton->joints[static_cast<size_t>(j)];
      const Joint& b = imported.skeleton->joints[static_cast<size_t>(imported.skeleton->find(a.name))];
      CHECK(glm::length(a.offset - b.offset) < 1e-5f);
      CHECK(a.has_end_site == b.has_end_site);
      if (a.has_end_site) CHECK(glm::length(a.end_site - b.end_site) < 1e-5f);
    }
    const test::PoseDifference d = clip_difference(clip, imported);
    CHECK(d.position < 1e-4f);
    CHECK(d.rotation < 1e-4f);
  }
}

TEST_CASE("BVH export then import gives the same joint transforms") {
  const Clip clip = test::daz43_clip("jump_forward_13_11.bvh", 200, 100);
  const std::string path = scratch("jump.bvh");
  write_bvh(clip, path);
  BvhReadOptions options;
  options.unit_scale = 0.01f;
  const Clip back = read_bvh(path, options);
  const test::PoseDifference d = clip_difference(clip, back);
  CHECK(d.position < 1e-4f);
  CHECK(d.rotation < 1e-4f);
}

TEST_CASE("A skinned character round-trips through glTF: same mesh, same skinned vertices") {
  const auto skeleton = builtin_skeleton();
  const SkinnedMesh mesh = build_character_mesh(*skeleton, BodyMap::detect(*skeleton));
  // A clip that bends the knees and turns the trunk, so that skinning is exercised.
  Clip clip;
  clip.name = "bend";
  clip.skeleton = skeleton;
  clip.fps = 30.0f;
  for (int f = 0; f < 10; ++f) {
    Pose pose(skeleton->size());
    pose.root_position = character_bind_root(*skeleton, BodyMap::detect(*skeleton)) + glm::vec3(0.01f * f, 0, 0);
    const float a = 0.1f * f;
    pose.rotations[static_cast<size_t>(skeleton->find("LeftLeg"))] = glm::angleAxis(a, glm::vec3(1, 0, 0));
    pose.rotations[static_cast<size_t>(skeleton->find("Spine1"))] = glm::angleAxis(0.5f * a, glm::vec3(0, 1, 0));
    clip.frames.push_back(pose);
  }
  const std::string path = scratch("bend_with_mesh.glb");
  GltfScene scene;
  scene.characters = {clip};
  scene.mesh = &mesh;
  write_gltf(scene, path);
  test::check_gltf_valid(path);
  const std::vector<GltfCharacter> back = read_gltf(path);
  REQUIRE(back.size() == 1);
  const GltfCharacter& c = back[0];
  REQUIRE(c.mesh.vertex_count() == mesh.vertex_count());
  REQUIRE(c.mesh.indices == mesh.indices);
  REQUIRE(c.clips.size() == 1);
  const test::PoseDifference d = clip_difference(clip, c.clips[0]);
  CHECK(d.position < 1e-4f);
  CHECK(d.rotation < 1e-4f);
  // Skinned vertices of the last frame agree.
  std::vector<glm::vec3> p, pa, pb;
  std::vector<glm::quat> q;
  std::vector<glm::mat4> sa, sb;
  forward_kinematics(*skeleton, clip.frames.back(), p, &q);
  skinning_matrices(mesh, p, q, sa);
  skin_vertices(mesh, sa, pa);
  forward_kinematics(*c.skeleton, c.clips[0].frames.back(), p, &q);
  skinning_matrices(c.mesh, p, q, sb);
  skin_vertices(c.mesh, sb, pb);
  float worst = 0.0f;
  for (size_t v = 0; v < pa.size(); ++v) worst = std::max(worst, glm::length(pa[v] - pb[v]));
  CHECK(worst < 1e-4f);
}

// ---------------------------------------------------------------------------------------------------
// Malformed files, all made from a good one.
// ---------------------------------------------------------------------------------------------------

struct Glb {
  nlohmann::json json;
  std::string bin;
};

uint32_t u32(const std::string& s, size_t at) {
  uint32_t v;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}

Glb split_glb(const std::string& bytes) {
  const uint32_t json_len = u32(bytes, 12);
  Glb g;
  g.json = nlohmann::json::parse(bytes.substr(20, json_len));
  const size_t bin_at = 20 + json_len;
  g.bin = bytes.substr(bin_at + 8, u32(bytes, bin_at));
  return g;
}

std::string join_glb(const Glb& g) {
  std::string json = g.json.dump();
  while (json.size() % 4) json += ' ';
  std::string out(12, '\0');
  auto put = [&](size_t at, uint32_t v) { std::memcpy(&out[at], &v, 4); };
  auto append_u32 = [&](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  append_u32(static_cast<uint32_t>(json.size()));
  append_u32(0x4E4F534A);
  out += json;
  append_u32(static_cast<uint32_t>(g.bin.size()));
  append_u32(0x004E4942);
  out += g.bin;
  put(0, 0x46546C67);
  put(4, 2);
  put(8, static_cast<uint32_t>(out.size()));
  return out;
}

const std::string& good_glb() {
  static const std::string bytes = [] {
    const auto skeleton = builtin_skeleton();
    const SkinnedMesh mesh = build_character_mesh(*skeleton, BodyMap::detect(*skeleton));
    Clip clip;
    clip.name = "still";
    clip.skeleton = skeleton;
    clip.frames.assign(3, Pose(skeleton->size()));
    GltfScene scene;
    scene.characters = {clip};
    scene.mesh = &mesh;
    return format_gltf(scene, true);
  }();
  return bytes;
}

// The byte offset in the BIN chunk of element 0 of an accessor.
size_t accessor_data_offset(const Glb& g, int accessor) {
  const auto& a = g.json["accessors"][static_cast<size_t>(accessor)];
  const auto& bv = g.json["bufferViews"][a["bufferView"].get<size_t>()];
  return bv.value("byteOffset", size_t{0}) + a.value("byteOffset", size_t{0});
}

std::string error_of(const std::string& bytes) {
  try {
    parse_gltf(bytes, "bad.glb");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST_CASE("The good file that the malformed ones start from is read") {
  const std::vector<GltfCharacter> c = parse_gltf(good_glb(), "good.glb");
  REQUIRE(c.size() == 1);
  CHECK(!c[0].mesh.empty());
  CHECK(c[0].clips.size() == 1);
}

TEST_CASE("Malformed glTF files give a clear error naming the file and the field") {
  const std::string good = good_glb();
  const Glb base = split_glb(good);
  const int position = base.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>();
  const int joints = base.json["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"].get<int>();
  const int ibm = base.json["skins"][0]["inverseBindMatrices"].get<int>();

  SUBCASE("truncated .glb") {
    const std::string e = error_of(good.substr(0, good.size() / 2));
    CHECK(contains(e, "bad.glb: GLB: header declares"));
    CHECK(contains(e, "truncated"));
  }
  SUBCASE("truncated inside the header") { CHECK(contains(error_of(good.substr(0, 7)), "GLB: truncated header")); }
  SUBCASE("bad JSON") {
    std::string json = base.json.dump();
    json.erase(json.size() / 2, 1);
    json = json.substr(0, json.size() - 3);
    const std::string e = error_of(json);
    CHECK(contains(e, "bad.glb: not a valid glTF"));
  }
  SUBCASE("an accessor running past its buffer") {
    Glb g = base;
    g.json["accessors"][static_cast<size_t>(position)]["count"] = g.json["accessors"][static_cast<size_t>(position)]["count"].get<size_t>() + 100000;
    const std::string e = error_of(join_glb(g));
    CHECK(contains(e, "meshes[0].primitives[0].attributes.POSITION (accessors[" + std::to_string(position) + "])"));
    CHECK(contains(e, "runs past the end of bufferViews"));
  }
  SUBCASE("a huge count does not overflow the range check") {
    Glb g = base;
    g.json["accessors"][static_cast<size_t>(position)]["count"] = std::numeric_limits<uint32_t>::max();
    CHECK(contains(error_of(join_glb(g)), "runs past the end of bufferViews"));
  }
  SUBCASE("a buffer view past its buffer") {
    Glb g = base;
    const size_t view = g.json["accessors"][static_cast<size_t>(position)]["bufferView"].get<size_t>();
    g.json["bufferViews"][view]["byteLength"] = g.bin.size() * 2;
    const std::string e = error_of(join_glb(g));
    CHECK((contains(e, "runs past buffers[0]") || contains(e, "bufferView")));
  }
  SUBCASE("count 0") {
    Glb g = base;
    g.json["accessors"][static_cast<size_t>(position)]["count"] = 0;
    const std::string e = error_of(join_glb(g));
    CHECK(contains(e, "bad.glb: "));
    CHECK(contains(e, "count"));
  }
  SUBCASE("negative stride") {
    Glb g = base;
    const size_t view = g.json["accessors"][static_cast<size_t>(position)]["bufferView"].get<size_t>();
    g.json["bufferViews"][view]["byteStride"] = -12;
    const std::string e = error_of(join_glb(g));
    CHECK(contains(e, "bad.glb: "));
    CHECK(contains(e, "byteStride"));
  }
  SUBCASE("a huge stride") {
    Glb g = base;
    const size_t view = g.json["accessors"][static_cast<size_t>(position)]["bufferView"].get<size_t>();
    g.json["bufferViews"][view]["byteStride"] = 4000000;
    CHECK(contains(error_of(join_glb(g)), "byteStride"));
  }
  SUBCASE("a skin joint index out of range in JOINTS_0") {
    Glb g = base;
    const uint16_t bad = 999;
    std::memcpy(&g.bin[accessor_data_offset(g, joints) + 8 * 5], &bad, 2);  // vertex 5, first joint
    const std::string e = error_of(join_glb(g));
    CHECK(contains(e, "attributes.JOINTS_0: vertex 5 uses joint 999 but skins[0] has"));
  }
  SUBCASE("a skin listing a node that does not exist") {
    Glb g = base;
    g.json["skins"][0]["joints"].push_back(4096);
    const std::string e = error_of(join_glb(g));
    CHECK(contains(e, "bad.glb: "));
    CHECK((contains(e, "skins[0].joints: node 4096 does not exist") || contains(e, "4096")));
  }
  SUBCASE("NaN in an inverse bind matrix") {
    Glb g = base;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&g.bin[accessor_data_offset(g, ibm) + 64 * 3 + 4 * 5], &nan, 4);  // matrix 3, element 5
    const std::string e = error_of(join_glb(g));
    CHECK(contains(e, "skins[0].inverseBindMatrices: matrix 3 element 5 is not finite"));
  }
  SUBCASE("an index out of range") {
    Glb g = base;
    const int indices = g.json["meshes"][0]["primitives"][0]["indices"].get<int>();
    const uint16_t bad = 65000;
    std::memcpy(&g.bin[accessor_data_offset(g, indices) + 2 * 7], &bad, 2);
    CHECK(contains(error_of(join_glb(g)), "primitives[0].indices: index 7 = 65000 is out of range"));
  }
  SUBCASE("animation times not increasing") {
    Glb g = base;
    const int input = g.json["animations"][0]["samplers"][0]["input"].get<int>();
    const float t = 5.0f;
    std::memcpy(&g.bin[accessor_data_offset(g, input)], &t, 4);
    CHECK(contains(error_of(join_glb(g)), "times are not strictly increasing"));
  }
  SUBCASE("a node hierarchy with a cycle") {
    Glb g = base;
    g.json["nodes"][1]["children"].push_back(0);
    CHECK(contains(error_of(join_glb(g)), "bad.glb: "));
  }
  SUBCASE("an empty file and random bytes") {
    CHECK(contains(error_of(""), "bad.glb: "));
    CHECK(contains(error_of(std::string("glTF\x02\0\0\0\xff\xff\xff\xff", 12)), "GLB: header declares"));
  }
}

TEST_CASE("animation keys too far apart to resample are refused, naming the file and the animation") {
  // Found by the glTF fuzz target (the input is in its corpus): two keys 6.8e22 s apart. Their spacing as a
  // frame rate, 1.5e-23 frames/s, was rounded to 0, and every resampled time became 0/0: the channel
  // sampler then read past its last key. Keys farther apart than a second are resampled at the default
  // 30 frames/s instead, so this animation is 2e24 frames long, and refused.
  const std::string path = test::repo() + "/tests/fuzz/corpus/gltf/anim_keys_far_apart.gltf";
  std::string error = "(no error)";
  try {
    read_gltf(path);
  } catch (const InputError& e) {
    error = e.what();
  }
  CHECK(contains(error, "anim_keys_far_apart.gltf"));
  CHECK(contains(error, "animations[0]: "));
  CHECK(contains(error, "too long to resample"));
  // The seed it was made from (keys 0.5 s apart) still reads at its keys' own rate.
  const std::vector<GltfCharacter> rig = read_gltf(test::repo() + "/tests/fuzz/corpus/gltf/rig.gltf");
  REQUIRE(rig.size() == 1);
  REQUIRE(rig[0].clips.size() == 1);
  CHECK(rig[0].clips[0].fps == doctest::Approx(2.0f));
  CHECK(rig[0].clips[0].frame_count() == 2);
}

TEST_CASE("load_character_mesh binds the committed character to the built-in skeleton") {
  const auto skeleton = builtin_skeleton();
  const std::string path = test::repo() + "/assets/character.glb";
  test::check_gltf_valid(path);
  const SkinnedMesh loaded = load_character_mesh(path, *skeleton);
  const SkinnedMesh built = build_character_mesh(*skeleton, BodyMap::detect(*skeleton));
  // The committed asset is what the current code builds.
  REQUIRE(loaded.vertex_count() == built.vertex_count());
  float worst = 0.0f;
  for (int v = 0; v < built.vertex_count(); ++v)
    worst = std::max(worst, glm::length(loaded.positions[static_cast<size_t>(v)] - built.positions[static_cast<size_t>(v)]));
  CHECK(worst < 1e-5f);
  CHECK(loaded.joints == built.joints);
  CHECK_THROWS_AS(load_character_mesh(path, *test::daz43_clip("walk_02_01.bvh", 1, 2).skeleton), InputError);
}

}  // namespace
}  // namespace prep
