// The static meshes the renderer instances: a capsule of zero length (capsule.vert stretches it between a
// bone's two ends) and a unit cube (box.vert places it).
#pragma once

#include <vector>

namespace prep::render {

// A unit-radius capsule of zero length, `slices` vertices around and `half_rings` rings per end (at least
// 3 and 1). Each vertex is four floats: its offset from its end's centre (x, y, z; y along the axis) and
// the end it belongs to (0: A, below; 1: B, above). A closed surface, its triangles counter-clockwise seen
// from outside: 2 + 2 * slices * half_rings vertices, 4 * slices * half_rings triangles.
void capsule_mesh(int slices, int half_rings, std::vector<float>& vertices, std::vector<unsigned>& indices);

// A unit cube centred on the origin, a quad per face with its own normal: six floats a vertex (position,
// normal), counter-clockwise seen from outside.
void cube_mesh(std::vector<float>& vertices, std::vector<unsigned>& indices);

}  // namespace prep::render
