// Feeds each input to parse_gltf as the bytes of a .gltf or .glb file (chosen by the GLB magic, as
// read_gltf does), with no folder for external buffers: tinygltf's parsing plus our accessor, node-tree,
// skin and animation checks. Failure: anything but an InputError naming "fuzz.glb" (a crash, a sanitizer
// report, a leak, an escaping exception, an input slower than the run's -timeout).
#include "engine/interop/gltf_io.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string source = "fuzz.glb";
  prep::fuzz::expect_clean(source, [&] { (void)prep::parse_gltf(prep::fuzz::bytes(data, size), source); });
  return 0;
}
