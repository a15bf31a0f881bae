// Feeds each input to params_from_json as the text of a Params file, then writes the result with
// params_to_json and reads that back. Failure: anything but an InputError naming "fuzz.json" (a crash, a
// sanitizer report, a leak, an escaping exception, an input slower than the run's -timeout), or Params
// whose own JSON does not read back to the same JSON.
#include <cstdlib>

#include "engine/params/params.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string source = "fuzz.json";
  prep::fuzz::expect_clean(source, [&] {
    const prep::Params params = prep::params_from_json(std::string(prep::fuzz::bytes(data, size)), source);
    const std::string json = prep::params_to_json(params);
    if (prep::params_to_json(prep::params_from_json(json, "written.json")) != json) std::abort();
  });
  return 0;
}
