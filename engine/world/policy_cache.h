// The controller's policy for a motion set: trained with SARSA (Sec. 6.3) on the set's core locomotion
// (action effects from its clips, Next(m) from the motion graph), cached on disk, and trained in a
// background thread with progress so that a front end never freezes.
//
// Cache: one file per motion set and configuration in the cache folder:
// policy-<set name>-<policy_params_hash>-<action_table_fingerprint>.bin (hashes as 16 hex digits). The
// fingerprint of the set's core motions keeps two sets of the same name (two folders scanned into
// "my_set") apart, so each trains once. A cached file is used only if it parses for these Params (policy.h
// checks the hash, version and checksum) and its action table equals the one the set gives now;
// otherwise it is retrained and rewritten.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "engine/control/action_effects.h"
#include "engine/control/policy.h"
#include "engine/control/sarsa.h"
#include "engine/graph/motion_graph.h"
#include "engine/motion/motion_set.h"
#include "engine/params/params.h"

namespace prep {

// Trains a policy for the set's core motions (QuantizationParams::core_roles). Throws InputError naming the
// set when a core role has no cyclic clip.
Policy train_policy(const MotionSet& set, const MotionGraph& graph, const Params& params,
                    const TrainingOptions& options = {});

// $PREP_CACHE_DIR, else $XDG_CACHE_HOME/prep, else $HOME/.cache/prep, else <repository>/build/cache.
std::string default_policy_cache_dir();
// A hash of the core motions' names and what each action does (to 0.1 mm and 0.001 degree).
std::uint64_t action_table_fingerprint(const ActionTable& table);
std::string policy_cache_path(const std::string& cache_dir, const MotionSet& set, const Params& params);

// The cached policy if it is valid for this set and these Params, else nullptr.
std::shared_ptr<const Policy> load_cached_policy(const MotionSet& set, const std::string& cache_dir, const Params& params);

// Loads the cached policy or trains one and caches it (the cache folder is created; a cache that cannot
// be written is not an error). `trained` tells which happened.
std::shared_ptr<const Policy> load_or_train_policy(const MotionSet& set, const MotionGraph& graph, const Params& params,
                                                   const std::string& cache_dir, const TrainingOptions& options = {},
                                                   bool* trained = nullptr);

// load_or_train_policy in a background thread. The set and graph must outlive it; the destructor waits
// for the thread (training cannot be interrupted midway; its length is bounded by SarsaParams::max_steps).
class PolicyJob {
 public:
  PolicyJob(const MotionSet& set, const MotionGraph& graph, const Params& params, std::string cache_dir);
  ~PolicyJob();
  PolicyJob(const PolicyJob&) = delete;
  PolicyJob& operator=(const PolicyJob&) = delete;

  bool done() const { return done_.load(); }
  // 0..1: training steps over SarsaParams::max_steps (training usually converges before 1); 1 when done.
  float progress() const;
  std::string status() const;  // "loading", "training: N steps", "cached", "trained", or the error
  // The policy once done; rethrows the error if it failed; nullptr while running.
  std::shared_ptr<const Policy> result() const;
  bool trained() const { return trained_.load(); }
  // Asks the job to stop at the end of the current training round (within about a second): it then
  // finishes with status "cancelled" and no policy (result() is nullptr), and nothing is cached. A job
  // that has already finished is not affected. The destructor still waits for the thread.
  void cancel() { cancelled_.store(true); }
  bool cancelled() const { return cancelled_.load(); }

 private:
  std::atomic<bool> done_{false};
  std::atomic<bool> cancelled_{false};
  std::atomic<bool> trained_{false};
  std::atomic<std::int64_t> steps_{0};
  std::int64_t max_steps_ = 1;
  mutable std::mutex mutex_;
  std::string status_;
  std::shared_ptr<const Policy> policy_;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace prep
