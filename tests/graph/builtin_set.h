// The built-in motion set with the default Params, shared by the graph tests: made once per test process.
#pragma once

#include "engine/library/builtin.h"
#include "engine/params/params.h"

namespace prep::test {

inline const MotionSet& builtin() {
  static const MotionSet set = make_builtin_motion_set(Params());
  return set;
}

}  // namespace prep::test
