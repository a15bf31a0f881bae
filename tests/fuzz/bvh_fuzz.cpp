// Feeds each input to parse_bvh as the text of a BVH file, then writes the clip it read back out with
// format_bvh and reads that again. Failure: anything but an InputError naming "fuzz.bvh" (a crash, a
// sanitizer report, a leak, an escaping exception, an input slower than the run's -timeout), or a clip
// that its own BVH text does not read back with the same joints and frames.
#include <cstdlib>
#include <string>
#include <vector>

#include "engine/motion/bvh.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string source = "fuzz.bvh";
  prep::fuzz::expect_clean(source, [&] {
    std::vector<std::string> warnings;
    prep::BvhReadOptions options;
    options.warnings = &warnings;
    const prep::Clip clip = prep::parse_bvh(std::string(prep::fuzz::bytes(data, size)), source, options);
    const prep::Clip again = prep::parse_bvh(prep::format_bvh(clip), "written.bvh");
    if (again.skeleton->size() != clip.skeleton->size() || again.frame_count() != clip.frame_count()) std::abort();
  });
  return 0;
}
