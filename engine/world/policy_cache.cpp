#include "engine/world/policy_cache.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "engine/control/action_effects.h"
#include "engine/control/environment.h"
#include "engine/util/error.h"
#include "engine/util/files.h"

namespace prep {

namespace {

// Next(m) among the core motions, from the graph (node i is clip i). A core motion with no successor but
// itself in the graph would strand the controller, so then every core motion may follow it (the core nodes
// of a hierarchical motion graph are meant to be joined, Sec. 4.1; the world cross-fades where the graph
// has no edge, world.cpp control()).
std::vector<std::vector<int>> core_next(const MotionSet& set, const MotionGraph& graph, const std::vector<const MotionClip*>& core) {
  std::vector<int> node_of;
  for (const MotionClip* c : core) node_of.push_back(static_cast<int>(c - set.clips.data()));
  std::vector<std::vector<int>> next(core.size());
  for (size_t m = 0; m < core.size(); ++m) {
    for (size_t n = 0; n < core.size(); ++n) {
      const auto& succ = graph.next(node_of[m]);
      if (std::find(succ.begin(), succ.end(), node_of[n]) != succ.end()) next[m].push_back(static_cast<int>(n));
    }
    const bool only_itself = next[m].empty() || (next[m].size() == 1 && next[m][0] == static_cast<int>(m));
    if (only_itself) {
      next[m].clear();
      for (size_t n = 0; n < core.size(); ++n) next[m].push_back(static_cast<int>(n));
    }
  }
  return next;
}

bool same_table(const ActionTable& a, const ActionTable& b) {
  if (a.motions != b.motions || a.alpha_levels != b.alpha_levels || a.motion_names != b.motion_names ||
      !(a.curve == b.curve) || a.effects.size() != b.effects.size())
    return false;
  for (size_t i = 0; i < a.effects.size(); ++i) {
    const ActionEffect &x = a.effects[i], &y = b.effects[i];
    // The policy file stores floats exactly; allow for nothing but rounding of recomputation.
    if (std::abs(x.forward - y.forward) > 1e-5f || std::abs(x.left - y.left) > 1e-5f || std::abs(x.turn - y.turn) > 1e-5f ||
        std::abs(x.duration - y.duration) > 1e-5f)
      return false;
  }
  return true;
}

}  // namespace

Policy train_policy(const MotionSet& set, const MotionGraph& graph, const Params& params, const TrainingOptions& options) {
  const ActionTable table = tabulate_action_effects(set, params);
  const std::vector<const MotionClip*> core = core_clips(set, params.quantization);
  const StateSpace states(params.quantization, table.motions);
  const ActionSpace actions(table.motions, table.alpha_levels, core_next(set, graph, core), action_levels(params.quantization));
  const Environment env(states, actions, table, params.reward);
  const TrainingResult r = train_sarsa(env, params.sarsa, options);

  return make_policy(params, table, actions, r);
}

std::string default_policy_cache_dir() {
  if (const char* d = std::getenv("PREP_CACHE_DIR"); d && *d) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return std::string(d) + "/prep";
  if (const char* d = std::getenv("HOME"); d && *d) return std::string(d) + "/.cache/prep";
  return source_dir() + "/build/cache";
}

std::uint64_t action_table_fingerprint(const ActionTable& table) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a
  auto add = [&h](const void* data, size_t size) {
    for (size_t i = 0; i < size; ++i) {
      h ^= static_cast<const unsigned char*>(data)[i];
      h *= 1099511628211ull;
    }
  };
  for (const std::string& name : table.motion_names) add(name.c_str(), name.size() + 1);
  for (const ActionEffect& e : table.effects) {
    // Rounded to 0.1 mm and 0.001 degree, well above recomputation's rounding, so that the same clips
    // always name the same file.
    const std::int64_t q[] = {std::llround(e.forward * 1e4), std::llround(e.left * 1e4),
                              std::llround(e.turn * 57.2957795 * 1e3), std::llround(e.duration * 1e4)};
    add(q, sizeof q);
  }
  return h;
}

std::string policy_cache_path(const std::string& cache_dir, const MotionSet& set, const Params& params) {
  char hash[40];
  std::snprintf(hash, sizeof hash, "%016llx-%016llx", static_cast<unsigned long long>(policy_params_hash(params)),
                static_cast<unsigned long long>(action_table_fingerprint(tabulate_action_effects(set, params))));
  std::string name = set.name.empty() ? "set" : set.name;
  for (char& c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_')) c = '_';
  return cache_dir + "/policy-" + name + "-" + hash + ".bin";
}

std::shared_ptr<const Policy> load_cached_policy(const MotionSet& set, const std::string& cache_dir, const Params& params) {
  const std::string path = policy_cache_path(cache_dir, set, params);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return nullptr;
  try {
    auto p = std::make_shared<Policy>(load_policy(path, params));
    if (!same_table(p->table, tabulate_action_effects(set, params))) return nullptr;
    return p;
  } catch (const InputError&) {
    return nullptr;  // stale or damaged: retrain and overwrite
  }
}

std::shared_ptr<const Policy> load_or_train_policy(const MotionSet& set, const MotionGraph& graph, const Params& params,
                                                   const std::string& cache_dir, const TrainingOptions& options,
                                                   bool* trained) {
  if (auto cached = load_cached_policy(set, cache_dir, params)) {
    if (trained) *trained = false;
    return cached;
  }
  auto p = std::make_shared<Policy>(train_policy(set, graph, params, options));
  if (trained) *trained = true;
  try {
    std::error_code ec;
    std::filesystem::create_directories(cache_dir, ec);
    save_policy(*p, policy_cache_path(cache_dir, set, params));
  } catch (const std::exception&) {
    // A read-only cache costs a retraining next time, nothing more.
  }
  return p;
}

namespace {
struct Cancelled {};  // thrown out of training by a cancelled PolicyJob (not a std::exception: never an error)
}  // namespace

PolicyJob::PolicyJob(const MotionSet& set, const MotionGraph& graph, const Params& params, std::string cache_dir)
    : max_steps_(std::max<std::int64_t>(1, params.sarsa.max_steps)), status_("loading") {
  thread_ = std::thread([this, &set, &graph, params, cache_dir = std::move(cache_dir)] {
    try {
      TrainingOptions options;
      options.progress = [this](const TrainingProgress& p) {
        // Training has no stop flag of its own: leaving from the progress callback, which runs on the
        // training thread between rounds, unwinds train_sarsa cleanly (its worker pool joins).
        if (cancelled_.load()) throw Cancelled{};
        steps_.store(p.steps);
        std::lock_guard<std::mutex> lock(mutex_);
        status_ = "training: " + std::to_string(p.steps) + " steps";
      };
      bool trained = false;
      auto p = load_or_train_policy(set, graph, params, cache_dir, options, &trained);
      std::lock_guard<std::mutex> lock(mutex_);
      policy_ = std::move(p);
      trained_.store(trained);
      status_ = trained ? "trained" : "cached";
    } catch (const Cancelled&) {
      std::lock_guard<std::mutex> lock(mutex_);
      status_ = "cancelled";
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();
      status_ = e.what();
    }
    done_.store(true);
  });
}

PolicyJob::~PolicyJob() {
  if (thread_.joinable()) thread_.join();
}

float PolicyJob::progress() const {
  if (done_.load()) return 1.0f;
  return std::min(1.0f, static_cast<float>(steps_.load()) / static_cast<float>(max_steps_));
}

std::string PolicyJob::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

std::shared_ptr<const Policy> PolicyJob::result() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (error_) std::rethrow_exception(error_);
  return policy_;
}

}  // namespace prep
