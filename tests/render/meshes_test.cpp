// The instanced meshes are closed surfaces with every triangle facing out (back faces are culled), and the
// capsule carries no vertex or triangle a rasterizer would process for nothing.
#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <map>
#include <utility>
#include <vector>

#include "app/render/meshes.h"

using namespace prep;

namespace {

struct Surface {
  std::vector<glm::vec3> points;
  std::vector<unsigned> indices;
};

// Every triangle has area and faces away from the nearest point of the axis from `axis_a` to `axis_b` (the
// segment the surface is built around); every directed edge is used once and its reverse once: closed,
// consistently wound.
void check_closed_and_outward(const Surface& s, glm::vec3 axis_a, glm::vec3 axis_b) {
  REQUIRE(s.indices.size() % 3 == 0);
  std::map<std::pair<unsigned, unsigned>, int> directed;
  for (size_t t = 0; t < s.indices.size(); t += 3) {
    const unsigned i[3] = {s.indices[t], s.indices[t + 1], s.indices[t + 2]};
    for (unsigned k : i) REQUIRE(k < s.points.size());
    const glm::vec3 a = s.points[i[0]], b = s.points[i[1]], c = s.points[i[2]];
    const glm::vec3 normal = glm::cross(b - a, c - a);
    CHECK(glm::length(normal) > 1e-4f);
    const glm::vec3 centroid = (a + b + c) / 3.0f;
    const glm::vec3 axis = axis_b - axis_a;
    const float along = glm::clamp(glm::dot(centroid - axis_a, axis) / glm::dot(axis, axis), 0.0f, 1.0f);
    CHECK(glm::dot(normal, centroid - (axis_a + along * axis)) > 0.0f);
    for (int e = 0; e < 3; ++e) ++directed[{i[e], i[(e + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    CHECK(count == 1);
    const auto reverse = directed.find({edge.second, edge.first});
    CHECK((reverse != directed.end() && reverse->second == 1));
  }
}

}  // namespace

TEST_CASE("the capsule mesh is closed, faces out, and has one vertex per pole and none twice") {
  for (const std::pair<int, int>& size : std::vector<std::pair<int, int>>{{4, 1}, {6, 1}, {20, 7}, {5, 3}}) {
    const int slices = size.first, half_rings = size.second;  // plain variables: CAPTURE's lambda takes them
    CAPTURE(slices);
    CAPTURE(half_rings);
    std::vector<float> v;
    std::vector<unsigned> idx;
    render::capsule_mesh(slices, half_rings, v, idx);
    REQUIRE(v.size() % 4 == 0);
    CHECK(v.size() / 4 == static_cast<size_t>(2 + 2 * slices * half_rings));
    CHECK(idx.size() / 3 == static_cast<size_t>(4 * slices * half_rings));
    // Stretched as capsule.vert does (end B one unit up the axis), radius 0.5.
    Surface s;
    for (size_t k = 0; k < v.size(); k += 4) {
      const glm::vec3 offset(v[k], v[k + 1], v[k + 2]);
      CHECK(glm::length(offset) == doctest::Approx(1.0f).epsilon(1e-5));
      CHECK((v[k + 3] == 0.0f || v[k + 3] == 1.0f));
      // End A's vertices lie on its lower half, end B's on its upper one.
      CHECK((v[k + 3] == 0.0f ? offset.y <= 1e-6f : offset.y >= -1e-6f));
      s.points.push_back(0.5f * offset + glm::vec3(0.0f, v[k + 3], 0.0f));
    }
    for (size_t a = 0; a < s.points.size(); ++a)
      for (size_t b = a + 1; b < s.points.size(); ++b) CHECK(glm::length(s.points[a] - s.points[b]) > 1e-4f);
    s.indices = idx;
    check_closed_and_outward(s, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
  }
}

TEST_CASE("the cube mesh faces out, each face with its own outward normal") {
  std::vector<float> v;
  std::vector<unsigned> idx;
  render::cube_mesh(v, idx);
  REQUIRE(v.size() == 24 * 6);
  REQUIRE(idx.size() == 36);
  for (size_t t = 0; t < idx.size(); t += 3) {
    const auto point = [&](unsigned i) { return glm::vec3(v[6 * i], v[6 * i + 1], v[6 * i + 2]); };
    const glm::vec3 a = point(idx[t]), b = point(idx[t + 1]), c = point(idx[t + 2]);
    const glm::vec3 n(v[6 * idx[t] + 3], v[6 * idx[t] + 4], v[6 * idx[t] + 5]);
    const glm::vec3 face = glm::cross(b - a, c - a);
    CHECK(glm::dot(face, n) > 0.0f);            // counter-clockwise seen from outside
    CHECK(glm::dot(n, (a + b + c) / 3.0f) > 0.0f);  // the normal points out of the cube
  }
}
