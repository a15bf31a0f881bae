#include "engine/interop/gltf_document.h"

#include <cmath>
#include <fstream>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>
#include <set>

namespace prep::gltf_document {

// ------------------------------------------------------------------------------------------------
// Reading: container and model
// ------------------------------------------------------------------------------------------------

namespace {

uint32_t read_u32_le(std::string_view bytes, size_t at) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + at);
  return static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) | (static_cast<uint32_t>(p[2]) << 16) |
         (static_cast<uint32_t>(p[3]) << 24);
}

constexpr uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;     // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;      // "BIN\0"

bool is_glb(std::string_view bytes) { return bytes.size() >= 4 && read_u32_le(bytes, 0) == kGlbMagic; }

// Checks the GLB container (header, chunk headers and lengths) before tinygltf sees it, so that a
// truncated or inconsistent file gets an exact message.
void check_glb_container(std::string_view bytes, const std::string& src) {
  if (bytes.size() < 12) throw InputError(src, "GLB: truncated header (" + num(bytes.size()) + " bytes, 12 needed)");
  const uint32_t version = read_u32_le(bytes, 4);
  if (version != 2) throw InputError(src, "GLB: container version " + std::to_string(version) + ", expected 2");
  const uint32_t length = read_u32_le(bytes, 8);
  if (length != bytes.size())
    throw InputError(src, "GLB: header declares " + std::to_string(length) + " bytes but the file has " +
                              num(bytes.size()) + (length > bytes.size() ? " (truncated)" : ""));
  size_t at = 12;
  int chunk = 0;
  while (at < bytes.size()) {
    if (bytes.size() - at < 8) throw InputError(src, "GLB: truncated chunk header at byte " + num(at));
    const uint32_t chunk_length = read_u32_le(bytes, at);
    const uint32_t type = read_u32_le(bytes, at + 4);
    if (chunk_length > bytes.size() - at - 8)
      throw InputError(src, "GLB: chunk " + num(chunk) + " declares " + std::to_string(chunk_length) +
                                " bytes, past the end of the file");
    if (chunk == 0 && type != kChunkJson) throw InputError(src, "GLB: the first chunk is not JSON");
    if (chunk == 1 && type != kChunkBin) throw InputError(src, "GLB: the second chunk is not BIN");
    if (chunk_length % 4 != 0) throw InputError(src, "GLB: chunk " + num(chunk) + " length is not a multiple of 4");
    at += 8 + static_cast<size_t>(chunk_length);
    ++chunk;
  }
  if (chunk == 0) throw InputError(src, "GLB: no JSON chunk");
}

// File-system callbacks for tinygltf: plain reads relative to base_dir, no shell expansion, no writes.
bool fs_exists(const std::string& path, void*) { return std::ifstream(path, std::ios::binary).good(); }
std::string fs_expand(const std::string& path, void*) { return path; }
bool fs_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (err) *err += "cannot open " + path + "\n";
    return false;
  }
  out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return true;
}
bool fs_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is disabled while reading\n";
  return false;
}
// Images are not needed (we use geometry, skins and animations): keep them undecoded.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

// tinygltf silently treats some invalid numbers as absent (a negative byteStride reads as "tightly
// packed"), so the JSON's integer fields that locate data are checked here first, and bad JSON gets
// nlohmann's message with its byte position.
void check_json_fields(std::string_view json_text, const std::string& src) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(json_text.begin(), json_text.end());
  } catch (const nlohmann::json::exception& e) {
    throw InputError(src, std::string("not a valid glTF: bad JSON: ") + e.what());
  }
  if (!j.is_object()) throw InputError(src, "not a valid glTF: the JSON is not an object");
  auto check = [&](const char* array, std::initializer_list<const char*> fields) {
    auto it = j.find(array);
    if (it == j.end()) return;
    if (!it->is_array()) throw InputError(src, std::string(array) + " is not an array");
    for (size_t i = 0; i < it->size(); ++i) {
      const nlohmann::json& item = (*it)[i];
      if (!item.is_object()) throw InputError(src, std::string(array) + "[" + num(i) + "] is not an object");
      for (const char* field : fields) {
        auto f = item.find(field);
        if (f != item.end() && !f->is_number_unsigned())
          throw InputError(src, std::string(array) + "[" + num(i) + "]." + field + " is " + f->dump() +
                                    ", not a non-negative integer");
      }
    }
  };
  check("bufferViews", {"buffer", "byteOffset", "byteLength", "byteStride"});
  check("accessors", {"bufferView", "byteOffset", "count", "componentType"});
  check("buffers", {"byteLength"});
  check("skins", {"inverseBindMatrices", "skeleton"});
  check("nodes", {"mesh", "skin"});
}

}  // namespace

tinygltf::Model load_model(std::string_view bytes, const std::string& src, const std::string& base_dir) {
  if (bytes.size() > std::numeric_limits<unsigned int>::max())
    throw InputError(src, "file too large for a glTF reader (" + num(bytes.size()) + " bytes)");
  tinygltf::TinyGLTF loader;
  tinygltf::FsCallbacks fs{};
  fs.FileExists = base_dir.empty() ? [](const std::string&, void*) { return false; } : &fs_exists;
  fs.ExpandFilePath = &fs_expand;
  fs.ReadWholeFile = &fs_read;
  fs.WriteWholeFile = &fs_write;
  fs.user_data = nullptr;
  loader.SetFsCallbacks(fs);
  loader.SetImageLoader(&skip_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  bool ok = false;
  if (is_glb(bytes)) {
    check_glb_container(bytes, src);
    check_json_fields(bytes.substr(20, read_u32_le(bytes, 12)), src);
    ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                     static_cast<unsigned int>(bytes.size()), base_dir);
  } else {
    check_json_fields(bytes, src);
    ok = loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()),
                                    base_dir);
  }
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw InputError(src, "not a valid glTF: " + (err.empty() ? std::string("unknown error") : err));
  }
  return model;
}

// ------------------------------------------------------------------------------------------------
// Node transforms
// ------------------------------------------------------------------------------------------------


glm::dquat rotation_of(const glm::dmat4& m, bool* ok) {
  glm::dmat3 r(m);
  const double sx = glm::length(r[0]), sy = glm::length(r[1]), sz = glm::length(r[2]);
  *ok = sx > 1e-12 && sy > 1e-12 && sz > 1e-12 && std::isfinite(sx + sy + sz);
  if (!*ok) return glm::dquat(1, 0, 0, 0);
  r[0] /= sx;
  r[1] /= sy;
  r[2] /= sz;
  if (glm::determinant(r) < 0.0) {  // a mirror: keep the rotation part
    r[2] = -r[2];
  }
  return glm::normalize(glm::quat_cast(r));
}

namespace {

bool finite_all(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

}  // namespace

Trs node_trs(const tinygltf::Node& node, size_t index, const Reader& rd) {
  const std::string where = "nodes[" + num(index) + "]";
  Trs trs;
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16 || !finite_all(node.matrix)) rd.fail(where + ".matrix is not 16 finite numbers");
    const glm::dmat4 m = glm::make_mat4(node.matrix.data());
    bool ok = false;
    trs.r = rotation_of(m, &ok);
    if (!ok) rd.fail(where + ".matrix is singular");
    trs.t = glm::dvec3(m[3]);
    trs.s = glm::dvec3(glm::length(glm::dvec3(m[0])), glm::length(glm::dvec3(m[1])), glm::length(glm::dvec3(m[2])));
    return trs;
  }
  if (!node.translation.empty()) {
    if (node.translation.size() != 3 || !finite_all(node.translation)) rd.fail(where + ".translation is not 3 finite numbers");
    trs.t = glm::dvec3(node.translation[0], node.translation[1], node.translation[2]);
  }
  if (!node.rotation.empty()) {
    if (node.rotation.size() != 4 || !finite_all(node.rotation)) rd.fail(where + ".rotation is not 4 finite numbers");
    const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    if (glm::length(q) < 1e-6) rd.fail(where + ".rotation is a zero quaternion");
    trs.r = glm::normalize(q);
  }
  if (!node.scale.empty()) {
    if (node.scale.size() != 3 || !finite_all(node.scale)) rd.fail(where + ".scale is not 3 finite numbers");
    trs.s = glm::dvec3(node.scale[0], node.scale[1], node.scale[2]);
  }
  return trs;
}

namespace {

bool ends_with_end(const std::string& name) {
  if (name.size() < 4) return false;
  std::string tail = name.substr(name.size() - 4);
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return tail == "_end";
}

}  // namespace

// ------------------------------------------------------------------------------------------------
// Rigs: which nodes are the joints of one character
// ------------------------------------------------------------------------------------------------

std::string node_name(const tinygltf::Model& model, int node) {
  const std::string& n = model.nodes[static_cast<size_t>(node)].name;
  return n.empty() ? "node" + num(node) : n;
}

namespace {

// Builds a rig from a set of candidate joint nodes (in a preferred order).
Rig make_rig(const tinygltf::Model& model, const NodeGraph& graph, const std::vector<int>& candidates, const Reader& rd,
             const std::string& what) {
  std::set<int> members(candidates.begin(), candidates.end());
  auto joint_parent_of = [&](int node) {
    for (int p = graph.parent[static_cast<size_t>(node)]; p != -1; p = graph.parent[static_cast<size_t>(p)])
      if (members.count(p)) return p;
    return -1;
  };
  auto has_member_child = [&](int node) {
    for (int c : model.nodes[static_cast<size_t>(node)].children)
      if (members.count(c)) return true;
    return false;
  };
  // Leaves named *_end become End Sites of their parent joint.
  std::map<int, int> end_of;  // joint node -> end node
  for (int node : candidates) {
    const int p = joint_parent_of(node);
    if (p != -1 && !has_member_child(node) && model.nodes[static_cast<size_t>(node)].children.empty() &&
        ends_with_end(model.nodes[static_cast<size_t>(node)].name) && !end_of.count(p))
      end_of[p] = node;
  }
  std::set<int> end_nodes;
  for (auto& e : end_of) end_nodes.insert(e.second);
  // Non-member leaf children named *_end (our own exports keep End Sites outside the skin).
  for (int node : candidates) {
    if (end_nodes.count(node) || end_of.count(node)) continue;
    for (int c : model.nodes[static_cast<size_t>(node)].children)
      if (!members.count(c) && model.nodes[static_cast<size_t>(c)].children.empty() &&
          model.nodes[static_cast<size_t>(c)].mesh < 0 && ends_with_end(model.nodes[static_cast<size_t>(c)].name)) {
        end_of[node] = c;
        break;
      }
  }
  std::vector<int> joints;
  for (int node : candidates)
    if (!end_nodes.count(node)) joints.push_back(node);
  members = std::set<int>(joints.begin(), joints.end());
  int roots = 0;
  for (int node : joints)
    if (joint_parent_of(node) == -1) ++roots;
  if (roots != 1) rd.fail(what + ": its joints form " + num(roots) + " separate trees (one root expected)");
  // Parents first: keep the given order when it already is, else a depth-first order.
  std::map<int, int> position;
  bool parents_first = true;
  for (size_t i = 0; i < joints.size(); ++i) {
    const int p = joint_parent_of(joints[i]);
    if (p != -1 && !position.count(p)) parents_first = false;
    position[joints[i]] = static_cast<int>(i);
  }
  if (!parents_first) {
    std::map<int, std::vector<int>> kids;
    int root = -1;
    for (int node : joints) {
      const int p = joint_parent_of(node);
      if (p == -1) root = node;
      else kids[p].push_back(node);
    }
    std::vector<int> ordered, stack{root};
    while (!stack.empty()) {
      const int node = stack.back();
      stack.pop_back();
      ordered.push_back(node);
      auto& k = kids[node];
      for (auto it = k.rbegin(); it != k.rend(); ++it) stack.push_back(*it);
    }
    joints = ordered;
  }
  Rig rig;
  rig.joint_nodes = joints;
  for (size_t i = 0; i < joints.size(); ++i) rig.node_to_joint[joints[i]] = static_cast<int>(i);
  for (int node : joints) {
    const int p = joint_parent_of(node);
    rig.joint_parent.push_back(p == -1 ? -1 : rig.node_to_joint[p]);
    auto e = end_of.find(node);
    rig.end_node.push_back(e == end_of.end() ? -1 : e->second);
  }
  for (int node : end_nodes) {
    const int p = joint_parent_of(node);
    rig.node_to_joint[node] = rig.node_to_joint[p];
  }
  return rig;
}

}  // namespace

std::vector<Rig> find_rigs(const tinygltf::Model& model, const NodeGraph& graph, const Reader& rd) {
  std::vector<Rig> rigs;
  for (size_t s = 0; s < model.skins.size(); ++s) {
    const tinygltf::Skin& skin = model.skins[s];
    const std::string what = "skins[" + num(s) + "]";
    if (skin.joints.empty()) rd.fail(what + ".joints is empty");
    std::set<int> seen;
    for (int j : skin.joints) {
      if (j < 0 || static_cast<size_t>(j) >= model.nodes.size())
        rd.fail(what + ".joints: node " + num(j) + " does not exist");
      if (!seen.insert(j).second) rd.fail(what + ".joints lists node " + num(j) + " twice");
    }
    Rig rig = make_rig(model, graph, skin.joints, rd, what);
    rig.skin = static_cast<int>(s);
    rig.name = skin.name.empty() ? node_name(model, rig.joint_nodes[0]) : skin.name;
    rigs.push_back(std::move(rig));
  }
  if (!rigs.empty()) return rigs;
  // No skin: every scene root with a subtree of at least two nodes (no meshes) is a skeleton.
  std::vector<int> roots;
  int scene = model.defaultScene;
  if (scene < 0 || static_cast<size_t>(scene) >= model.scenes.size()) scene = model.scenes.empty() ? -1 : 0;
  if (scene >= 0) {
    for (int r : model.scenes[static_cast<size_t>(scene)].nodes) {
      if (r < 0 || static_cast<size_t>(r) >= model.nodes.size())
        rd.fail("scenes[" + num(scene) + "].nodes: node " + num(r) + " does not exist");
      roots.push_back(r);
    }
  } else {
    for (size_t i = 0; i < model.nodes.size(); ++i)
      if (graph.parent[i] == -1) roots.push_back(static_cast<int>(i));
  }
  for (int r : roots) {
    std::vector<int> subtree, stack{r};
    while (!stack.empty()) {
      const int node = stack.back();
      stack.pop_back();
      if (model.nodes[static_cast<size_t>(node)].mesh >= 0) continue;
      subtree.push_back(node);
      const auto& kids = model.nodes[static_cast<size_t>(node)].children;
      for (auto it = kids.rbegin(); it != kids.rend(); ++it) stack.push_back(*it);
    }
    if (subtree.size() < 2) continue;
    Rig rig = make_rig(model, graph, subtree, rd, "node tree of nodes[" + num(r) + "]");
    rig.name = node_name(model, r);
    rigs.push_back(std::move(rig));
  }
  return rigs;
}

// ------------------------------------------------------------------------------------------------
// Animation sampling
// ------------------------------------------------------------------------------------------------


std::vector<Channel> read_channels(const tinygltf::Model& model, size_t anim_index, const Reader& rd) {
  const tinygltf::Animation& anim = model.animations[anim_index];
  const std::string what = "animations[" + num(anim_index) + "]";
  std::vector<Channel> out;
  for (size_t c = 0; c < anim.channels.size(); ++c) {
    const tinygltf::AnimationChannel& ch = anim.channels[c];
    const std::string cw = what + ".channels[" + num(c) + "]";
    if (ch.target_path == "weights") continue;  // morph weights: not a skeleton's business
    if (ch.target_node < 0) continue;           // targets something of an extension
    if (static_cast<size_t>(ch.target_node) >= model.nodes.size())
      rd.fail(cw + ".target.node " + num(ch.target_node) + " does not exist");
    if (ch.sampler < 0 || static_cast<size_t>(ch.sampler) >= anim.samplers.size())
      rd.fail(cw + ".sampler " + num(ch.sampler) + " does not exist");
    const tinygltf::AnimationSampler& smp = anim.samplers[static_cast<size_t>(ch.sampler)];
    const std::string sw = what + ".samplers[" + num(ch.sampler) + "]";
    Channel channel;
    channel.node = ch.target_node;
    if (ch.target_path == "translation") channel.path = Channel::kTranslation;
    else if (ch.target_path == "rotation") channel.path = Channel::kRotation;
    else if (ch.target_path == "scale") channel.path = Channel::kScale;
    else rd.fail(cw + ".target.path \"" + ch.target_path + "\" is not a glTF path");
    if (smp.interpolation == "LINEAR" || smp.interpolation.empty()) channel.interp = Channel::kLinear;
    else if (smp.interpolation == "STEP") channel.interp = Channel::kStep;
    else if (smp.interpolation == "CUBICSPLINE") channel.interp = Channel::kCubic;
    else rd.fail(sw + ".interpolation \"" + smp.interpolation + "\" is unknown");
    const AccessorView in = rd.accessor(smp.input, sw + ".input", {TINYGLTF_TYPE_SCALAR}, {TINYGLTF_COMPONENT_TYPE_FLOAT});
    channel.times.resize(in.count);
    for (size_t k = 0; k < in.count; ++k) {
      channel.times[k] = in.get(k, 0);
      if (!std::isfinite(channel.times[k])) rd.fail(sw + ".input: time " + num(k) + " is not finite");
      if (k > 0 && !(channel.times[k] > channel.times[k - 1]))
        rd.fail(sw + ".input: times are not strictly increasing at key " + num(k));
    }
    const bool rotation = channel.path == Channel::kRotation;
    const AccessorView outv =
        rotation ? rd.accessor(smp.output, sw + ".output", {TINYGLTF_TYPE_VEC4},
                               {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                               true)
                 : rd.accessor(smp.output, sw + ".output", {TINYGLTF_TYPE_VEC3}, {TINYGLTF_COMPONENT_TYPE_FLOAT});
    const size_t per_key = channel.interp == Channel::kCubic ? 3 : 1;
    if (outv.count / per_key != in.count || outv.count % per_key != 0)
      rd.fail(sw + ": output has " + num(outv.count) + " elements for " + num(in.count) + " keys");
    channel.values.resize(outv.count);
    for (size_t k = 0; k < outv.count; ++k) {
      glm::dvec4 v(0.0);
      for (int i = 0; i < outv.components; ++i) v[i] = outv.get(k, i);
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || !std::isfinite(v.w))
        rd.fail(sw + ".output: element " + num(k) + " is not finite");
      const bool is_value = per_key == 1 || k % 3 == 1;
      if (rotation && is_value) {
        if (glm::length(v) < 1e-6) rd.fail(sw + ".output: rotation " + num(k) + " is a zero quaternion");
        v = glm::normalize(v);
      }
      channel.values[k] = v;
    }
    out.push_back(std::move(channel));
  }
  return out;
}

}  // namespace prep::gltf_document
