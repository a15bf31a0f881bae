// The random courses `prep evaluate --random N --seed S [--vary-sizes]` draws on the built-in set, for the
// world tests that replay some of them.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/world/courses.h"
#include "tests/world/builtin_assets.h"

namespace prep::test {

// The random courses' options for the built-in set (what it can act on and pass), as `prep evaluate` sets them.
inline CourseOptions builtin_course_options(std::uint64_t seed, bool vary_sizes) {
  CourseOptions o;
  o.seed = seed;
  o.actions = actions_of(*builtin_assets());
  o.reach = reaches_of(*builtin_assets());
  o.vary_sizes = vary_sizes;
  o.heights = heights_of(*builtin_assets());
  return o;
}

// Course k of a seed on the built-in set, as `prep evaluate --random N --seed S` draws it.
inline Scenario builtin_random_course(std::uint64_t seed, int k) {
  return make_courses(builtin_course_options(seed, false), k + 1)[static_cast<size_t>(k)];
}

}  // namespace prep::test
