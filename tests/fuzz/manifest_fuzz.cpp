// Feeds each input to parse_motion_set as the text of a motion-set manifest placed in the folder of the
// build's humanoids (fuzz_support.h: data_dir), so that "folder": "." finds the two small humanoid BVH files
// there: the manifest's fields, frame ranges, loops, T_t, floors, steering and the retargeting of the
// taller performer. Failure: anything but an InputError naming a file (the manifest, or a BVH it lists: a
// crash, a sanitizer report, a leak, an escaping exception, an input slower than the run's -timeout).
#include "engine/motion/motion_set.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string manifest = prep::fuzz::data_dir() + "/manifest.json";
  static const prep::Params params;
  prep::fuzz::expect_clean("", [&] {
    (void)prep::parse_motion_set(std::string(prep::fuzz::bytes(data, size)), manifest, params);
  });
  return 0;
}
