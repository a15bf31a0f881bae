// Where tests find the repository's assets and the shared mocap beside the repository.
#pragma once

#include <string>

namespace prep::test {
inline std::string repo() { return PREP_SOURCE_DIR; }
inline std::string mocap() { return std::string(PREP_SOURCE_DIR) + "/../shared/mocap"; }
// The BVH files the build writes for the fuzz targets and the tests (tests/fuzz/bvh_seeds.cmake).
inline std::string fuzz_seeds() { return PREP_FUZZ_SEED_DIR; }
inline std::string tmp_dir() { return std::string(PREP_SOURCE_DIR) + "/build-tmp"; }
}  // namespace prep::test
