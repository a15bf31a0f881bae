// The skinned glTF body in the renderer: the built-in skeleton gets assets/character.glb through tinygltf,
// other humanoids a body built for them, anything else capsules; the GPU skinning puts the body's pixels
// exactly where the CPU skinning of engine/interop puts its vertices.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "app/render/camera.h"
#include "app/render/gl_context.h"
#include "app/render/palette.h"
#include "app/render/renderer.h"
#include "app/render/skinned_body.h"
#include "engine/interop/gltf_io.h"
#include "engine/library/builtin.h"
#include "engine/motion/kinematics.h"
#include "engine/motion/motion_set.h"
#include "tests/support/paths.h"

using namespace prep;
using namespace prep::render;
using palette::PixelClass;

namespace {

const MotionSet& builtin_set() {
  static const MotionSet set = make_builtin_motion_set(Params{});
  return set;
}

struct Box {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
  void add(int x, int y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  bool empty() const { return x1 < 0; }
};

}  // namespace

TEST_CASE("the built-in skeleton's body is assets/character.glb, read through tinygltf") {
  const auto skeleton = builtin_skeleton();
  std::string why;
  const auto mesh = body_for_skeleton(*skeleton, default_character_path(), &why);
  REQUIRE(mesh);
  CHECK(why.empty());  // the file was made for this skeleton: nothing was built instead
  const SkinnedMesh from_file = load_character_mesh(default_character_path(), *skeleton);
  CHECK(mesh->vertex_count() == from_file.vertex_count());
  CHECK(mesh->triangle_count() == from_file.triangle_count());
  CHECK(mesh->positions.front() == from_file.positions.front());
}

TEST_CASE("other humanoids get a body built for them, a broken character file falls back, and non-humanoids get none") {
  // The daz43 CMU skeleton (43 joints): the character file is for another skeleton, so ours is built.
  const MotionSet daz = load_motion_set(test::repo() + "/assets/manifests/daz43.json", Params{});
  std::string why;
  const auto daz_body = body_for_skeleton(*daz.skeleton, default_character_path(), &why);
  REQUIRE(daz_body);
  CHECK(daz_body->inverse_bind.size() == static_cast<size_t>(daz.skeleton->size()));
  CHECK(why.find("character.glb") != std::string::npos);  // says why the file was not used

  // A corrupt character file: the reason names the file, and the body is built instead.
  std::filesystem::create_directories(test::tmp_dir());
  const std::string broken = test::tmp_dir() + "/broken_character.glb";
  std::ofstream(broken, std::ios::binary) << "glTF\x02\x00\x00\x00 truncated";
  const auto fallback = body_for_skeleton(*builtin_skeleton(), broken, &why);
  REQUIRE(fallback);
  CHECK(why.find("broken_character.glb") != std::string::npos);

  // Two joints are no humanoid: no body (the renderer draws capsules).
  auto stick = std::make_shared<Skeleton>();
  stick->joints.resize(2);
  stick->joints[0].name = "a";
  stick->joints[1].name = "b";
  stick->joints[1].parent = 0;
  stick->joints[1].offset = {0.0f, 0.5f, 0.0f};
  CHECK_FALSE(body_for_skeleton(*stick, default_character_path(), &why));
  CHECK_FALSE(why.empty());
}

TEST_CASE("GPU skinning draws the body where the CPU skinning puts it") {
  const MotionSet& set = builtin_set();
  const MotionClip* walk = nullptr;
  for (const MotionClip& c : set.clips)
    if (c.role == Role::Walk) walk = &c;
  REQUIRE(walk);
  Pose pose = walk->clip.frames[walk->clip.frames.size() / 3];
  pose.root_position.x = pose.root_position.z = 0.0f;
  const SceneCharacter character = make_scene_character(set.skeleton, pose, palette::kCharacter);

  OsMesaContext context(640, 480);
  Renderer renderer;
  const SkinnedBody* body = renderer.body_for(set.skeleton);
  REQUIRE(body);
  Scene scene;
  scene.characters = {character};
  scene.focus = {0.0f, 0.9f, 0.0f};
  Camera camera;
  camera.target = {0.0f, 0.9f, 0.0f};
  camera.yaw = 1.2f;  // from the character's front-left
  camera.pitch = 0.15f;
  camera.distance = 3.2f;
  renderer.draw(scene, camera, 0, 0, 640, 480);
  const Image image = context.read_pixels();
  write_png(image, test::tmp_dir() + "/render_skinned_body.png");  // for a look by eye
  // The shadow pass and the main pass each drew the whole mesh, and no capsule of the body.
  CHECK(renderer.triangles_last_frame() >= 2 * body->triangle_count());
  CHECK(renderer.triangles_last_frame() < 2 * body->triangle_count() + 100);

  // The character's pixels and the CPU-skinned vertices cover the same screen box (within 2 pixels).
  std::vector<glm::mat4> skinning;
  skinning_matrices(body->mesh(), character.joint_positions, character.joint_rotations, skinning);
  std::vector<glm::vec3> skinned;
  skin_vertices(body->mesh(), skinning, skinned);
  const glm::mat4 vp = camera.view_projection(640.0f / 480.0f);
  Box expected, drawn;
  for (const glm::vec3& v : skinned) {
    glm::vec2 pixel;
    REQUIRE(project_to_pixel(vp, v, image.width, image.height, pixel));
    expected.add(static_cast<int>(pixel.x), static_cast<int>(pixel.y));
  }
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* c = image.pixel(x, y);
      if (palette::classify(c[0], c[1], c[2]) == PixelClass::Character) drawn.add(x, y);
    }
  REQUIRE_FALSE(drawn.empty());
  CHECK(std::abs(drawn.x0 - expected.x0) <= 2);
  CHECK(std::abs(drawn.x1 - expected.x1) <= 2);
  CHECK(std::abs(drawn.y0 - expected.y0) <= 2);
  CHECK(std::abs(drawn.y1 - expected.y1) <= 2);

  // The head joint lies inside the head of the body.
  glm::vec2 head;
  const int head_joint_index = head_joint(*set.skeleton);
  REQUIRE(project_to_pixel(vp, character.joint_positions[static_cast<size_t>(head_joint_index)], image.width, image.height, head));
  const std::uint8_t* h = image.pixel(static_cast<int>(head.x), static_cast<int>(head.y));
  CHECK(palette::classify(h[0], h[1], h[2]) == PixelClass::Character);
}
