// A vertex of the unit capsule mesh placed on a capsule (shared by capsule.vert and capsule_batch.vert):
// `offset` is a point of the unit sphere around cap centre A (end 0) or B (end 1), in a frame whose Y axis
// is the capsule's axis; it becomes both the offset from that centre (times the radius) and the normal.
void place_capsule_vertex(vec3 a, vec3 b, float radius, vec3 offset, float end, out vec3 world, out vec3 normal) {
  vec3 axis = b - a;
  float len = length(axis);
  vec3 y = len > 1e-6 ? axis / len : vec3(0.0, 1.0, 0.0);
  vec3 helper = abs(y.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 x = normalize(cross(helper, y));
  vec3 z = cross(x, y);
  normal = mat3(x, y, z) * offset;
  world = mix(a, b, end) + normal * radius;
}
