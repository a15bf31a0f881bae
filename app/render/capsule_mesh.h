// The unit capsule mesh the capsule shaders place (capsule_frame.glsl): a unit-radius capsule of zero
// length, rows of vertices from the bottom pole of end A to the top pole of end B; the band between A's
// equator and B's equator is the cylinder. Four floats per vertex: the point on the unit sphere (x, y, z)
// and which end it belongs to (0: A, 1: B).
#pragma once

#include <vector>

namespace prep::render {

void capsule_mesh(int slices, int half_rings, std::vector<float>& vertices, std::vector<unsigned>& indices);

}  // namespace prep::render
