// What the fuzz targets share: the test of a loader's answer to one input, and where the fixed data lives.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "engine/util/error.h"

namespace prep::fuzz {

inline std::string_view bytes(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// The folder of the fixed files the targets use besides their input (a humanoid BVH and a taller one),
// written by the build (bvh_seeds.cmake).
inline std::string data_dir() { return std::string(PREP_FUZZ_SEED_DIR) + "/data"; }

// Runs `load` on one input. The loader may accept it, or refuse it with an InputError whose message starts
// with the file it names ("FILE: ..." or "FILE:LINE: ...") and says something after that; when `source` is
// not empty the named file must be `source` itself. A refusal that names no file aborts; any other
// exception escapes to libFuzzer (or the replay runner) and ends the run. Both count as failures.
template <class Load>
void expect_clean(const std::string& source, Load&& load) {
  try {
    load();
  } catch (const InputError& e) {
    const std::string what = e.what();
    const std::string shown = InputError::printable(e.file());  // the file as what() names it
    const bool names_file = !e.file().empty() && what.rfind(shown + ":", 0) == 0 && what.size() > shown.size() + 2;
    if (!names_file || (!source.empty() && e.file() != source)) {
      std::fprintf(stderr, "fuzz: the error does not name %s: %s\n", source.empty() ? "a file" : source.c_str(), what.c_str());
      std::abort();
    }
  }
}

}  // namespace prep::fuzz
