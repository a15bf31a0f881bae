// Feeds each input to parse_scenario as the text of a scenario file (characters, objects, goal, the
// motions and params paths, which are only resolved, not loaded). Failure: anything but an InputError
// naming "fuzz/scenario.json" (a crash, a sanitizer report, a leak, an escaping exception, an input slower
// than the run's -timeout), or a scenario that scenario_json does not write as text it reads back.
#include "engine/world/scenario.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string source = "fuzz/scenario.json";
  prep::fuzz::expect_clean(source, [&] {
    const prep::Scenario scenario = prep::parse_scenario(std::string(prep::fuzz::bytes(data, size)), source);
    const prep::Scenario again = prep::parse_scenario(prep::scenario_json(scenario), "written.json");
    if (again.characters.size() != scenario.characters.size() || again.objects.size() != scenario.objects.size() ||
        again.goal.size() != scenario.goal.size())
      std::abort();
  });
  return 0;
}
