// glTF import: the engine's skeletons, clips and skinned meshes built from a checked glTF document
// (gltf_document.h).
#include "engine/interop/gltf_io.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <set>

#include "engine/interop/gltf_document.h"
#include "engine/motion/pose.h"
#include "engine/util/error.h"
#include "engine/util/files.h"

namespace prep {
namespace gltf_document {

// ------------------------------------------------------------------------------------------------
// Building the engine types
// ------------------------------------------------------------------------------------------------

glm::vec3 to_vec3(const glm::dvec3& v) { return glm::vec3(static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)); }
glm::quat to_quat(const glm::dquat& q) {
  const glm::quat f = glm::normalize(glm::quat(static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z)));
  return without_negligible_components(glm::dquat(f));
}

struct RigRest {
  std::vector<glm::dvec3> position;  // world rest position per joint
  std::vector<glm::dquat> rotation;  // world rest rotation per joint (G_j(rest))
  std::vector<glm::dmat4> world;     // world rest matrix per joint
};

RigRest rig_rest(const Rig& rig, const NodeGraph& graph, const Reader& rd) {
  std::vector<glm::dmat4> world;
  graph.world(graph.rest, world);
  RigRest rest;
  for (int node : rig.joint_nodes) {
    const glm::dmat4& m = world[static_cast<size_t>(node)];
    bool ok = false;
    rest.rotation.push_back(rotation_of(m, &ok));
    if (!ok) rd.fail("nodes[" + num(node) + "]: its world transform is singular (zero scale)");
    rest.position.push_back(glm::dvec3(m[3]));
    rest.world.push_back(m);
  }
  (void)rd;
  return rest;
}

std::shared_ptr<Skeleton> build_skeleton(const tinygltf::Model& model, const Rig& rig, const RigRest& rest,
                                         const NodeGraph& graph, const Reader& rd) {
  auto skeleton = std::make_shared<Skeleton>();
  std::set<std::string> names;
  std::vector<glm::dmat4> world;
  graph.world(graph.rest, world);
  for (size_t j = 0; j < rig.joint_nodes.size(); ++j) {
    Joint joint;
    joint.name = node_name(model, rig.joint_nodes[j]);
    if (!names.insert(joint.name).second) {
      joint.name += "_" + num(rig.joint_nodes[j]);
      names.insert(joint.name);
    }
    joint.parent = rig.joint_parent[j];
    joint.offset = to_vec3(joint.parent < 0 ? rest.position[j] : rest.position[j] - rest.position[static_cast<size_t>(joint.parent)]);
    if (rig.end_node[j] >= 0) {
      joint.has_end_site = true;
      joint.end_site = to_vec3(glm::dvec3(world[static_cast<size_t>(rig.end_node[j])][3]) - rest.position[j]);
    }
    skeleton->joints.push_back(joint);
  }
  try {
    skeleton->validate();
  } catch (const std::invalid_argument& e) {
    rd.fail(std::string("skeleton: ") + e.what());
  }
  return skeleton;
}

Clip build_clip(const tinygltf::Model& model, size_t anim_index, const std::vector<Channel>& all_channels,
                const Rig& rig, const RigRest& rest, const NodeGraph& graph, std::shared_ptr<const Skeleton> skeleton,
                const GltfReadOptions& options, const Reader& rd) {
  // Nodes whose transforms reach the joints: the joints and every ancestor.
  std::set<int> relevant;
  for (int node : rig.joint_nodes)
    for (int p = node; p != -1; p = graph.parent[static_cast<size_t>(p)]) relevant.insert(p);
  std::vector<const Channel*> channels;
  bool moves_joint = false;
  for (const Channel& c : all_channels) {
    if (!relevant.count(c.node)) continue;
    channels.push_back(&c);
    if (rig.node_to_joint.count(c.node)) moves_joint = true;
  }
  Clip clip;
  if (!moves_joint) return clip;
  const tinygltf::Animation& anim = model.animations[anim_index];
  clip.name = anim.name.empty() ? "animation" + num(anim_index) : anim.name;
  clip.skeleton = skeleton;
  double t0 = std::numeric_limits<double>::max(), t1 = std::numeric_limits<double>::lowest();
  for (const Channel* c : channels) {
    t0 = std::min(t0, c->times.front());
    t1 = std::max(t1, c->times.back());
  }
  double fps = options.fps;
  if (!(fps > 0.0)) {
    fps = 30.0;
    // The key spacing of the channel with the most keys, if it is regular.
    const Channel* densest = channels.front();
    for (const Channel* c : channels)
      if (c->times.size() > densest->times.size()) densest = c;
    const size_t n = densest->times.size();
    if (n >= 2) {
      const double dt = (densest->times.back() - densest->times.front()) / static_cast<double>(n - 1);
      bool regular = dt > 0.0;
      for (size_t k = 1; k < n && regular; ++k)
        regular = std::fabs(densest->times[k] - densest->times[k - 1] - dt) <= 1e-3 * dt + 1e-6;
      // Keys at least a second apart are not a frame rate: those are resampled at the default.
      if (regular && dt <= 1.0) {
        fps = 1.0 / dt;
        if (std::fabs(fps - std::round(fps)) < 1e-2) fps = std::round(fps);
      }
    }
  }
  const double span = (t1 - t0) * fps;
  if (!(span <= 1e6)) rd.fail("animations[" + num(anim_index) + "]: " + std::to_string(t1 - t0) + " s is too long to resample");
  const size_t frames = static_cast<size_t>(std::llround(span)) + 1;
  clip.fps = static_cast<float>(fps);
  clip.frames.reserve(frames);
  std::vector<Trs> local = graph.rest;
  std::vector<glm::dmat4> world;
  const size_t nj = rig.joint_nodes.size();
  std::vector<glm::dquat> ours(nj);
  for (size_t f = 0; f < frames; ++f) {
    const double t = std::min(t0 + static_cast<double>(f) / fps, t1);
    for (const Channel* c : channels) {
      const glm::dvec4 v = c->sample(t);
      Trs& trs = local[static_cast<size_t>(c->node)];
      if (c->path == Channel::kTranslation) trs.t = glm::dvec3(v);
      else if (c->path == Channel::kScale) trs.s = glm::dvec3(v);
      else trs.r = glm::dquat(v.w, v.x, v.y, v.z);
    }
    graph.world(local, world);
    Pose pose(static_cast<int>(nj));
    for (size_t j = 0; j < nj; ++j) {
      bool ok = false;
      const glm::dquat g = rotation_of(world[static_cast<size_t>(rig.joint_nodes[j])], &ok);
      if (!ok) rd.fail("animations[" + num(anim_index) + "]: a scale of 0 makes joint " + skeleton->joints[j].name + " singular");
      ours[j] = glm::normalize(g * glm::conjugate(rest.rotation[j]));
      const int p = rig.joint_parent[j];
      pose.rotations[j] = to_quat(p < 0 ? ours[j] : glm::conjugate(ours[static_cast<size_t>(p)]) * ours[j]);
    }
    pose.root_position = to_vec3(glm::dvec3(world[static_cast<size_t>(rig.joint_nodes[0])][3]));
    clip.frames.push_back(std::move(pose));
  }
  make_hemisphere_continuous(clip);
  return clip;
}

void compute_normals(SkinnedMesh& mesh, size_t first_vertex, size_t first_index) {
  for (size_t v = first_vertex; v < mesh.positions.size(); ++v) mesh.normals[v] = glm::vec3(0.0f);
  for (size_t i = first_index; i + 2 < mesh.indices.size(); i += 3) {
    const glm::vec3 a = mesh.positions[mesh.indices[i]], b = mesh.positions[mesh.indices[i + 1]],
                    c = mesh.positions[mesh.indices[i + 2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    for (int k = 0; k < 3; ++k) mesh.normals[mesh.indices[i + static_cast<size_t>(k)]] += n;
  }
  for (size_t v = first_vertex; v < mesh.positions.size(); ++v) {
    const float len = glm::length(mesh.normals[v]);
    mesh.normals[v] = len > 0.0f ? mesh.normals[v] / len : glm::vec3(0.0f, 1.0f, 0.0f);
  }
}

SkinnedMesh build_mesh(const tinygltf::Model& model, const Rig& rig, const RigRest& rest, const Reader& rd) {
  SkinnedMesh mesh;
  const tinygltf::Skin& skin = model.skins[static_cast<size_t>(rig.skin)];
  const std::string sw = "skins[" + num(rig.skin) + "]";
  const size_t slots = skin.joints.size();
  // Inverse bind matrices per skin slot.
  std::vector<glm::dmat4> ibm(slots, glm::dmat4(1.0));
  if (skin.inverseBindMatrices >= 0) {
    const AccessorView v = rd.accessor(skin.inverseBindMatrices, sw + ".inverseBindMatrices", {TINYGLTF_TYPE_MAT4},
                                       {TINYGLTF_COMPONENT_TYPE_FLOAT});
    if (v.count < slots)
      rd.fail(sw + ".inverseBindMatrices: " + num(v.count) + " matrices for " + num(slots) + " joints");
    for (size_t s = 0; s < slots; ++s)
      for (int e = 0; e < 16; ++e) {
        const double x = v.get(s, e);
        if (!std::isfinite(x))
          rd.fail(sw + ".inverseBindMatrices: matrix " + num(s) + " element " + num(e) + " is not finite (NaN or infinity)");
        ibm[s][e / 4][e % 4] = x;
      }
  }
  // Skin slot -> our joint. End Site nodes in the skin follow their parent joint.
  std::vector<int> slot_joint(slots);
  for (size_t s = 0; s < slots; ++s) slot_joint[s] = rig.node_to_joint.at(skin.joints[s]);
  // Our inverse bind for joint j: M_rest(j)^-1 * G_rest(j) * IBM(slot of j); M_rest(j) = translate(p_rest(j))
  // because our rest rotations are the identity. See the header for why.
  mesh.inverse_bind.assign(rig.joint_nodes.size(), glm::mat4(1.0f));
  for (size_t s = 0; s < slots; ++s) {
    auto it = std::find(rig.joint_nodes.begin(), rig.joint_nodes.end(), skin.joints[s]);
    if (it == rig.joint_nodes.end()) continue;
    const size_t j = static_cast<size_t>(it - rig.joint_nodes.begin());
    const glm::dmat4 m = glm::translate(glm::dmat4(1.0), -rest.position[j]) * rest.world[j] * ibm[s];
    mesh.inverse_bind[j] = glm::mat4(m);
  }
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const tinygltf::Node& node = model.nodes[n];
    if (node.skin != rig.skin || node.mesh < 0) continue;
    if (static_cast<size_t>(node.mesh) >= model.meshes.size())
      rd.fail("nodes[" + num(n) + "].mesh " + num(node.mesh) + " does not exist");
    const tinygltf::Mesh& m = model.meshes[static_cast<size_t>(node.mesh)];
    for (size_t p = 0; p < m.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = m.primitives[p];
      const std::string pw = "meshes[" + num(node.mesh) + "].primitives[" + num(p) + "]";
      if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) continue;  // points and lines: nothing to draw
      auto attribute = [&](const char* name) {
        auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
      };
      if (attribute("POSITION") < 0) rd.fail(pw + ": no POSITION attribute");
      if (attribute("JOINTS_0") < 0 || attribute("WEIGHTS_0") < 0)
        rd.fail(pw + ": a skinned mesh needs JOINTS_0 and WEIGHTS_0");
      const std::vector<glm::dvec3> pos = rd.vec3s(attribute("POSITION"), pw + ".attributes.POSITION");
      const size_t nv = pos.size();
      const size_t base = mesh.positions.size();
      if (nv > std::numeric_limits<uint32_t>::max() - base) rd.fail(pw + ": too many vertices");
      std::vector<glm::dvec3> nrm;
      if (attribute("NORMAL") >= 0) {
        nrm = rd.vec3s(attribute("NORMAL"), pw + ".attributes.NORMAL");
        if (nrm.size() != nv) rd.fail(pw + ".attributes.NORMAL: " + num(nrm.size()) + " normals for " + num(nv) + " positions");
      }
      const AccessorView jv = rd.accessor(attribute("JOINTS_0"), pw + ".attributes.JOINTS_0", {TINYGLTF_TYPE_VEC4},
                                          {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
      const AccessorView wv = rd.accessor(attribute("WEIGHTS_0"), pw + ".attributes.WEIGHTS_0", {TINYGLTF_TYPE_VEC4},
                                          {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                           TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                          true);
      if (jv.count != nv || wv.count != nv)
        rd.fail(pw + ": JOINTS_0/WEIGHTS_0 counts (" + num(jv.count) + ", " + num(wv.count) + ") differ from POSITION (" + num(nv) + ")");
      for (size_t v = 0; v < nv; ++v) {
        mesh.positions.push_back(to_vec3(pos[v]));
        mesh.normals.push_back(nrm.empty() ? glm::vec3(0.0f) : glm::normalize(to_vec3(nrm[v])));
        if (!nrm.empty() && !std::isfinite(mesh.normals.back().x)) mesh.normals.back() = glm::vec3(0.0f, 1.0f, 0.0f);
        std::vector<std::pair<int, double>> influence;  // in the file's order; slots of one joint merged
        double sum = 0.0;
        for (int k = 0; k < 4; ++k) {
          const double w = wv.get(v, k);
          if (!std::isfinite(w) || w < 0.0) rd.fail(pw + ".attributes.WEIGHTS_0: vertex " + num(v) + " has a negative or non-finite weight");
          const double slot = jv.get(v, k);
          if (slot >= static_cast<double>(slots))
            rd.fail(pw + ".attributes.JOINTS_0: vertex " + num(v) + " uses joint " + std::to_string(static_cast<long long>(slot)) +
                    " but " + sw + " has " + num(slots) + " joints");
          if (w == 0.0) continue;
          const int joint = slot_joint[static_cast<size_t>(slot)];
          auto same = std::find_if(influence.begin(), influence.end(), [&](const auto& p) { return p.first == joint; });
          if (same == influence.end()) influence.emplace_back(joint, w);
          else same->second += w;
          sum += w;
        }
        if (!(sum > 0.0)) rd.fail(pw + ".attributes.WEIGHTS_0: vertex " + num(v) + " has no weight");
        glm::ivec4 joints(0);
        glm::vec4 weights(0.0f);
        int k = 0;
        for (auto& [joint, w] : influence) {
          joints[k] = joint;
          weights[k] = static_cast<float>(w / sum);
          ++k;
        }
        mesh.joints.push_back(joints);
        mesh.weights.push_back(weights);
      }
      const size_t first_index = mesh.indices.size();
      if (prim.indices >= 0) {
        const AccessorView iv = rd.accessor(prim.indices, pw + ".indices", {TINYGLTF_TYPE_SCALAR},
                                            {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
        if (iv.count % 3 != 0) rd.fail(pw + ".indices: " + num(iv.count) + " indices is not a whole number of triangles");
        for (size_t i = 0; i < iv.count; ++i) {
          const double idx = iv.get(i, 0);
          if (idx >= static_cast<double>(nv))
            rd.fail(pw + ".indices: index " + num(i) + " = " + std::to_string(static_cast<long long>(idx)) +
                    " is out of range (" + num(nv) + " vertices)");
          mesh.indices.push_back(static_cast<uint32_t>(base + static_cast<size_t>(idx)));
        }
      } else {
        if (nv % 3 != 0) rd.fail(pw + ": " + num(nv) + " vertices without indices is not a whole number of triangles");
        for (size_t v = 0; v < nv; ++v) mesh.indices.push_back(static_cast<uint32_t>(base + v));
      }
      if (nrm.empty()) compute_normals(mesh, base, first_index);
    }
  }
  if (mesh.positions.empty()) mesh.inverse_bind.clear();
  return mesh;
}

}  // namespace gltf_document

std::vector<GltfCharacter> parse_gltf(std::string_view bytes, const std::string& source_name,
                                      const GltfReadOptions& options, const std::string& base_dir) {
  using namespace gltf_document;
  const tinygltf::Model model = load_model(bytes, source_name, base_dir);
  const Reader rd{model, source_name};
  const NodeGraph graph(model, rd);
  const std::vector<Rig> rigs = find_rigs(model, graph, rd);
  if (rigs.empty()) rd.fail("no skin and no node hierarchy: nothing that looks like a skeleton");
  std::vector<std::vector<Channel>> channels;
  for (size_t a = 0; a < model.animations.size(); ++a) channels.push_back(read_channels(model, a, rd));
  std::vector<GltfCharacter> characters;
  for (const Rig& rig : rigs) {
    GltfCharacter character;
    character.name = rig.name;
    const RigRest rest = rig_rest(rig, graph, rd);
    auto skeleton = build_skeleton(model, rig, rest, graph, rd);
    character.skeleton = skeleton;
    if (rig.skin >= 0) character.mesh = build_mesh(model, rig, rest, rd);
    for (size_t a = 0; a < model.animations.size(); ++a) {
      Clip clip = build_clip(model, a, channels[a], rig, rest, graph, skeleton, options, rd);
      if (!clip.frames.empty()) character.clips.push_back(std::move(clip));
    }
    characters.push_back(std::move(character));
  }
  return characters;
}

std::vector<GltfCharacter> read_gltf(const std::string& path, const GltfReadOptions& options) {
  const std::string bytes = read_file(path);
  const size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash);
  return parse_gltf(bytes, path, options, dir);
}

SkinnedMesh load_character_mesh(const std::string& path, const Skeleton& skeleton) {
  const std::vector<GltfCharacter> characters = read_gltf(path);
  const GltfCharacter* found = nullptr;
  for (const GltfCharacter& c : characters)
    if (!c.mesh.empty()) {
      found = &c;
      break;
    }
  if (!found) throw InputError(path, "no skinned mesh in the file");
  const Skeleton& from = *found->skeleton;
  std::vector<int> to_ours(static_cast<size_t>(from.size()), -1);
  for (int j = 0; j < from.size(); ++j) {
    const Joint& fj = from.joints[static_cast<size_t>(j)];
    const int k = skeleton.find(fj.name);
    if (k < 0) throw InputError(path, "joint \"" + fj.name + "\" of the mesh's skeleton is not in the target skeleton");
    if (j > 0 && glm::length(fj.offset - skeleton.joints[static_cast<size_t>(k)].offset) > 1e-3f)
      throw InputError(path, "joint \"" + fj.name + "\": bone offset differs from the target skeleton's (made for another skeleton?)");
    to_ours[static_cast<size_t>(j)] = k;
  }
  SkinnedMesh mesh = found->mesh;
  // Joints of the target skeleton that the file lacks follow their nearest ancestor present in the file.
  std::vector<glm::mat4> ibm(static_cast<size_t>(skeleton.size()), glm::mat4(1.0f));
  std::vector<bool> have(static_cast<size_t>(skeleton.size()), false);
  for (int j = 0; j < from.size(); ++j) {
    ibm[static_cast<size_t>(to_ours[static_cast<size_t>(j)])] = found->mesh.inverse_bind[static_cast<size_t>(j)];
    have[static_cast<size_t>(to_ours[static_cast<size_t>(j)])] = true;
  }
  for (int k = 0; k < skeleton.size(); ++k)
    if (!have[static_cast<size_t>(k)]) {
      // Rest offsets are translations only, so the bind of k is its ancestor's shifted by the bone vectors.
      glm::vec3 shift(0.0f);
      int a = k;
      while (a >= 0 && !have[static_cast<size_t>(a)]) {
        shift += skeleton.joints[static_cast<size_t>(a)].offset;
        a = skeleton.joints[static_cast<size_t>(a)].parent;
      }
      if (a < 0) throw InputError(path, "the mesh's skeleton does not contain the target's root");
      ibm[static_cast<size_t>(k)] = glm::translate(glm::mat4(1.0f), -shift) * ibm[static_cast<size_t>(a)];
    }
  for (glm::ivec4& j : mesh.joints)
    for (int i = 0; i < 4; ++i) j[i] = to_ours[static_cast<size_t>(j[i])];
  mesh.inverse_bind = ibm;
  try {
    mesh.validate(skeleton);
  } catch (const std::invalid_argument& e) {
    throw InputError(path, e.what());
  }
  return mesh;
}

}  // namespace prep
