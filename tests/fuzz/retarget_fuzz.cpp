// Feeds each input to parse_joint_map as the text of a retarget joint map, then builds a Retargeter with
// the map from the build's humanoid (fuzz_support.h: data_dir) onto its taller variant and retargets one frame. Failure:
// anything but an InputError naming "fuzz.json" or the std::invalid_argument the Retargeter documents for
// a map that leaves the roots unmapped (a crash, a sanitizer report, a leak, another exception, an input
// slower than the run's -timeout).
#include <stdexcept>

#include "engine/interop/retarget.h"
#include "engine/motion/bvh.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const prep::Clip source_clip = prep::read_bvh(prep::fuzz::data_dir() + "/humanoid.bvh");
  static const prep::Clip target_clip = prep::read_bvh(prep::fuzz::data_dir() + "/humanoid_tall.bvh");
  const std::string source = "fuzz.json";
  prep::fuzz::expect_clean(source, [&] {
    const prep::JointMap map = prep::parse_joint_map(std::string(prep::fuzz::bytes(data, size)), source);
    try {
      const prep::Retargeter retargeter(source_clip.skeleton, target_clip.skeleton, map);
      prep::Pose pose(target_clip.skeleton->size());
      retargeter.retarget(source_clip.frames[1], pose);
    } catch (const std::invalid_argument&) {
      // the documented refusal of a map that does not join the two roots
    }
  });
  return 0;
}
