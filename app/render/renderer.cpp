#include "app/render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>
#include <string>

#include "app/render/culling.h"
#include "app/render/meshes.h"
#include "app/render/palette.h"
#include "app/render/shader.h"
#include "engine/world/object_solids.h"

namespace prep::render {

using namespace prep::gl;

namespace {

glm::mat4 box_model(const glm::vec3& origin, float heading, const glm::vec3& local_centre, const glm::vec3& extents) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), origin);
  m = glm::rotate(m, heading, glm::vec3(0, 1, 0));
  m = glm::translate(m, local_centre);
  return glm::scale(m, extents);
}

void bind_float_attribute(GLuint location, int components, int stride, size_t offset, bool per_instance) {
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offset));
  glVertexAttribDivisor(location, per_instance ? 1 : 0);
}

template <typename T>
void upload(GLuint buffer, const std::vector<T>& data) {
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(T)), data.empty() ? nullptr : data.data(),
               GL_STREAM_DRAW);
}

}  // namespace

const BodyVolumes& BodyVolumesCache::get(const std::shared_ptr<const Skeleton>& skeleton) {
  for (const Entry& e : entries_)
    if (e.skeleton == skeleton) return e.volumes;
  entries_.push_back({skeleton, BodyVolumes(*skeleton)});
  return entries_.back().volumes;
}

namespace {

// The character's capsules placed at its pose; false (nothing placed) for a pose of another skeleton.
bool place_capsules(const SceneCharacter& character, const BodyVolumes& volumes, std::vector<PlacedCapsule>& placed) {
  const size_t joints = static_cast<size_t>(character.skeleton->size());
  if (character.joint_positions.size() != joints || character.joint_rotations.size() != joints) return false;
  volumes.place(character.joint_positions, character.joint_rotations, placed);
  return true;
}

}  // namespace

void append_character_capsules(const SceneCharacter& character, const BodyVolumes& volumes, std::vector<CapsuleInstance>& out) {
  std::vector<PlacedCapsule> placed;
  if (!place_capsules(character, volumes, placed)) return;
  const float glow = character.is_source ? 1.0f : 0.0f;
  for (const PlacedCapsule& c : placed) out.push_back({glm::vec4(c.a, c.radius), glm::vec4(c.b, glow), character.colour});
}

void append_flagged_capsules(const SceneCharacter& character, const BodyVolumes& volumes, std::vector<CapsuleInstance>& out) {
  if (character.flagged.empty()) return;
  std::vector<PlacedCapsule> placed;
  if (!place_capsules(character, volumes, placed)) return;
  for (int k : character.flagged) {
    if (k < 0 || static_cast<size_t>(k) >= placed.size()) continue;  // flagged for another skeleton's volumes
    const PlacedCapsule& c = placed[static_cast<size_t>(k)];
    out.push_back({glm::vec4(c.a, c.radius + kFlaggedMargin), glm::vec4(c.b, 0.0f), palette::kClearance});
  }
}

void append_object_primitives(const SceneObject& object, ScenePrimitives& out) {
  const glm::vec3 o = object.position;
  const float h = object.heading;
  const float glow = object.is_source ? 1.0f : 0.0f;
  const glm::vec4 main_colour(palette::kObstacle, glow);
  const glm::vec4 frame_colour(palette::kObstacle * 0.72f, glow);  // posts and legs: same hue, darker
  prep::ObjectType type = prep::ObjectType::Ball;
  switch (object.type) {
    case ObjectType::Ball: type = prep::ObjectType::Ball; break;
    case ObjectType::Bar: type = prep::ObjectType::Bar; break;
    case ObjectType::Beam: type = prep::ObjectType::Beam; break;
    case ObjectType::Hurdle: type = prep::ObjectType::Hurdle; break;
    case ObjectType::Box:  // not a scenario object: no solids of the engine's, the box is its size
      out.boxes.push_back({box_model(o, h, {0, 0.5f * object.size.y, 0}, object.size), main_colour});
      return;
  }
  for (const ObjectSolid& s : object_solids(type, object.size)) {
    if (s.sphere) {
      const glm::vec3 c(box_model(o, h, s.centre, glm::vec3(1.0f)) * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
      (object.light ? out.light_capsules : out.capsules).push_back({glm::vec4(c, 0.5f * s.extents.x), glm::vec4(c, glow), palette::kBall});
      continue;
    }
    const bool rail = s.part == SolidPart::Rail || s.part == SolidPart::Board;  // what is crossed: the bright part
    out.boxes.push_back({box_model(o, h, s.centre, s.extents), rail ? main_colour : frame_colour});
  }
}

ScenePrimitives build_primitives(const Scene& scene, const std::vector<bool>& skinned) {
  BodyVolumesCache volumes;
  return build_primitives(scene, skinned, volumes);
}

ScenePrimitives build_primitives(const Scene& scene, const std::vector<bool>& skinned, BodyVolumesCache& volumes) {
  ScenePrimitives prims;
  for (size_t i = 0; i < scene.characters.size(); ++i) {
    const SceneCharacter& c = scene.characters[i];
    if (!c.skeleton) continue;
    const BodyVolumes& v = volumes.get(c.skeleton);
    if (c.light) append_character_capsules(c, v, prims.light_capsules);
    else if (i >= skinned.size() || !skinned[i]) append_character_capsules(c, v, prims.capsules);
    append_flagged_capsules(c, v, prims.flagged);
  }
  for (const SceneObject& o : scene.objects) append_object_primitives(o, prims);
  for (size_t i = 0; i < scene.goal.size(); ++i) {
    const glm::vec3 g(scene.goal[i].x, 0.0f, scene.goal[i].z);
    if (i == 0) {
      prims.markers.push_back({glm::vec4(g, scene.goal_radius), glm::vec4(palette::kGoal, 0.78f * scene.goal_radius)});
      prims.markers.push_back({glm::vec4(g, 0.07f), glm::vec4(palette::kGoal, 0.0f)});
      // A pole with a ball on top, visible from afar and above obstacles.
      prims.capsules.push_back({glm::vec4(g, 0.02f), glm::vec4(g + glm::vec3(0, 1.3f, 0), 0.0f), palette::kGoal});
      prims.capsules.push_back({glm::vec4(g + glm::vec3(0, 1.3f, 0), 0.07f), glm::vec4(g + glm::vec3(0, 1.3f, 0), 0.0f), palette::kGoal});
    } else {
      prims.markers.push_back({glm::vec4(g, 0.15f), glm::vec4(palette::kGoal, 0.10f)});
    }
  }
  if (scene.source) {
    const glm::vec3 s(scene.source->x, 0.0f, scene.source->z);
    prims.markers.push_back({glm::vec4(s, scene.source_radius), glm::vec4(palette::kSource, 0.82f * scene.source_radius)});
  }
  return prims;
}

namespace {

struct FloorRect {
  glm::vec2 lo{1e30f}, hi{-1e30f};
  bool empty() const { return lo.x > hi.x; }
  void add(glm::vec2 p, float grow) {
    lo = glm::min(lo, p - glm::vec2(grow));
    hi = glm::max(hi, p + glm::vec2(grow));
  }
  float area() const { return empty() ? 0.0f : (hi.x - lo.x) * (hi.y - lo.y); }
};

FloorRect merged(const FloorRect& a, const FloorRect& b) {
  FloorRect m;
  m.lo = glm::min(a.lo, b.lo);
  m.hi = glm::max(a.hi, b.hi);
  return m;
}

}  // namespace

std::vector<glm::vec4> shadow_receiver_rects(const Scene& scene, const ScenePrimitives& prims, const glm::vec3& light_dir,
                                             int max_rects, glm::vec2 focus, float reach) {
  const glm::vec3 l = glm::normalize(light_dir);
  const float up = std::max(l.y, 0.05f);
  // Slack for the shadow lookup's normal offset and filtering (a texel or two of the map).
  const float slack = 0.05f;
  std::vector<FloorRect> rects;
  auto caster = [&](FloorRect& r, const glm::vec3& p, float radius) {
    const float y = std::max(p.y, 0.0f);
    const glm::vec3 shadow = p - l * (y / up);  // where the point's shadow meets the floor
    const float grow = radius / up + slack;     // a sphere's shadow on the floor is stretched by 1 / l.y
    r.add({p.x, p.z}, grow);
    r.add({shadow.x, shadow.z}, grow);
  };
  for (const CapsuleInstance& c : prims.capsules) {
    FloorRect r;
    caster(r, glm::vec3(c.a_radius), c.a_radius.w);
    caster(r, glm::vec3(c.b_glow), c.a_radius.w);
    rects.push_back(r);
  }
  for (const BoxInstance& b : prims.boxes) {
    FloorRect r;
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec4 local((corner & 1) ? 0.5f : -0.5f, (corner & 2) ? 0.5f : -0.5f, (corner & 4) ? 0.5f : -0.5f, 1.0f);
      caster(r, glm::vec3(b.model * local), 0.0f);
    }
    rects.push_back(r);
  }
  for (const SceneCharacter& c : scene.characters) {  // skinned bodies have no capsules: their joints, with flesh
    FloorRect r;
    for (const glm::vec3& p : c.joint_positions) caster(r, p, 0.18f);
    if (!r.empty()) rects.push_back(r);
  }
  if (std::isfinite(reach)) {
    const auto beyond = [&](const FloorRect& r) {
      const glm::vec2 nearest = glm::clamp(focus, r.lo, r.hi);
      return glm::length(nearest - focus) > reach;
    };
    rects.erase(std::remove_if(rects.begin(), rects.end(), beyond), rects.end());
  }
  // Merge down to max_rects: each time the pair whose union adds the least area.
  while (static_cast<int>(rects.size()) > std::max(max_rects, 1)) {
    size_t best_i = 0, best_j = 1;
    float best = 1e30f;
    for (size_t i = 0; i < rects.size(); ++i)
      for (size_t j = i + 1; j < rects.size(); ++j) {
        const float added = merged(rects[i], rects[j]).area() - rects[i].area() - rects[j].area();
        if (added < best) best = added, best_i = i, best_j = j;
      }
    rects[best_i] = merged(rects[best_i], rects[best_j]);
    rects.erase(rects.begin() + static_cast<std::ptrdiff_t>(best_j));
  }
  std::vector<glm::vec4> out;
  for (const FloorRect& r : rects) out.emplace_back(r.lo.x, r.lo.y, r.hi.x, r.hi.y);
  return out;
}

Renderer::Renderer(const RenderSettings& settings) : settings_(settings) {
  if (!gl::loaded()) throw std::logic_error("Renderer: no current GL context (gl::load not done)");
  settings_.light_dir = glm::normalize(settings_.light_dir);
  capsule_program_ = build_program("capsule.vert", "lit.frag");
  box_program_ = build_program("box.vert", "lit.frag");
  capsule_depth_program_ = build_program("capsule.vert", "depth.frag");
  box_depth_program_ = build_program("box.vert", "depth.frag");
  ground_program_ = build_program("ground.vert", "ground.frag");
  ground_unshadowed_program_ = build_program("ground.vert", "ground_unshadowed.frag");
  marker_program_ = build_program("marker.vert", "marker.frag");
  skinned_program_ = build_program("skinned.vert", "lit.frag");
  skinned_depth_program_ = build_program("skinned.vert", "depth.frag");
  // The skinning matrices of the character being drawn: one uniform block at binding point 0.
  for (GLuint program : {skinned_program_, skinned_depth_program_})
    glUniformBlockBinding(program, glGetUniformBlockIndex(program, "Skin"), 0);
  glGenBuffers(1, &skin_block_);
  glBindBuffer(GL_UNIFORM_BUFFER, skin_block_);
  glBufferData(GL_UNIFORM_BUFFER, kMaxSkinJoints * sizeof(glm::mat4), nullptr, GL_STREAM_DRAW);
  glBindBuffer(GL_UNIFORM_BUFFER, 0);

  // Capsules: per-vertex offset + end flag, per-instance a/radius, b/glow, colour.
  {
    // A capsule mesh of `slices` x `half_rings` into its own vertex array; returns its index count.
    auto upload_capsule_mesh = [](int slices, int half_rings, GLuint& vao, GLuint& vbo, GLuint& ibo) {
      std::vector<float> v;
      std::vector<unsigned> idx;
      capsule_mesh(slices, half_rings, v, idx);
      glGenVertexArrays(1, &vao);
      glBindVertexArray(vao);
      glGenBuffers(1, &vbo);
      glBindBuffer(GL_ARRAY_BUFFER, vbo);
      glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(float)), v.data(), GL_STATIC_DRAW);
      bind_float_attribute(0, 3, 4 * sizeof(float), 0, false);
      bind_float_attribute(1, 1, 4 * sizeof(float), 3 * sizeof(float), false);
      glGenBuffers(1, &ibo);
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
      glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(idx.size() * sizeof(unsigned)), idx.data(), GL_STATIC_DRAW);
      return static_cast<int>(idx.size());
    };
    auto bind_instances = [](GLuint& buffer) {
      glGenBuffers(1, &buffer);
      glBindBuffer(GL_ARRAY_BUFFER, buffer);
      bind_float_attribute(2, 4, sizeof(CapsuleInstance), offsetof(CapsuleInstance, a_radius), true);
      bind_float_attribute(3, 4, sizeof(CapsuleInstance), offsetof(CapsuleInstance, b_glow), true);
      bind_float_attribute(4, 3, sizeof(CapsuleInstance), offsetof(CapsuleInstance, colour), true);
    };
    capsule_index_count_ = upload_capsule_mesh(20, 7, capsule_vao_, capsule_vbo_, capsule_ibo_);
    bind_instances(capsule_instances_);
    // The flagged capsules: the same mesh with instances of their own (GL 3.3 cannot start an instanced
    // draw part-way into a buffer), so they are drawn in a later pass than the bodies' capsules.
    glGenVertexArrays(1, &flagged_vao_);
    glBindVertexArray(flagged_vao_);
    glBindBuffer(GL_ARRAY_BUFFER, capsule_vbo_);
    bind_float_attribute(0, 3, 4 * sizeof(float), 0, false);
    bind_float_attribute(1, 1, 4 * sizeof(float), 3 * sizeof(float), false);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, capsule_ibo_);
    bind_instances(flagged_instances_);
    // Light bodies: a capsule of 6 slices and one ring per end (24 triangles against 560).
    light_index_count_ = upload_capsule_mesh(6, 1, light_vao_, light_vbo_, light_ibo_);
    bind_instances(light_instances_);
    // Light bodies far away: 4 slices (16 triangles).
    distant_index_count_ = upload_capsule_mesh(4, 1, distant_vao_, distant_vbo_, distant_ibo_);
    bind_instances(distant_instances_);
  }
  // Boxes: per-vertex position + normal, per-instance model matrix (4 columns) and colour/glow.
  {
    std::vector<float> v;
    std::vector<unsigned> idx;
    cube_mesh(v, idx);
    box_index_count_ = static_cast<int>(idx.size());
    glGenVertexArrays(1, &box_vao_);
    glBindVertexArray(box_vao_);
    glGenBuffers(1, &box_vbo_);
    glBindBuffer(GL_ARRAY_BUFFER, box_vbo_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(float)), v.data(), GL_STATIC_DRAW);
    bind_float_attribute(0, 3, 6 * sizeof(float), 0, false);
    bind_float_attribute(1, 3, 6 * sizeof(float), 3 * sizeof(float), false);
    glGenBuffers(1, &box_ibo_);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, box_ibo_);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(idx.size() * sizeof(unsigned)), idx.data(), GL_STATIC_DRAW);
    glGenBuffers(1, &box_instances_);
    glBindBuffer(GL_ARRAY_BUFFER, box_instances_);
    for (int column = 0; column < 4; ++column)
      bind_float_attribute(2 + column, 4, sizeof(BoxInstance), offsetof(BoxInstance, model) + column * sizeof(glm::vec4), true);
    bind_float_attribute(6, 4, sizeof(BoxInstance), offsetof(BoxInstance, colour_glow), true);
  }
  // Ground: two triangles 400 m wide (fog hides the edge).
  {
    const float s = 200.0f;
    const float quad[] = {-s, 0, -s, s, 0, -s, s, 0, s, -s, 0, -s, s, 0, s, -s, 0, s};
    glGenVertexArrays(1, &ground_vao_);
    glBindVertexArray(ground_vao_);
    glGenBuffers(1, &ground_vbo_);
    glBindBuffer(GL_ARRAY_BUFFER, ground_vbo_);
    glBufferData(GL_ARRAY_BUFFER, sizeof(quad), quad, GL_STATIC_DRAW);
    bind_float_attribute(0, 3, 3 * sizeof(float), 0, false);
    // The floor where shadows can fall: quads rebuilt each frame (shadow_receiver_rects).
    glGenVertexArrays(1, &receiver_vao_);
    glBindVertexArray(receiver_vao_);
    glGenBuffers(1, &receiver_vbo_);
    glBindBuffer(GL_ARRAY_BUFFER, receiver_vbo_);
    bind_float_attribute(0, 3, 3 * sizeof(float), 0, false);
  }
  // Markers: a [-1, 1]^2 square per instance.
  {
    const float corners[] = {-1, -1, 1, -1, 1, 1, -1, -1, 1, 1, -1, 1};
    glGenVertexArrays(1, &marker_vao_);
    glBindVertexArray(marker_vao_);
    glGenBuffers(1, &marker_vbo_);
    glBindBuffer(GL_ARRAY_BUFFER, marker_vbo_);
    glBufferData(GL_ARRAY_BUFFER, sizeof(corners), corners, GL_STATIC_DRAW);
    bind_float_attribute(0, 2, 2 * sizeof(float), 0, false);
    glGenBuffers(1, &marker_instances_);
    glBindBuffer(GL_ARRAY_BUFFER, marker_instances_);
    bind_float_attribute(1, 4, sizeof(MarkerInstance), offsetof(MarkerInstance, centre_outer), true);
    bind_float_attribute(2, 4, sizeof(MarkerInstance), offsetof(MarkerInstance, colour_inner), true);
  }
  glBindVertexArray(0);

  if (settings_.shadow_map_size > 0) {
    glGenTextures(1, &shadow_texture_);
    glBindTexture(GL_TEXTURE_2D, shadow_texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, settings_.shadow_map_size, settings_.shadow_map_size, 0,
                 GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glGenFramebuffers(1, &shadow_fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadow_texture_, 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) throw std::runtime_error("Renderer: the shadow map framebuffer is incomplete");
  }
}

Renderer::~Renderer() {
  bodies_.clear();  // their GL objects go while the context is current
  const GLuint programs[] = {capsule_program_,       box_program_,       ground_program_,  ground_unshadowed_program_,
                             marker_program_,        capsule_depth_program_, box_depth_program_, skinned_program_,
                             skinned_depth_program_};
  for (GLuint p : programs) glDeleteProgram(p);
  const GLuint buffers[] = {capsule_vbo_, capsule_ibo_, capsule_instances_, flagged_instances_, box_vbo_, box_ibo_, box_instances_,
                            ground_vbo_, receiver_vbo_, marker_vbo_, marker_instances_, skin_block_,
                            light_vbo_, light_ibo_, light_instances_, distant_vbo_, distant_ibo_, distant_instances_};
  glDeleteBuffers(static_cast<GLsizei>(std::size(buffers)), buffers);
  const GLuint arrays[] = {capsule_vao_, flagged_vao_, box_vao_, ground_vao_, receiver_vao_, marker_vao_, light_vao_, distant_vao_};
  glDeleteVertexArrays(static_cast<GLsizei>(std::size(arrays)), arrays);
  if (shadow_fbo_) glDeleteFramebuffers(1, &shadow_fbo_);
  if (shadow_texture_) glDeleteTextures(1, &shadow_texture_);
}

const SkinnedBody* Renderer::body_for(const std::shared_ptr<const Skeleton>& skeleton) {
  if (!skeleton) return nullptr;
  for (const BodyEntry& e : bodies_)
    if (e.skeleton == skeleton) return e.body.get();
  BodyEntry entry;
  entry.skeleton = skeleton;
  if (auto mesh = body_for_skeleton(*skeleton, settings_.character_path)) entry.body = std::make_unique<SkinnedBody>(std::move(mesh));
  bodies_.push_back(std::move(entry));
  return bodies_.back().body.get();
}

void Renderer::set_body(std::shared_ptr<const Skeleton> skeleton, std::shared_ptr<const SkinnedMesh> mesh) {
  if (!skeleton || !mesh) throw std::invalid_argument("Renderer::set_body: no skeleton or no mesh");
  mesh->validate(*skeleton);
  if (skeleton->size() > kMaxSkinJoints) throw std::invalid_argument("Renderer::set_body: more joints than a skinned body may have");
  for (BodyEntry& e : bodies_)
    if (e.skeleton == skeleton) {
      e.body = std::make_unique<SkinnedBody>(std::move(mesh));
      return;
    }
  bodies_.push_back({std::move(skeleton), std::make_unique<SkinnedBody>(std::move(mesh))});
}

void Renderer::prepare(const Scene& scene) {
  std::vector<bool> skinned(scene.characters.size(), false);
  size_t draws = 0;
  if (settings_.skinned_bodies) {
    for (size_t i = 0; i < scene.characters.size(); ++i) {
      const SceneCharacter& c = scene.characters[i];
      if (c.light) continue;
      const SkinnedBody* body = body_for(c.skeleton);
      if (!body || c.joint_positions.size() != static_cast<size_t>(c.skeleton->size())) continue;
      skinned[i] = true;
      if (skinned_draws_.size() <= draws) skinned_draws_.emplace_back();
      SkinnedDraw& d = skinned_draws_[draws++];
      d.body = body;
      skinning_matrices(body->mesh(), c.joint_positions, c.joint_rotations, d.skinning);
      d.colour = c.colour;
      d.glow = c.is_source ? 1.0f : 0.0f;
    }
  }
  skinned_draws_.resize(draws);
  primitives_ = build_primitives(scene, skinned, volumes_);
  focus_ = scene.focus;
  upload(flagged_instances_, primitives_.flagged);
  upload(marker_instances_, primitives_.markers);
  // The shadow camera: orthographic, looking down the light direction at the focus.
  const glm::vec3 centre(focus_.x, 0.0f, focus_.z);
  const glm::vec3 up = std::fabs(settings_.light_dir.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  const glm::mat4 view = glm::lookAt(centre + settings_.light_dir * 30.0f, centre, up);
  const float e = settings_.shadow_extent;
  light_view_proj_ = glm::ortho(-e, e, -e, e, 1.0f, 60.0f) * view;
  // The shadow map's square seen on the floor: its half-diagonal, stretched by the light's slant.
  const float reach = 1.5f * e / std::max(settings_.light_dir.y, 0.05f);
  shadow_rects_ = shadow_receiver_rects(scene, primitives_, settings_.light_dir, kMaxShadowRects, {centre.x, centre.z}, reach);
}

void Renderer::upload_visible(const glm::mat4& view_proj, const glm::vec3* eye) {
  distant_.clear();
  if (!settings_.cull) {
    visible_.capsules = primitives_.capsules;
    visible_.light_capsules = primitives_.light_capsules;
    visible_.boxes = primitives_.boxes;
  } else {
    const ClipVolume volume = eye ? ClipVolume(view_proj, *eye, settings_.fog_end) : ClipVolume(view_proj);
    keep_visible(primitives_.capsules, volume, visible_.capsules);
    if (eye) {
      keep_visible(primitives_.light_capsules, volume, *eye, settings_.distant_capsules_from, visible_.light_capsules, distant_);
    } else {
      keep_visible(primitives_.light_capsules, volume, visible_.light_capsules);
    }
    keep_visible(primitives_.boxes, volume, visible_.boxes);
  }
  upload(capsule_instances_, visible_.capsules);
  upload(light_instances_, visible_.light_capsules);
  upload(distant_instances_, distant_);
  upload(box_instances_, visible_.boxes);
}

void Renderer::draw_capsule_bodies(GLuint program, const glm::mat4& view_proj) {
  if (visible_.capsules.empty() && visible_.light_capsules.empty() && distant_.empty()) return;
  glUseProgram(program);
  glUniformMatrix4fv(glGetUniformLocation(program, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
  if (!visible_.capsules.empty()) {
    glBindVertexArray(capsule_vao_);
    glDrawElementsInstanced(GL_TRIANGLES, capsule_index_count_, GL_UNSIGNED_INT, nullptr,
                            static_cast<GLsizei>(visible_.capsules.size()));
    triangles_ += capsule_index_count_ / 3 * static_cast<int>(visible_.capsules.size());
  }
  if (!visible_.light_capsules.empty()) {
    glBindVertexArray(light_vao_);
    glDrawElementsInstanced(GL_TRIANGLES, light_index_count_, GL_UNSIGNED_INT, nullptr,
                            static_cast<GLsizei>(visible_.light_capsules.size()));
    triangles_ += light_index_count_ / 3 * static_cast<int>(visible_.light_capsules.size());
  }
  if (!distant_.empty()) {
    glBindVertexArray(distant_vao_);
    glDrawElementsInstanced(GL_TRIANGLES, distant_index_count_, GL_UNSIGNED_INT, nullptr, static_cast<GLsizei>(distant_.size()));
    triangles_ += distant_index_count_ / 3 * static_cast<int>(distant_.size());
  }
}

void Renderer::draw_boxes(GLuint program, const glm::mat4& view_proj) {
  if (visible_.boxes.empty()) return;
  glUseProgram(program);
  glUniformMatrix4fv(glGetUniformLocation(program, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
  glBindVertexArray(box_vao_);
  glDrawElementsInstanced(GL_TRIANGLES, box_index_count_, GL_UNSIGNED_INT, nullptr,
                          static_cast<GLsizei>(visible_.boxes.size()));
  triangles_ += box_index_count_ / 3 * static_cast<int>(visible_.boxes.size());
}

void Renderer::draw_skinned_bodies(GLuint program, const glm::mat4& view_proj) {
  if (skinned_draws_.empty()) return;
  glUseProgram(program);
  glUniformMatrix4fv(glGetUniformLocation(program, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
  const GLint colour = glGetUniformLocation(program, "u_colour"), glow = glGetUniformLocation(program, "u_glow");
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, skin_block_);
  for (const SkinnedDraw& d : skinned_draws_) {
    glBufferSubData(GL_UNIFORM_BUFFER, 0, static_cast<GLsizeiptr>(d.skinning.size() * sizeof(glm::mat4)), d.skinning.data());
    if (colour >= 0) glUniform3fv(colour, 1, glm::value_ptr(d.colour));
    if (glow >= 0) glUniform1f(glow, d.glow);
    d.body->draw();
    triangles_ += d.body->triangle_count();
  }
}

void Renderer::draw_flagged(const glm::mat4& view_proj) {
  if (primitives_.flagged.empty()) return;
  glUseProgram(capsule_program_);
  glUniformMatrix4fv(glGetUniformLocation(capsule_program_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
  glBindVertexArray(flagged_vao_);
  glDrawElementsInstanced(GL_TRIANGLES, capsule_index_count_, GL_UNSIGNED_INT, nullptr,
                          static_cast<GLsizei>(primitives_.flagged.size()));
  triangles_ += capsule_index_count_ / 3 * static_cast<int>(primitives_.flagged.size());
}

void Renderer::shadow_pass() {
  triangles_ = 0;
  if (!shadow_fbo_) return;
  glBindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_);
  glViewport(0, 0, settings_.shadow_map_size, settings_.shadow_map_size);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);  // back faces into the map: less self-shadowing on lit sides
  upload_visible(light_view_proj_, nullptr);
  draw_capsule_bodies(capsule_depth_program_, light_view_proj_);
  draw_skinned_bodies(skinned_depth_program_, light_view_proj_);
  draw_boxes(box_depth_program_, light_view_proj_);
  glCullFace(GL_BACK);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Renderer::set_lighting_uniforms(GLuint program, const glm::vec3& eye) {
  glUseProgram(program);
  glUniform3fv(glGetUniformLocation(program, "u_light_dir"), 1, glm::value_ptr(settings_.light_dir));
  glUniformMatrix4fv(glGetUniformLocation(program, "u_light_view_proj"), 1, GL_FALSE, glm::value_ptr(light_view_proj_));
  glUniform1i(glGetUniformLocation(program, "u_shadow_map"), 0);
  glUniform1f(glGetUniformLocation(program, "u_shadow_texel"), shadow_fbo_ ? 1.0f / settings_.shadow_map_size : 0.0f);
  glUniform3fv(glGetUniformLocation(program, "u_eye"), 1, glm::value_ptr(eye));
  glUniform3fv(glGetUniformLocation(program, "u_sky"), 1, glm::value_ptr(palette::kSky));
  glUniform2f(glGetUniformLocation(program, "u_fog_range"), settings_.fog_start, settings_.fog_end);
  glUniform3fv(glGetUniformLocation(program, "u_source_colour"), 1, glm::value_ptr(palette::kSource));
}

void Renderer::main_pass(const Camera& camera, int x, int y, int width, int height) {
  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(height, 1));
  const glm::mat4 view_proj = camera.view_projection(aspect);
  const glm::vec3 eye = camera.eye();

  glViewport(x, y, width, height);
  glEnable(GL_SCISSOR_TEST);
  glScissor(x, y, width, height);
  glClearColor(palette::kSky.r, palette::kSky.g, palette::kSky.b, 1.0f);
  glClearDepth(1.0);
  glDepthMask(GL_TRUE);
  const bool flagged = !primitives_.flagged.empty();
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | (flagged ? GL_STENCIL_BUFFER_BIT : 0));
  if (!covered_.empty()) {
    // Depth 0 under the panels: every fragment there fails the depth test before it is shaded.
    glClearDepth(0.0);
    for (const glm::vec4& r : covered_) {
      const int rx = std::max(0, static_cast<int>(std::ceil(r.x))), ry = std::max(0, static_cast<int>(std::ceil(r.y)));
      const int rw = std::min(width - rx, static_cast<int>(std::floor(r.x + r.z)) - rx);
      const int rh = std::min(height - ry, static_cast<int>(std::floor(r.y + r.w)) - ry);
      if (rw <= 0 || rh <= 0) continue;
      glScissor(x + rx, y + height - ry - rh, rw, rh);  // GL's origin is the bottom-left
      glClear(GL_DEPTH_BUFFER_BIT);
    }
    glClearDepth(1.0);
  }
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, shadow_texture_);

  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  upload_visible(view_proj, &eye);
  set_lighting_uniforms(capsule_program_, eye);
  draw_capsule_bodies(capsule_program_, view_proj);
  // The flagged capsules before the skinned bodies, marking the stencil where they show, and no skin is
  // drawn there: the skin wraps the bones more loosely than the capsules (a flagged capsule a few
  // millimetres thicker would still be inside it), yet the capsule is what went in. Obstacles and the
  // floor still hide them by depth, so what shows is the part that sticks out of what it is in. Without a
  // stencil buffer (an FBO of depth alone) they are only depth-tested, hidden where the skin is.
  if (flagged) {
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    draw_flagged(view_proj);  // the capsule program's lighting is set above
    glStencilFunc(GL_NOTEQUAL, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  }
  set_lighting_uniforms(skinned_program_, eye);
  draw_skinned_bodies(skinned_program_, view_proj);
  glDisable(GL_STENCIL_TEST);
  set_lighting_uniforms(box_program_, eye);
  draw_boxes(box_program_, view_proj);

  glDisable(GL_CULL_FACE);
  set_lighting_uniforms(ground_program_, eye);
  glUniformMatrix4fv(glGetUniformLocation(ground_program_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
  glUniform3fv(glGetUniformLocation(ground_program_, "u_ground"), 1, glm::value_ptr(palette::kGround));
  glUniform3fv(glGetUniformLocation(ground_program_, "u_grid_line"), 1, glm::value_ptr(palette::kGridLine));
  // The floor in two parts (ground.glsl): first where shadows can fall, with the shadow lookup, pulled
  // slightly toward the camera; then the whole floor without it, which the depth test keeps out of the
  // first part before its fragments are shaded.
  if (shadow_fbo_ && !shadow_rects_.empty()) {
    std::vector<float> quads;
    quads.reserve(shadow_rects_.size() * 18);
    for (const glm::vec4& r : shadow_rects_)
      quads.insert(quads.end(), {r.x, 0, r.y, r.z, 0, r.y, r.z, 0, r.w, r.x, 0, r.y, r.z, 0, r.w, r.x, 0, r.w});
    glBindBuffer(GL_ARRAY_BUFFER, receiver_vbo_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(quads.size() * sizeof(float)), quads.data(), GL_STREAM_DRAW);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(-1.0f, -2.0f);
    glBindVertexArray(receiver_vao_);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(quads.size() / 3));
    glDisable(GL_POLYGON_OFFSET_FILL);
    triangles_ += static_cast<int>(quads.size() / 9);
  }
  set_lighting_uniforms(ground_unshadowed_program_, eye);
  glUniformMatrix4fv(glGetUniformLocation(ground_unshadowed_program_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
  glUniform3fv(glGetUniformLocation(ground_unshadowed_program_, "u_ground"), 1, glm::value_ptr(palette::kGround));
  glUniform3fv(glGetUniformLocation(ground_unshadowed_program_, "u_grid_line"), 1, glm::value_ptr(palette::kGridLine));
  glBindVertexArray(ground_vao_);
  glDrawArrays(GL_TRIANGLES, 0, 6);
  triangles_ += 2;

  if (!primitives_.markers.empty()) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(-1.0f, -4.0f);
    set_lighting_uniforms(marker_program_, eye);
    glUniformMatrix4fv(glGetUniformLocation(marker_program_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
    glBindVertexArray(marker_vao_);
    glDrawArraysInstanced(GL_TRIANGLES, 0, 6, static_cast<GLsizei>(primitives_.markers.size()));
    triangles_ += 2 * static_cast<int>(primitives_.markers.size());
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace prep::render
