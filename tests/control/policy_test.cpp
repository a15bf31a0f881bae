#include <doctest/doctest.h>

#include <filesystem>

#include "engine/control/policy.h"
#include "engine/util/error.h"
#include "engine/util/files.h"
#include "hand_made.h"
#include "tests/support/paths.h"

using namespace prep;

namespace {

Policy sample_policy(const Params& params) {
  const auto world = test::hand_made_world(params);
  const StateSpace states(params.quantization, world.table.motions);
  const ActionSpace actions(states.motions(), states.alpha_levels());
  Policy p;
  p.params_hash = policy_params_hash(params);
  p.quantization = params.quantization;
  p.target = "kick";
  p.table = world.table;
  for (int m = 0; m < states.motions(); ++m) p.allowed_masks.push_back(actions.allowed_mask(m));
  p.states = states.size();
  p.actions = actions.size();
  p.q.resize(static_cast<size_t>(p.states) * static_cast<size_t>(p.actions));
  for (size_t i = 0; i < p.q.size(); ++i) p.q[i] = 0.001f * static_cast<float>(i % 997);
  p.steps = 1234;
  p.seed = 5;
  p.threads = 2;
  p.converged = true;
  return p;
}

}  // namespace

TEST_CASE("a policy survives a round trip through its file") {
  const Params params = test::small_params();
  const Policy p = sample_policy(params);
  std::filesystem::create_directories(test::tmp_dir());
  const std::string path = test::tmp_dir() + "/control_policy_roundtrip.bin";
  save_policy(p, path);
  const Policy q = load_policy(path, params);
  CHECK(q.q == p.q);
  CHECK(q.target == "kick");
  CHECK(q.table.motion_names == p.table.motion_names);
  CHECK(q.table.at(3).forward == p.table.at(3).forward);
  CHECK(q.table.curve == p.table.curve);
  CHECK(q.table.motion_roles == p.table.motion_roles);
  CHECK(q.quantization.core_roles == p.table.motion_roles);  // the file keeps each core clip's role
  CHECK(q.steps == 1234);
  CHECK(q.converged);
  CHECK(serialize_policy(q) == serialize_policy(p));
}

TEST_CASE("a truncated policy file is refused, naming the file") {
  const Params params = test::small_params();
  const std::string bytes = serialize_policy(sample_policy(params));
  for (size_t keep : {size_t{0}, size_t{7}, size_t{20}, bytes.size() / 2, bytes.size() - 1}) {
    CAPTURE(keep);
    CHECK_THROWS_AS(parse_policy(bytes.substr(0, keep), "p.bin", params), InputError);
  }
  CHECK_THROWS_WITH_AS(parse_policy(bytes.substr(0, bytes.size() - 100), "p.bin", params),
                       doctest::Contains("p.bin: truncated"), InputError);
}

TEST_CASE("a policy whose bin counts multiply past 64 bits is refused, naming the file") {
  // Two distance bin counts of 2^31 - 1 each: the state count overflowed a signed 64-bit product before the
  // limit was checked (UBSan, found by the policy fuzz target; the file is in its corpus, checksum intact).
  CHECK_THROWS_WITH_AS(load_policy(test::repo() + "/tests/fuzz/corpus/policy/state_count_overflow.policy", Params{}),
                       doctest::Contains("state_count_overflow.policy: corrupt quantization: quantization: too many states (more than 2^30"),
                       InputError);
}

TEST_CASE("a bit flipped anywhere in a policy file is caught") {
  const Params params = test::small_params();
  const std::string bytes = serialize_policy(sample_policy(params));
  for (size_t at : {size_t{30}, size_t{100}, bytes.size() / 2, bytes.size() - 20, bytes.size() - 3}) {
    std::string damaged = bytes;
    damaged[at] = static_cast<char>(damaged[at] ^ 0x10);
    CAPTURE(at);
    CHECK_THROWS_WITH_AS(parse_policy(damaged, "p.bin", params), doctest::Contains("p.bin: corrupt"), InputError);
  }
  std::string bad_magic = bytes;
  bad_magic[0] = 'X';
  CHECK_THROWS_WITH_AS(parse_policy(bad_magic, "p.bin", params), doctest::Contains("not a prep policy"), InputError);
}

TEST_CASE("a policy trained for another configuration is refused") {
  const Params params = test::small_params();
  const std::string bytes = serialize_policy(sample_policy(params));
  Params other = params;
  other.reward.w_alpha = 0.5f;
  CHECK_THROWS_WITH_AS(parse_policy(bytes, "p.bin", other), doctest::Contains("p.bin: trained for another configuration"),
                       InputError);
  Params stride = params;
  stride.blend.C_lower = 0.8f;  // another lower-body curve: another stride (Sec. 8)
  CHECK_THROWS_AS(parse_policy(bytes, "p.bin", stride), InputError);
  Params seed = params;
  seed.sarsa.seed = 99;  // another seed trains the same problem
  CHECK_NOTHROW(parse_policy(bytes, "p.bin", seed));
}
