// The OpenGL 3.3 core renderer: lit floor with a grid, a shadow map, characters as skinned bodies (the glTF
// character, skinned_body.h; shaded capsules per bone for a skeleton without a body), obstacles as boxes,
// balls as spheres, the goal marker, the highlighted source of influence, and the clearance view's red
// capsules over the bodies.
// It draws a Scene (scene.h) and reads nothing else. Requires a current context with gl::load() done.
//
// The capsules are the engine's body volumes (engine/motion/body_volumes.h) and the obstacles' boxes and
// balls the engine's object solids (engine/world/object_solids.h): what is drawn is what the clearance
// measure tests, so the renderer keeps no sizes of its own.
#pragma once

#include <cmath>

#include <glm/mat4x4.hpp>
#include <deque>
#include <glm/vec4.hpp>
#include <memory>
#include <string>
#include <vector>

#include "app/render/camera.h"
#include "app/render/gl_api.h"
#include "app/render/instances.h"
#include "app/render/scene.h"
#include "app/render/skinned_body.h"
#include "engine/motion/body_volumes.h"

namespace prep::render {

struct RenderSettings {
  // Texels per side; 0 disables shadows. 1024 over +-7 m (1.4 cm texels) keeps the interactive demo above
  // 60 frames/s on llvmpipe (2048 cost about 6 ms of CPU per frame more); strips use 2048.
  int shadow_map_size = 1024;
  float shadow_extent = 7.0f;  // m: half-size of the square around Scene::focus that casts shadows
  glm::vec3 light_dir{0.45f, 1.0f, 0.35f};  // toward the light (normalized by the renderer)
  // m from the eye: the fog starts, and is full (the sky's colour: nothing beyond is drawn).
  float fog_start = 30.0f, fog_end = 90.0f;
  // m from the eye: light bodies' capsules wholly beyond are drawn with 4 sides instead of 6 (16 triangles
  // instead of 24); a bone there is at most a few pixels wide.
  float distant_capsules_from = 25.0f;
  // Leave out what a pass cannot show (culling.h); false draws every instance, for comparison.
  bool cull = true;
  // Characters are drawn with their skeleton's skinned body (body_for_skeleton: the glTF character file
  // for the skeleton it was made for, our built body for other humanoids); false: capsules per bone.
  bool skinned_bodies = true;
  std::string character_path = default_character_path();  // glTF character tried first for every skeleton
};

// The primitives a scene turns into (public so that tests can check them without a GL context).
struct ScenePrimitives {
  std::vector<CapsuleInstance> capsules;
  std::vector<BoxInstance> boxes;
  std::vector<MarkerInstance> markers;
  // The clearance view's capsules (SceneCharacter::flagged): drawn over the skinned bodies, in the main
  // pass only (a debugging aid casts no shadow, so turning it on changes no other pixel).
  std::vector<CapsuleInstance> flagged;
  // The capsules of light bodies (SceneCharacter::light) and light balls (SceneObject::light), drawn with
  // the low-poly capsule.
  std::vector<CapsuleInstance> light_capsules;
};

// The body volumes of each skeleton drawn, made on first use: BodyVolumes reads the body map and every
// joint name, more than a frame should redo per character.
class BodyVolumesCache {
 public:
  // Stays valid as long as the cache (a later skeleton's entry does not move this one).
  const BodyVolumes& get(const std::shared_ptr<const Skeleton>& skeleton);

 private:
  struct Entry {
    std::shared_ptr<const Skeleton> skeleton;  // kept alive: its address must not be reused by another skeleton
    BodyVolumes volumes;
  };
  std::deque<Entry> entries_;  // a deque: appending moves no entry
};

// Characters whose entry in `skinned` is true are drawn as skinned bodies and get no capsules (their
// flagged capsules are drawn all the same). Without a cache the volumes are made for this call.
ScenePrimitives build_primitives(const Scene& scene, const std::vector<bool>& skinned, BodyVolumesCache& volumes);
ScenePrimitives build_primitives(const Scene& scene, const std::vector<bool>& skinned = {});
// Where on the floor shadows can fall: for every caster (each capsule, each box, each character's joints;
// a light body's capsules lie within its joints' rectangle) the rectangle (min x, min z, max x, max z)
// holding its footprint and its shadow cast along light_dir (toward the light), grown by its radius;
// merged (the pair whose union adds the least area first) to at most max_rects. Only there is the floor
// drawn with the shadow map lookup (ground.glsl). Rectangles wholly farther than `reach` from `focus` (on
// the floor) are left out: the shadow map does not reach them.
std::vector<glm::vec4> shadow_receiver_rects(const Scene& scene, const ScenePrimitives& prims, const glm::vec3& light_dir,
                                             int max_rects, glm::vec2 focus = glm::vec2(0.0f), float reach = INFINITY);
constexpr int kMaxShadowRects = 8;
// The capsules of one character's body, `volumes` (made for its skeleton) placed at its pose, in its colour.
void append_character_capsules(const SceneCharacter& character, const BodyVolumes& volumes, std::vector<CapsuleInstance>& out);
// Its flagged capsules in palette::kClearance, kFlaggedMargin thicker than the body's so that they show
// over the capsule view of the same body (over a skinned body the stencil shows them: Renderer::main_pass).
void append_flagged_capsules(const SceneCharacter& character, const BodyVolumes& volumes, std::vector<CapsuleInstance>& out);
constexpr float kFlaggedMargin = 0.005f;  // m
// The boxes of an obstacle (posts, bar, board, legs, feet: object_solids) or the sphere of a ball; a Box
// (a render-only type) is its own size.
void append_object_primitives(const SceneObject& object, ScenePrimitives& out);

class Renderer {
 public:
  explicit Renderer(const RenderSettings& settings = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // The three stages of a frame, separable so that the demo can time each:
  // upload the scene's instances, render the shadow map, draw the scene into the viewport (GL pixels,
  // origin bottom-left) of the currently bound framebuffer (clearing that viewport first).
  void prepare(const Scene& scene);
  void shadow_pass();
  void main_pass(const Camera& camera, int x, int y, int width, int height);

  // All three.
  void draw(const Scene& scene, const Camera& camera, int x, int y, int width, int height) {
    prepare(scene);
    shadow_pass();
    main_pass(camera, x, y, width, height);
  }

  // Screen rectangles (x, y, width, height; pixels from the top-left of the viewport) that opaque panels
  // will cover: main_pass marks them nearest in the depth buffer right after clearing, so that nothing of
  // the scene is shaded under them (on llvmpipe the floor's fragments are most of a frame). Empty: none.
  void set_covered(std::vector<glm::vec4> rects) { covered_ = std::move(rects); }

  int triangles_last_frame() const { return triangles_; }
  // The skinned body the renderer draws for this skeleton (made on first use), or nullptr: capsules.
  const SkinnedBody* body_for(const std::shared_ptr<const Skeleton>& skeleton);
  // Draws this skeleton with the given mesh (bound to it, e.g. a user's glTF character) from now on.
  void set_body(std::shared_ptr<const Skeleton> skeleton, std::shared_ptr<const SkinnedMesh> mesh);
  const RenderSettings& settings() const { return settings_; }

 private:
  void set_lighting_uniforms(GLuint program, const glm::vec3& eye);
  // The capsules and boxes a pass through this view-projection can show (culling.h) into the instance
  // buffers the draws below read; seen from `eye` (the main pass), also without what lies beyond the fog,
  // and with the light capsules beyond distant_capsules_from apart.
  void upload_visible(const glm::mat4& view_proj, const glm::vec3* eye);
  void draw_capsule_bodies(GLuint program, const glm::mat4& view_proj);
  void draw_boxes(GLuint program, const glm::mat4& view_proj);
  void draw_skinned_bodies(GLuint program, const glm::mat4& view_proj);
  void draw_flagged(const glm::mat4& view_proj);

  struct BodyEntry {
    std::shared_ptr<const Skeleton> skeleton;  // kept alive: the key must not be reused by another skeleton
    std::unique_ptr<SkinnedBody> body;         // nullptr: this skeleton has no body, draw capsules
  };
  struct SkinnedDraw {
    const SkinnedBody* body = nullptr;
    std::vector<glm::mat4> skinning;  // S[j] = W[j] * inverse_bind[j] of this frame's pose
    glm::vec3 colour{0.0f};
    float glow = 0.0f;
  };

  RenderSettings settings_;
  std::vector<glm::vec4> covered_;
  ScenePrimitives primitives_;
  ScenePrimitives visible_;  // of primitives_, what the pass being drawn can show (capsules, light capsules, boxes)
  std::vector<CapsuleInstance> distant_;  // of the light capsules, those drawn with the distant mesh
  std::vector<BodyEntry> bodies_;
  BodyVolumesCache volumes_;
  std::vector<SkinnedDraw> skinned_draws_;
  glm::vec3 focus_{0.0f};
  glm::mat4 light_view_proj_{1.0f};
  std::vector<glm::vec4> shadow_rects_;

  GLuint capsule_program_ = 0, box_program_ = 0, ground_program_ = 0, marker_program_ = 0;
  GLuint capsule_depth_program_ = 0, box_depth_program_ = 0;
  GLuint skinned_program_ = 0, skinned_depth_program_ = 0, skin_block_ = 0;
  GLuint capsule_vao_ = 0, capsule_vbo_ = 0, capsule_ibo_ = 0, capsule_instances_ = 0;
  GLuint flagged_vao_ = 0, flagged_instances_ = 0;  // the same capsule mesh, the flagged instances
  GLuint light_vao_ = 0, light_vbo_ = 0, light_ibo_ = 0, light_instances_ = 0;  // the low-poly capsule
  int light_index_count_ = 0;
  GLuint distant_vao_ = 0, distant_vbo_ = 0, distant_ibo_ = 0, distant_instances_ = 0;  // the 4-sided capsule
  int distant_index_count_ = 0;
  GLuint box_vao_ = 0, box_vbo_ = 0, box_ibo_ = 0, box_instances_ = 0;
  GLuint ground_vao_ = 0, ground_vbo_ = 0, receiver_vao_ = 0, receiver_vbo_ = 0;
  GLuint ground_unshadowed_program_ = 0;
  GLuint marker_vao_ = 0, marker_vbo_ = 0, marker_instances_ = 0;
  GLuint shadow_fbo_ = 0, shadow_texture_ = 0;
  int capsule_index_count_ = 0;
  int box_index_count_ = 0;
  int triangles_ = 0;
};

}  // namespace prep::render
