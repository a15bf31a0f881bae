#include <doctest/doctest.h>

#include <cmath>
#include <set>
#include <stdexcept>

#include "engine/control/state.h"

using namespace prep;

namespace {
float deg(float d) { return d * 3.14159265358979f / 180.0f; }
}  // namespace

TEST_CASE("the paper's configuration has 19,200 states (4 core motions x 6 alpha levels x 5 x 8 x 5 x 4)") {
  const Params p;
  const StateSpace s(p.quantization, 4);  // the built-in set's own core motions: walk, two turns, slow walk
  CHECK(s.size() == 19200);
  CHECK(s.alpha_levels() == 6);
  CHECK(s.alpha_of(s.top_alpha_level()) == doctest::Approx(1.0));
}

TEST_CASE("distance bins: 40 cm steps, edges belong to the upper bin, far distances clamp into the last") {
  const StateSpace s(QuantizationParams{}, 4);
  CHECK(s.d_g_bin(0.0f) == 0);
  CHECK(s.d_g_bin(0.399f) == 0);
  CHECK(s.d_g_bin(0.401f) == 1);
  CHECK(s.d_g_bin(0.799f) == 1);
  CHECK(s.d_g_bin(0.801f) == 2);
  CHECK(s.d_g_bin(1.599f) == 3);
  CHECK(s.d_g_bin(1.601f) == 4);
  CHECK(s.d_g_bin(1.999f) == 4);
  CHECK(s.d_g_bin(2.5f) == 4);
  CHECK(s.d_g_bin(1000.0f) == 4);
  CHECK(s.d_i_bin(-0.1f) == 0);
  CHECK(s.d_i_bin(std::nanf("")) == 0);
}

TEST_CASE("goal bearing bins: 45 degrees x 8 centred on straight ahead, counter-clockwise") {
  const StateSpace s(QuantizationParams{}, 4);
  CHECK(s.theta_g_bin(0.0f) == 0);
  CHECK(s.theta_g_bin(deg(22.4f)) == 0);
  CHECK(s.theta_g_bin(deg(-22.4f)) == 0);
  CHECK(s.theta_g_bin(deg(22.6f)) == 1);   // to the left
  CHECK(s.theta_g_bin(deg(-22.6f)) == 7);  // to the right wraps to the last bin
  CHECK(s.theta_g_bin(deg(67.4f)) == 1);
  CHECK(s.theta_g_bin(deg(67.6f)) == 2);
  CHECK(s.theta_g_bin(deg(157.6f)) == 4);
  CHECK(s.theta_g_bin(deg(180.0f)) == 4);
  CHECK(s.theta_g_bin(deg(-180.0f)) == 4);
  CHECK(s.theta_g_bin(deg(-157.4f)) == 5);
}

TEST_CASE("source bearing bins: 90 degrees x 4 (ahead, left, behind, right)") {
  const StateSpace s(QuantizationParams{}, 4);
  CHECK(s.theta_i_bin(deg(44.9f)) == 0);
  CHECK(s.theta_i_bin(deg(-44.9f)) == 0);
  CHECK(s.theta_i_bin(deg(45.1f)) == 1);
  CHECK(s.theta_i_bin(deg(134.9f)) == 1);
  CHECK(s.theta_i_bin(deg(135.1f)) == 2);
  CHECK(s.theta_i_bin(deg(-135.1f)) == 2);
  CHECK(s.theta_i_bin(deg(-134.9f)) == 3);
  CHECK(s.theta_i_bin(deg(-45.1f)) == 3);
}

TEST_CASE("alpha goes to the nearest level and clamps") {
  const StateSpace s(QuantizationParams{}, 4);
  CHECK(s.alpha_level(0.0f) == 0);
  CHECK(s.alpha_level(0.29f) == 1);
  CHECK(s.alpha_level(0.31f) == 2);
  CHECK(s.alpha_level(1.0f) == 5);
  CHECK(s.alpha_level(1.3f) == 5);
  CHECK(s.alpha_level(-0.2f) == 0);
}

TEST_CASE("state indices are a bijection with the bins") {
  QuantizationParams q;
  q.d_g_bins = 3;  // smaller, so the exhaustive check is quick
  const StateSpace s(q, 4);
  std::set<int> seen;
  for (int i = 0; i < s.size(); ++i) {
    const StateBins b = s.decode(i);
    CHECK_EQ(s.index(b), i);
    seen.insert(i);
  }
  CHECK(static_cast<int>(seen.size()) == s.size());
  const StateBins last = s.decode(s.size() - 1);
  CHECK(last.alpha == 5);
  CHECK(last.theta_i == 3);
}

TEST_CASE("quantization that cannot hold the paper's forcing of alpha to 1 is refused") {
  QuantizationParams q;
  q.alpha_levels = 5;  // Table I's printed count with 0.2 steps tops out at 0.8
  CHECK_THROWS_AS(StateSpace(q, 4), std::invalid_argument);
  QuantizationParams r;
  r.theta_g_bins = 7;
  CHECK_THROWS_AS(StateSpace(r, 4), std::invalid_argument);
  QuantizationParams finer;
  finer.alpha_step = 0.1f;
  finer.alpha_levels = 11;
  finer.d_step = 0.2f;
  finer.d_g_bins = 10;
  CHECK(StateSpace(finer, 4).size() == 11 * 4 * 10 * 8 * 5 * 4);
}
