// A trained controller on disk: a binary file holding what the Q table means and the table itself.
//
// Layout (little-endian; strings are a u32 length and bytes):
//   8 bytes  magic "PREPPOL\x1a"
//   u32      format version (kPolicyFormatVersion)
//   u64      total file size in bytes (a shorter file is reported as truncated)
//   u64      policy_params_hash(params) of the training configuration
//   quantization: f32 d_step, i32 d_g_bins, i32 d_i_bins, f32 theta_g_step_deg, i32 theta_g_bins,
//                 f32 theta_i_step_deg, i32 theta_i_bins, f32 alpha_step, i32 alpha_levels
//   string   target motion role the controller prepares for ("" if none named)
//   root curve: f32 C, f32 c, u8 linear (Eq. 1 of the root, which shapes the stride, Sec. 8)
//   u32      motions; per motion: string clip name, string role, u64 mask of the actions allowed after it
//   per action (motion-major, then alpha level): f32 forward, left, turn, duration (the action table)
//   training record: u64 steps, u64 episodes, u8 converged, u64 seed, u32 threads
//   u32 states, u32 actions, then states x actions f32 Q values (row per state)
//   u64      FNV-1a 64 checksum of every byte before it
// Written atomically (write_file_atomic). Reading refuses, with an InputError naming the file, anything
// truncated, corrupt (checksum), of another format version, or trained for another configuration.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/control/action_effects.h"
#include "engine/control/actions.h"
#include "engine/control/sarsa.h"
#include "engine/control/state.h"
#include "engine/params/params.h"

namespace prep {

// 3: actions of a gait cycle measured along the travel, the goal reached anywhere along an action, starts
// out to far_start_range (the same bytes, another training problem: older files are refused and caches
// retrain).
constexpr std::uint32_t kPolicyFormatVersion = 3;

struct Policy {
  std::uint64_t params_hash = 0;
  QuantizationParams quantization;  // core_roles are the table's motion roles
  std::string target;
  ActionTable table;
  std::vector<std::uint64_t> allowed_masks;  // per last motion (Next(m))
  std::int64_t steps = 0, episodes = 0;
  bool converged = false;
  std::uint64_t seed = 0;
  int threads = 0;
  int states = 0, actions = 0;
  std::vector<float> q;

  StateSpace state_space() const { return StateSpace(quantization, table.motions); }
  ActionSpace action_space() const;
  const float* row(int state) const { return q.data() + static_cast<size_t>(state) * static_cast<size_t>(actions); }
};

// The policy of a training run: the configuration's hash and quantization, the table, Next(m) and Q.
Policy make_policy(const Params& params, const ActionTable& table, const ActionSpace& actions, const TrainingResult& result,
                   const std::string& target = "");

std::uint64_t fnv1a64(std::string_view bytes);

std::string serialize_policy(const Policy& policy);
void save_policy(const Policy& policy, const std::string& path);

// Parses and checks a policy. `expected` is the configuration the caller runs with: a policy whose
// params hash differs is refused (it was trained for other quantization, rewards or stride).
Policy parse_policy(std::string_view bytes, const std::string& source_name, const Params& expected);
Policy load_policy(const std::string& path, const Params& expected);

}  // namespace prep
