// glTF export: skeletons, clips and skinned meshes written as .gltf or .glb through tinygltf.
#include "engine/interop/gltf_io.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "engine/interop/gltf_document.h"
#include "engine/util/files.h"

namespace prep {

namespace {

class BufferBuilder {
 public:
  explicit BufferBuilder(tinygltf::Model& model) : model_(model) {}

  int view(const void* data, size_t size, int target) {
    while (bytes_.size() % 4 != 0) bytes_.push_back(0);
    tinygltf::BufferView bv;
    bv.buffer = 0;
    bv.byteOffset = bytes_.size();
    bv.byteLength = size;
    bv.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
    model_.bufferViews.push_back(bv);
    return static_cast<int>(model_.bufferViews.size() - 1);
  }

  int accessor(int view, int component_type, int type, size_t count, std::vector<double> min = {},
               std::vector<double> max = {}) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.byteOffset = 0;
    a.componentType = component_type;
    a.type = type;
    a.count = count;
    a.normalized = false;
    a.minValues = std::move(min);
    a.maxValues = std::move(max);
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size() - 1);
  }

  void finish() {
    while (bytes_.size() % 4 != 0) bytes_.push_back(0);
    tinygltf::Buffer buffer;
    buffer.data = std::move(bytes_);
    model_.buffers.push_back(std::move(buffer));
  }

 private:
  tinygltf::Model& model_;
  std::vector<unsigned char> bytes_;
};

template <typename T>
int add_floats(BufferBuilder& b, const std::vector<T>& values, int components, int type, int target, bool minmax) {
  std::vector<float> flat;
  flat.reserve(values.size() * static_cast<size_t>(components));
  for (const T& v : values)
    for (int c = 0; c < components; ++c) flat.push_back(reinterpret_cast<const float*>(&v)[c]);
  std::vector<double> mn, mx;
  if (minmax) {
    mn.assign(static_cast<size_t>(components), std::numeric_limits<double>::max());
    mx.assign(static_cast<size_t>(components), std::numeric_limits<double>::lowest());
    for (size_t i = 0; i < flat.size(); ++i) {
      const size_t c = i % static_cast<size_t>(components);
      mn[c] = std::min(mn[c], static_cast<double>(flat[i]));
      mx[c] = std::max(mx[c], static_cast<double>(flat[i]));
    }
  }
  const int view = b.view(flat.data(), flat.size() * sizeof(float), target);
  return b.accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, type, values.size(), mn, mx);
}

std::vector<double> to_doubles(const glm::vec3& v) { return {v.x, v.y, v.z}; }

}  // namespace

std::string format_gltf(const GltfScene& scene, bool binary) {
  if (scene.characters.empty()) throw std::invalid_argument("glTF export: no character");
  const float fps = scene.characters.front().fps;
  for (const Clip& clip : scene.characters) {
    if (!clip.skeleton || clip.skeleton->size() == 0) throw std::invalid_argument("glTF export: a clip has no skeleton");
    if (clip.fps != fps) throw std::invalid_argument("glTF export: clips differ in frame rate");
    if (!(clip.fps > 0.0f)) throw std::invalid_argument("glTF export: frame rate must be positive");
    for (const Pose& pose : clip.frames)
      if (pose.rotations.size() != static_cast<size_t>(clip.skeleton->size()))
        throw std::invalid_argument("glTF export: a pose does not match its skeleton");
    if (scene.mesh) {
      if (static_cast<int>(scene.mesh->inverse_bind.size()) != clip.skeleton->size())
        throw std::invalid_argument("glTF export: the mesh is bound to another skeleton");
    }
  }
  if (scene.mesh) scene.mesh->validate(*scene.characters.front().skeleton);

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "prep (natural preparation behavior synthesis)";
  BufferBuilder buffer(model);
  tinygltf::Scene gscene;
  const bool prefix = scene.characters.size() > 1;

  // Joint nodes.
  std::vector<std::vector<int>> joint_node(scene.characters.size());
  for (size_t c = 0; c < scene.characters.size(); ++c) {
    const Clip& clip = scene.characters[c];
    const Skeleton& sk = *clip.skeleton;
    const std::string pre = prefix ? "character" + gltf_document::num(c) + ":" : "";
    glm::vec3 root_rest = sk.joints[0].offset;
    if (scene.mesh) root_rest = glm::vec3(glm::inverse(scene.mesh->inverse_bind[0])[3]);
    else if (!clip.frames.empty()) root_rest = clip.frames.front().root_position;
    for (int j = 0; j < sk.size(); ++j) {
      const Joint& joint = sk.joints[static_cast<size_t>(j)];
      tinygltf::Node node;
      node.name = pre + joint.name;
      const glm::vec3 t = j == 0 ? root_rest : joint.offset;
      node.translation = to_doubles(t);
      joint_node[c].push_back(static_cast<int>(model.nodes.size()));
      model.nodes.push_back(node);
      if (joint.parent >= 0)
        model.nodes[static_cast<size_t>(joint_node[c][static_cast<size_t>(joint.parent)])].children.push_back(joint_node[c].back());
      else
        gscene.nodes.push_back(joint_node[c].back());
    }
    for (int j = 0; j < sk.size(); ++j) {
      const Joint& joint = sk.joints[static_cast<size_t>(j)];
      if (!joint.has_end_site) continue;
      tinygltf::Node end;
      end.name = pre + joint.name + "_end";
      end.translation = to_doubles(joint.end_site);
      model.nodes.push_back(end);
      model.nodes[static_cast<size_t>(joint_node[c][static_cast<size_t>(j)])].children.push_back(static_cast<int>(model.nodes.size() - 1));
    }
  }

  // Mesh and skins.
  if (scene.mesh) {
    const SkinnedMesh& m = *scene.mesh;
    tinygltf::Material material;
    material.name = "body";
    material.pbrMetallicRoughness.baseColorFactor = {0.72, 0.62, 0.55, 1.0};
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.8;
    model.materials.push_back(material);
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = 0;
    prim.attributes["POSITION"] = add_floats(buffer, m.positions, 3, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
    prim.attributes["NORMAL"] = add_floats(buffer, m.normals, 3, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
    std::vector<uint16_t> joints;
    for (const glm::ivec4& j : m.joints)
      for (int k = 0; k < 4; ++k) joints.push_back(static_cast<uint16_t>(j[k]));
    prim.attributes["JOINTS_0"] =
        buffer.accessor(buffer.view(joints.data(), joints.size() * 2, TINYGLTF_TARGET_ARRAY_BUFFER),
                        TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, m.joints.size());
    prim.attributes["WEIGHTS_0"] = add_floats(buffer, m.weights, 4, TINYGLTF_TYPE_VEC4, TINYGLTF_TARGET_ARRAY_BUFFER, false);
    const bool small = m.positions.size() <= 65535;
    if (small) {
      std::vector<uint16_t> idx(m.indices.begin(), m.indices.end());
      prim.indices = buffer.accessor(buffer.view(idx.data(), idx.size() * 2, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, idx.size());
    } else {
      prim.indices = buffer.accessor(buffer.view(m.indices.data(), m.indices.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, m.indices.size());
    }
    tinygltf::Mesh mesh;
    mesh.name = "body";
    mesh.primitives.push_back(prim);
    model.meshes.push_back(mesh);
    const int ibm = add_floats(buffer, m.inverse_bind, 16, TINYGLTF_TYPE_MAT4, 0, false);
    for (size_t c = 0; c < scene.characters.size(); ++c) {
      tinygltf::Skin skin;
      skin.name = prefix ? "character" + gltf_document::num(c) : "skeleton";
      skin.inverseBindMatrices = ibm;
      skin.skeleton = joint_node[c][0];
      skin.joints = joint_node[c];
      model.skins.push_back(skin);
      tinygltf::Node node;
      node.name = prefix ? "character" + gltf_document::num(c) + ":body" : "body";
      node.mesh = 0;
      node.skin = static_cast<int>(c);
      model.nodes.push_back(node);
      gscene.nodes.push_back(static_cast<int>(model.nodes.size() - 1));
    }
  }

  // One animation: a translation channel per root, a rotation channel per joint.
  tinygltf::Animation anim;
  anim.name = scene.animation_name.empty() ? scene.characters.front().name : scene.animation_name;
  if (anim.name.empty()) anim.name = "motion";
  std::map<size_t, int> time_accessor;  // frame count -> accessor
  for (size_t c = 0; c < scene.characters.size(); ++c) {
    const Clip& clip = scene.characters[c];
    const size_t frames = clip.frames.size();
    if (frames == 0) continue;
    if (!time_accessor.count(frames)) {
      std::vector<float> times(frames);
      for (size_t f = 0; f < frames; ++f) times[f] = static_cast<float>(static_cast<double>(f) / static_cast<double>(clip.fps));
      for (size_t f = 1; f < frames; ++f)
        if (!(times[f] > times[f - 1])) throw std::invalid_argument("glTF export: frame times are not strictly increasing");
      const int view = buffer.view(times.data(), times.size() * sizeof(float), 0);
      time_accessor[frames] = buffer.accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, frames,
                                              {static_cast<double>(times.front())}, {static_cast<double>(times.back())});
    }
    const int input = time_accessor[frames];
    auto add_channel = [&](int output, int node, const char* path) {
      tinygltf::AnimationSampler s;
      s.input = input;
      s.output = output;
      s.interpolation = "LINEAR";
      anim.samplers.push_back(s);
      tinygltf::AnimationChannel ch;
      ch.sampler = static_cast<int>(anim.samplers.size() - 1);
      ch.target_node = node;
      ch.target_path = path;
      anim.channels.push_back(ch);
    };
    std::vector<glm::vec3> root(frames);
    for (size_t f = 0; f < frames; ++f) root[f] = clip.frames[f].root_position;
    add_channel(add_floats(buffer, root, 3, TINYGLTF_TYPE_VEC3, 0, false), joint_node[c][0], "translation");
    for (int j = 0; j < clip.skeleton->size(); ++j) {
      std::vector<glm::vec4> q(frames);  // x y z w
      glm::quat prev(1, 0, 0, 0);
      for (size_t f = 0; f < frames; ++f) {
        glm::quat r = glm::normalize(clip.frames[f].rotations[static_cast<size_t>(j)]);
        if (!std::isfinite(r.w) || !std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z))
          throw std::invalid_argument("glTF export: a rotation is not finite");
        if (f > 0 && glm::dot(prev, r) < 0.0f) r = -r;
        prev = r;
        q[f] = glm::vec4(r.x, r.y, r.z, r.w);
      }
      add_channel(add_floats(buffer, q, 4, TINYGLTF_TYPE_VEC4, 0, false), joint_node[c][static_cast<size_t>(j)], "rotation");
    }
  }
  if (!anim.channels.empty()) model.animations.push_back(anim);
  buffer.finish();
  model.scenes.push_back(gscene);
  model.defaultScene = 0;

  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&model, out, !binary, binary)) throw std::runtime_error("glTF export: tinygltf failed to serialize");
  return out.str();
}

void write_gltf(const GltfScene& scene, const std::string& path) {
  auto ends = [&](const char* ext) {
    const size_t n = std::strlen(ext);
    if (path.size() < n) return false;
    std::string tail = path.substr(path.size() - n);
    std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return tail == ext;
  };
  if (!ends(".glb") && !ends(".gltf")) throw std::invalid_argument(path + ": a glTF file name ends in .glb or .gltf");
  write_file_atomic(path, format_gltf(scene, ends(".glb")));
}

}  // namespace prep
