// The glTF document as the importer sees it: tinygltf's model, loaded from bytes whose container and JSON
// were checked first; accessors read with every element inside its buffer; the node graph with its rest
// transforms; the rigs (which nodes are one character's joints); the animation channels. Every failure is
// an InputError naming the file and the field. Used by the importer (gltf_read.cpp) and the exporter.
#pragma once

#include <tiny_gltf.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <initializer_list>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "engine/util/error.h"

namespace prep::gltf_document {

inline std::string num(size_t v) { return std::to_string(v); }
inline std::string num(int v) { return std::to_string(v); }

inline int component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;  // MAT2/MAT3 need column padding for small types; we read none of them
  }
}

inline size_t component_size(int component_type) {
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
// The model, nodes, rigs and channels
// ------------------------------------------------------------------------------------------------

// Parses a .gltf (JSON) or .glb file's bytes; external buffers are read relative to base_dir.
tinygltf::Model load_model(std::string_view bytes, const std::string& src, const std::string& base_dir);

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

// The rotation of a transform matrix (its scale divided out, a mirror's flip dropped); ok is false for
// a singular one.
glm::dquat rotation_of(const glm::dmat4& m, bool* ok);
Trs node_trs(const tinygltf::Node& node, size_t index, const Reader& rd);

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

struct Rig {
  std::string name;
  int skin = -1;
  std::vector<int> joint_nodes;     // skeleton order (parents first)
  std::vector<int> joint_parent;    // skeleton parent index per joint
  std::vector<int> end_node;        // per joint: the node that is its End Site, or -1
  std::map<int, int> node_to_joint; // joint nodes and End Site nodes (-> the joint they end)
};

std::string node_name(const tinygltf::Model& model, int node);
std::vector<Rig> find_rigs(const tinygltf::Model& model, const NodeGraph& graph, const Reader& rd);

struct Channel {
  int node = -1;
  enum Path { kTranslation, kRotation, kScale } path = kTranslation;
  enum Interp { kLinear, kStep, kCubic } interp = kLinear;
  std::vector<double> times;
  std::vector<glm::dvec4> values;  // xyz(w); for cubic splines: in-tangent, value, out-tangent per key

  glm::dvec4 sample(double t) const {
    const size_t n = times.size();
    auto value = [&](size_t k) { return interp == kCubic ? values[3 * k + 1] : values[k]; };
    // Written so that a time that is not a number takes the first key rather than reading past the last.
    if (n == 1 || !(t > times.front())) return value(0);
    if (!(t < times.back())) return value(n - 1);
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

std::vector<Channel> read_channels(const tinygltf::Model& model, size_t anim_index, const Reader& rd);

}  // namespace prep::gltf_document
