#include "engine/interop/gltf_io.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "engine/motion/pose.h"
#include "engine/util/error.h"
#include "engine/util/files.h"

namespace prep {

namespace {

// ------------------------------------------------------------------------------------------------
// Reading: container and model
// ------------------------------------------------------------------------------------------------

std::string num(size_t v) { return std::to_string(v); }
std::string num(int v) { return std::to_string(v); }

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
// Checked accessor reads
// ------------------------------------------------------------------------------------------------

int component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;  // MAT2/MAT3 need column padding for small types; we read none of them
  }
}

size_t component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

// A view of one accessor whose every element has been checked to lie inside its buffer.
struct AccessorView {
  const unsigned char* data = nullptr;
  size_t count = 0;
  size_t stride = 0;
  int component_type = 0;
  int components = 0;
  bool normalized = false;

  double get(size_t element, int component) const {
    const unsigned char* p = data + element * stride + static_cast<size_t>(component) * component_size(component_type);
    switch (component_type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float f;
        std::memcpy(&f, p, 4);
        return f;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0 : p[0];
      case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const auto v = static_cast<int8_t>(p[0]);
        return normalized ? std::max(v / 127.0, -1.0) : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? v / 65535.0 : v;
      }
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
      }
      default: return 0.0;
    }
  }
};

struct Reader {
  const tinygltf::Model& model;
  const std::string& src;

  [[noreturn]] void fail(const std::string& message) const { throw InputError(src, message); }

  // `what` names the field that refers to the accessor, e.g. "skins[0].inverseBindMatrices".
  AccessorView accessor(int index, const std::string& what, std::initializer_list<int> types,
                        std::initializer_list<int> component_types, bool allow_normalized_ints = false) const {
    if (index < 0 || static_cast<size_t>(index) >= model.accessors.size())
      fail(what + ": accessor " + num(index) + " does not exist (" + num(model.accessors.size()) + " accessors)");
    const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(index)];
    const std::string where = what + " (accessors[" + num(index) + "])";
    if (a.sparse.isSparse) fail(where + ": sparse accessors are not supported");
    if (std::find(types.begin(), types.end(), a.type) == types.end())
      fail(where + ": unexpected type " + num(a.type));
    if (std::find(component_types.begin(), component_types.end(), a.componentType) == component_types.end())
      fail(where + ": unexpected componentType " + num(a.componentType));
    if (a.normalized && !allow_normalized_ints) fail(where + ": normalized is not allowed here");
    if (a.count == 0) fail(where + ": count is 0");
    if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) >= model.bufferViews.size())
      fail(where + ": bufferView " + num(a.bufferView) + " does not exist");
    const tinygltf::BufferView& bv = model.bufferViews[static_cast<size_t>(a.bufferView)];
    const std::string view_name = "bufferViews[" + num(a.bufferView) + "]";
    if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= model.buffers.size())
      fail(where + ": " + view_name + ".buffer " + num(bv.buffer) + " does not exist");
    const size_t buffer_size = model.buffers[static_cast<size_t>(bv.buffer)].data.size();
    if (bv.byteOffset > buffer_size || bv.byteLength > buffer_size - bv.byteOffset)
      fail(where + ": " + view_name + " (byteOffset " + num(bv.byteOffset) + ", byteLength " + num(bv.byteLength) +
           ") runs past buffers[" + num(bv.buffer) + "] (" + num(buffer_size) + " bytes)");
    const size_t csize = component_size(a.componentType);
    const int ncomp = component_count(a.type);
    const size_t element = csize * static_cast<size_t>(ncomp);
    const size_t stride = bv.byteStride != 0 ? bv.byteStride : element;
    if (bv.byteStride != 0 && (bv.byteStride < element || bv.byteStride > 252 || bv.byteStride % csize != 0))
      fail(where + ": " + view_name + ".byteStride " + num(bv.byteStride) + " is invalid for " + num(element) +
           "-byte elements");
    if (a.byteOffset > bv.byteLength || element > bv.byteLength - a.byteOffset)
      fail(where + ": byteOffset " + num(a.byteOffset) + " leaves no room for one element in " + view_name + " (" +
           num(bv.byteLength) + " bytes)");
    const size_t room_after_first = bv.byteLength - a.byteOffset - element;
    if (a.count - 1 > room_after_first / stride)
      fail(where + ": count " + num(a.count) + " with stride " + num(stride) + " runs past the end of " + view_name +
           " (" + num(bv.byteLength) + " bytes, accessor byteOffset " + num(a.byteOffset) + ")");
    AccessorView view;
    view.data = model.buffers[static_cast<size_t>(bv.buffer)].data.data() + bv.byteOffset + a.byteOffset;
    view.count = a.count;
    view.stride = stride;
    view.component_type = a.componentType;
    view.components = ncomp;
    view.normalized = a.normalized;
    return view;
  }

  std::vector<glm::dvec3> vec3s(int index, const std::string& what) const {
    const AccessorView v = accessor(index, what, {TINYGLTF_TYPE_VEC3}, {TINYGLTF_COMPONENT_TYPE_FLOAT});
    std::vector<glm::dvec3> out(v.count);
    for (size_t i = 0; i < v.count; ++i) {
      out[i] = glm::dvec3(v.get(i, 0), v.get(i, 1), v.get(i, 2));
      if (!std::isfinite(out[i].x) || !std::isfinite(out[i].y) || !std::isfinite(out[i].z))
        fail(what + ": element " + num(i) + " is not finite");
    }
    return out;
  }
};

// ------------------------------------------------------------------------------------------------
// Node transforms
// ------------------------------------------------------------------------------------------------

struct Trs {
  glm::dvec3 t{0.0};
  glm::dquat r{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 s{1.0};
  glm::dmat4 matrix() const {
    glm::dmat4 m = glm::mat4_cast(r);
    m[0] *= s.x;
    m[1] *= s.y;
    m[2] *= s.z;
    m[3] = glm::dvec4(t, 1.0);
    return m;
  }
};

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

bool finite_all(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

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

bool ends_with_end(const std::string& name) {
  if (name.size() < 4) return false;
  std::string tail = name.substr(name.size() - 4);
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return tail == "_end";
}

// The node graph: parents, depth order, rest transforms.
struct NodeGraph {
  std::vector<int> parent;
  std::vector<int> order;  // parents before children
  std::vector<Trs> rest;

  NodeGraph(const tinygltf::Model& model, const Reader& rd) {
    const size_t n = model.nodes.size();
    parent.assign(n, -1);
    for (size_t i = 0; i < n; ++i) {
      for (int c : model.nodes[i].children) {
        if (c < 0 || static_cast<size_t>(c) >= n)
          rd.fail("nodes[" + num(i) + "].children: node " + num(c) + " does not exist");
        if (static_cast<size_t>(c) == i || parent[static_cast<size_t>(c)] != -1)
          rd.fail("nodes[" + num(c) + "] has more than one parent");
        parent[static_cast<size_t>(c)] = static_cast<int>(i);
      }
    }
    std::vector<int> depth(n, -1);
    for (size_t i = 0; i < n; ++i) {
      int d = 0;
      for (int p = parent[i]; p != -1; p = parent[static_cast<size_t>(p)])
        if (++d > static_cast<int>(n)) rd.fail("the node hierarchy has a cycle through nodes[" + num(i) + "]");
      depth[i] = d;
    }
    order.resize(n);
    for (size_t i = 0; i < n; ++i) order[i] = static_cast<int>(i);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return depth[static_cast<size_t>(a)] < depth[static_cast<size_t>(b)]; });
    rest.resize(n);
    for (size_t i = 0; i < n; ++i) rest[i] = node_trs(model.nodes[i], i, rd);
  }

  // World matrices of all nodes for the given local transforms.
  void world(const std::vector<Trs>& local, std::vector<glm::dmat4>& out) const {
    out.resize(local.size());
    for (int i : order) {
      const auto u = static_cast<size_t>(i);
      out[u] = parent[u] < 0 ? local[u].matrix() : out[static_cast<size_t>(parent[u])] * local[u].matrix();
    }
  }
};

// ------------------------------------------------------------------------------------------------
// Rigs: which nodes are the joints of one character
// ------------------------------------------------------------------------------------------------

struct Rig {
  std::string name;
  int skin = -1;
  std::vector<int> joint_nodes;     // skeleton order (parents first)
  std::vector<int> joint_parent;    // skeleton parent index per joint
  std::vector<int> end_node;        // per joint: the node that is its End Site, or -1
  std::map<int, int> node_to_joint; // joint nodes and End Site nodes (-> the joint they end)
};

std::string node_name(const tinygltf::Model& model, int node) {
  const std::string& n = model.nodes[static_cast<size_t>(node)].name;
  return n.empty() ? "node" + num(node) : n;
}

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

struct Channel {
  int node = -1;
  enum Path { kTranslation, kRotation, kScale } path = kTranslation;
  enum Interp { kLinear, kStep, kCubic } interp = kLinear;
  std::vector<double> times;
  std::vector<glm::dvec4> values;  // xyz(w); for cubic splines: in-tangent, value, out-tangent per key

  glm::dvec4 sample(double t) const {
    const size_t n = times.size();
    auto value = [&](size_t k) { return interp == kCubic ? values[3 * k + 1] : values[k]; };
    if (n == 1 || t <= times.front()) return value(0);
    if (t >= times.back()) return value(n - 1);
    const size_t k1 = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
    const size_t k0 = k1 - 1;
    const double dt = times[k1] - times[k0];
    const double u = (t - times[k0]) / dt;
    if (interp == kStep) return value(k0);
    if (interp == kCubic) {
      const double u2 = u * u, u3 = u2 * u;
      glm::dvec4 p = (2 * u3 - 3 * u2 + 1) * values[3 * k0 + 1] + (u3 - 2 * u2 + u) * dt * values[3 * k0 + 2] +
                     (-2 * u3 + 3 * u2) * values[3 * k1 + 1] + (u3 - u2) * dt * values[3 * k1];
      return path == kRotation ? glm::normalize(p) : p;
    }
    if (path == kRotation) {
      glm::dquat a(value(k0).w, value(k0).x, value(k0).y, value(k0).z);
      glm::dquat b(value(k1).w, value(k1).x, value(k1).y, value(k1).z);
      if (glm::dot(a, b) < 0.0) b = -b;
      const glm::dquat q = glm::normalize(glm::slerp(a, b, u));
      return glm::dvec4(q.x, q.y, q.z, q.w);
    }
    return value(k0) + (value(k1) - value(k0)) * u;
  }
};

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
      if (regular) {
        fps = 1.0 / dt;
        if (std::fabs(fps - std::round(fps)) < 1e-2) fps = std::round(fps);
      }
    }
  }
  const double span = (t1 - t0) * fps;
  if (span > 1e6) rd.fail("animations[" + num(anim_index) + "]: " + std::to_string(t1 - t0) + " s is too long to resample");
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

}  // namespace

std::vector<GltfCharacter> parse_gltf(std::string_view bytes, const std::string& source_name,
                                      const GltfReadOptions& options, const std::string& base_dir) {
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

// ------------------------------------------------------------------------------------------------
// Writing
// ------------------------------------------------------------------------------------------------

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
    const std::string pre = prefix ? "character" + num(c) + ":" : "";
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
      skin.name = prefix ? "character" + num(c) : "skeleton";
      skin.inverseBindMatrices = ibm;
      skin.skeleton = joint_node[c][0];
      skin.joints = joint_node[c];
      model.skins.push_back(skin);
      tinygltf::Node node;
      node.name = prefix ? "character" + num(c) + ":body" : "body";
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
