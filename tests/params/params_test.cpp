#include <doctest/doctest.h>

#include "engine/params/params.h"
#include "engine/util/error.h"
#include "tests/support/paths.h"

using namespace prep;

TEST_CASE("params defaults are the paper's") {
  Params p;
  CHECK(p.balance.w_b == 2.0f);
  CHECK(p.balance.w_s == 1.0f);
  CHECK(p.balance.w_m == 0.25f);
  CHECK(p.balance.max_steps == 10);
  CHECK(p.balance.alpha_threshold == doctest::Approx(0.3));
  CHECK(p.sarsa.learning_rate == doctest::Approx(0.7));
  CHECK(p.sarsa.discount == doctest::Approx(0.3));
  CHECK(p.sarsa.epsilon == doctest::Approx(0.1));
  CHECK(p.reward.w_theta == doctest::Approx(0.1));
  CHECK(p.reward.w_d == doctest::Approx(0.3));
  CHECK(p.reward.w_alpha == doctest::Approx(0.6));
}

TEST_CASE("params round-trip through JSON and keep unspecified defaults") {
  Params p;
  p.balance.w_b = 3.5f;
  p.blend.C_override["lShldr"] = 0.8f;
  p.sarsa.seed = 42;
  const Params q = params_from_json(params_to_json(p), "mem");
  CHECK(q.balance.w_b == 3.5f);
  CHECK(q.blend.C_override.at("lShldr") == 0.8f);
  CHECK(q.sarsa.seed == 42);
  const Params partial = params_from_json(R"({"balance": {"w_s": 0.5}})", "mem");
  CHECK(partial.balance.w_s == 0.5f);
  CHECK(partial.balance.w_b == 2.0f);
}

TEST_CASE("bad params files are refused with the file and field named") {
  CHECK_THROWS_WITH_AS(params_from_json("{\"balance\": {\"w_q\": 1}}", "p.json"),
                       doctest::Contains("p.json: unknown field 'balance.w_q'"), InputError);
  CHECK_THROWS_WITH_AS(params_from_json("{\"balance\": {\"w_b\": \"x\"}}", "p.json"),
                       doctest::Contains("'balance.w_b' has the wrong type"), InputError);
  CHECK_THROWS_WITH_AS(params_from_json("{\"balance\": ", "p.json"), doctest::Contains("p.json: invalid JSON"),
                       InputError);
  CHECK_THROWS_AS(params_from_json("[1,2]", "p.json"), InputError);
}

TEST_CASE("numbers a field's type cannot hold are refused with the file and field named") {
  // Inputs of the Params fuzz target's corpus (tests/fuzz/corpus/params): nlohmann's conversion would have
  // turned each silently into infinity, a wrapped or truncated integer, or undefined behaviour.
  const std::string corpus = test::repo() + "/tests/fuzz/corpus/params/";
  CHECK_THROWS_WITH_AS(load_params(corpus + "float_overflow.json"),
                       doctest::Contains("float_overflow.json: 'reward.goal_radius' is not a finite number within float range: 1e+39"),
                       InputError);
  CHECK_THROWS_WITH_AS(load_params(corpus + "int_overflow.json"),
                       doctest::Contains("int_overflow.json: 'quantization.d_g_bins' is out of range for this field (-2147483648 to 2147483647): 2147483648"),
                       InputError);
  CHECK_THROWS_WITH_AS(load_params(corpus + "int_fraction.json"),
                       doctest::Contains("int_fraction.json: 'quantization.alpha_levels' must be an integer: 2.5"), InputError);
  CHECK_THROWS_WITH_AS(load_params(corpus + "unsigned_negative.json"),
                       doctest::Contains("unsigned_negative.json: 'sarsa.seed' is out of range for this field"), InputError);
  CHECK_THROWS_WITH_AS(load_params(corpus + "float_in_integer_field.json"),
                       doctest::Contains("float_in_integer_field.json: 'sarsa.seed' must be an integer"), InputError);
  CHECK_THROWS_WITH_AS(load_params(corpus + "override_overflow.json"),
                       doctest::Contains("override_overflow.json: 'blend.C_override' has 'Hips', which is not a finite number"),
                       InputError);
  CHECK_THROWS_WITH_AS(load_params(corpus + "number_overflow.json"),
                       doctest::Contains("number_overflow.json: invalid JSON: [json.exception.out_of_range.406] number overflow"),
                       InputError);
  // The limits are the types': their extremes still load.
  const Params edge = params_from_json(R"({"quantization": {"d_g_bins": 2147483647}, "sarsa": {"seed": 18446744073709551615},
                                          "reward": {"goal_radius": 3.4e38}})", "edge.json");
  CHECK(edge.quantization.d_g_bins == 2147483647);
  CHECK(edge.sarsa.seed == 18446744073709551615ull);
  CHECK(edge.reward.goal_radius == doctest::Approx(3.4e38));
}

TEST_CASE("the policy hash follows what a policy depends on") {
  Params a, b;
  CHECK(policy_params_hash(a) == policy_params_hash(b));
  b.sarsa.threads = 7;
  CHECK(policy_params_hash(a) == policy_params_hash(b));
  b.blend.C_lower = 0.7f;
  CHECK(policy_params_hash(a) != policy_params_hash(b));
  Params c;
  c.balance.w_b = 9.0f;  // balance does not change the stride
  CHECK(policy_params_hash(a) == policy_params_hash(c));
}
