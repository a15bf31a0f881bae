#include "engine/control/sarsa.h"

#include <chrono>
#include <ctime>
#include <condition_variable>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace prep {
namespace {

// One worker's replica and counters.
struct Worker {
  Rng rng;
  std::vector<float> q;
  std::vector<std::uint64_t> tried;     // per state, bit a = action a has been taken there
  std::vector<int> touched;             // Q indices changed this round
  std::vector<std::uint8_t> touched_flag;
  std::int64_t steps = 0, episodes = 0, explored = 0;  // explored: untried actions taken
  int quota = 0;                        // episodes this round
  // The next episode's exploring start, drawn one episode ahead so that its Q row and tried flags (a
  // random state: a cache miss) are fetched while the current episode runs. Episodes last only a few
  // actions of a gait cycle, so these misses would otherwise cost as much as the steps.
  Situation next_start;
  int next_state = -1;
};

class Sarsa {
 public:
  Sarsa(const Environment& env, const SarsaParams& p)
      : env_(env),
        actions_(env.actions().size()),
        lr_(p.learning_rate),
        gamma_(p.discount),
        epsilon_(p.epsilon),
        source_at_goal_(p.source_at_goal_fraction),
        far_start_range_(p.far_start_range),
        max_episode_steps_(p.max_episode_steps),
        goal_value_(env.reward().max_reward() / (1.0f - p.discount)) {}  // the absorbing goal (reward.h)

  void run(Worker& w) const {
    for (int e = 0; e < w.quota; ++e) episode(w);
  }

 private:
  int choose(Worker& w, int state, int last_motion, bool& exploring) const {
    const std::uint64_t allowed = env_.actions().allowed_mask(last_motion);
    std::uint64_t untried = allowed & ~w.tried[static_cast<size_t>(state)];
    if (untried != 0) {  // exploring: an action never taken here first (Sec. 6.4)
      ++w.explored;
      exploring = true;
      int k = w.rng.below(__builtin_popcountll(untried));
      while (k-- > 0) untried &= untried - 1;
      return __builtin_ctzll(untried);
    }
    if (w.rng.uniform() < epsilon_) {  // epsilon-greedy
      exploring = true;
      const std::vector<int>& list = env_.actions().allowed(last_motion);
      return list[static_cast<size_t>(w.rng.below(static_cast<int>(list.size())))];
    }
    return greedy_action(env_, w.q.data() + static_cast<size_t>(state) * actions_, last_motion);
  }

  void update(Worker& w, int state, int action, float target) const {
    const size_t idx = static_cast<size_t>(state) * actions_ + static_cast<size_t>(action);
    const float delta = lr_ * (target - w.q[idx]);  // Eq. 19
    w.q[idx] += delta;
    w.tried[static_cast<size_t>(state)] |= std::uint64_t{1} << action;
    if (!w.touched_flag[idx]) {
      w.touched_flag[idx] = 1;
      w.touched.push_back(static_cast<int>(idx));
    }
  }

  void draw_start(Worker& w) const {
    env_.exploring_start(w.rng, source_at_goal_, far_start_range_, w.next_start);
    w.next_state = env_.quantize(w.next_start);
    const size_t row = static_cast<size_t>(w.next_state) * actions_;
    __builtin_prefetch(w.q.data() + row);
    __builtin_prefetch(w.q.data() + row + actions_ - 1);
    __builtin_prefetch(w.tried.data() + w.next_state);
    __builtin_prefetch(w.touched_flag.data() + row);
  }

  void episode(Worker& w) const {
    if (w.next_state < 0) draw_start(w);
    Situation s = w.next_start;
    int state = w.next_state;
    draw_start(w);
    bool exploring = false;
    int action = choose(w, state, s.motion, exploring);
    for (int t = 0; t < max_episode_steps_; ++t) {
      const StepOutcome out = env_.step(s, action);
      ++w.steps;
      if (out.at_goal) {
        update(w, state, action, out.reward + gamma_ * goal_value_);
        break;
      }
      const int next_state = env_.quantize(s);
      bool exploring = false;
      const int next_action = choose(w, next_state, s.motion, exploring);
      const float* next_row = w.q.data() + static_cast<size_t>(next_state) * actions_;
      // Eq. 19 bootstraps on the action taken next; an exploratory one (untried, or the epsilon draw) is
      // not a sample of what the policy does there, so its place is taken by the greedy action's value.
      const int bootstrap = exploring ? greedy_action(env_, next_row, s.motion) : next_action;
      update(w, state, action, out.reward + gamma_ * next_row[bootstrap]);
      state = next_state;
      action = next_action;
    }
    ++w.episodes;
  }

  const Environment& env_;
  size_t actions_;
  float lr_, gamma_, epsilon_, source_at_goal_, far_start_range_;
  int max_episode_steps_;
  float goal_value_;
};

// Runs a function on worker threads 1..T-1 once per round while the caller runs worker 0; a round ends
// when all are done. The threads persist across rounds.
class RoundPool {
 public:
  RoundPool(int threads, std::function<void(int)> work) : work_(std::move(work)) {
    for (int k = 1; k < threads; ++k) threads_.emplace_back([this, k] { loop(k); });
  }
  ~RoundPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
      ++generation_;
    }
    start_.notify_all();
    for (auto& t : threads_) t.join();
  }
  void run_round() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      pending_ = static_cast<int>(threads_.size());
      ++generation_;
    }
    start_.notify_all();
    work_(0);
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return pending_ == 0; });
  }

 private:
  void loop(int k) {
    std::uint64_t seen = 0;
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(mutex_);
        start_.wait(lock, [&] { return generation_ != seen; });
        seen = generation_;
        if (stop_) return;
      }
      work_(k);
      {
        std::lock_guard<std::mutex> lock(mutex_);
        --pending_;
      }
      done_.notify_one();
    }
  }
  std::function<void(int)> work_;
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  std::uint64_t generation_ = 0;
  int pending_ = 0;
  bool stop_ = false;
};

}  // namespace

double average_return_per_state(const Environment& env, const std::vector<float>& q) {
  const int states = env.states().size(), actions = env.actions().size();
  double sum = 0.0;
  for (int s = 0; s < states; ++s) {
    const int m = env.states().decode(s).motion;
    const float* row = q.data() + static_cast<size_t>(s) * static_cast<size_t>(actions);
    sum += row[greedy_action(env, row, m)];
  }
  return states > 0 ? sum / states : 0.0;
}

TrainingResult train_sarsa(const Environment& env, const SarsaParams& p, const TrainingOptions& options) {
  if (p.threads <= 0) throw std::invalid_argument("sarsa.threads must be positive");
  if (p.convergence_episodes <= 0) throw std::invalid_argument("sarsa.convergence_episodes must be positive");
  if (p.max_episode_steps <= 0) throw std::invalid_argument("sarsa.max_episode_steps must be positive");
  if (p.max_steps <= 0) throw std::invalid_argument("sarsa.max_steps must be positive");
  if (!(p.discount >= 0.0f && p.discount < 1.0f)) throw std::invalid_argument("sarsa.discount must be in [0, 1)");

  const auto start = std::chrono::steady_clock::now();
  auto cpu_now = [] {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  };
  const double cpu_start = cpu_now();
  const int T = p.threads;
  const size_t states = static_cast<size_t>(env.states().size());
  const size_t actions = static_cast<size_t>(env.actions().size());
  const size_t n = states * actions;

  std::vector<float> master(n, 0.0f);
  std::vector<std::uint64_t> master_tried(states, 0);
  std::vector<Worker> workers(static_cast<size_t>(T));
  for (int k = 0; k < T; ++k) {
    Worker& w = workers[static_cast<size_t>(k)];
    std::uint64_t sm = p.seed ^ (0x5851F42D4C957F2Dull * static_cast<std::uint64_t>(k + 1));
    w.rng.reseed(splitmix64(sm));
    w.q = master;
    w.tried = master_tried;
    w.touched_flag.assign(n, 0);
    w.touched.reserve(1 << 16);
  }

  SarsaParams sp = p;
  Sarsa sarsa(env, sp);
  RoundPool pool(T, [&](int k) { sarsa.run(workers[static_cast<size_t>(k)]); });

  std::vector<float> acc(n, 0.0f);
  std::vector<std::uint8_t> count(n, 0);
  std::vector<int> merged, changed_states;
  merged.reserve(1 << 16);
  std::vector<std::uint8_t> state_flag(states, 0);
  std::vector<int> policy(states), motion_of(states);  // the committed greedy action and last motion per state
  for (size_t s = 0; s < states; ++s) {
    motion_of[s] = env.states().decode(static_cast<int>(s)).motion;
    policy[s] = greedy_action(env, master.data() + s * actions, motion_of[s]);
  }

  TrainingResult result;
  const std::int64_t update_limit =
      static_cast<std::int64_t>(std::floor(static_cast<double>(p.convergence_fraction) * static_cast<double>(states)));
  std::int64_t next_curve = 0;
  auto record_curve = [&] {
    result.curve.push_back({result.steps, result.episodes, average_return_per_state(env, master)});
  };
  record_curve();
  next_curve = options.curve_every_steps;

  while (true) {
    for (int k = 0; k < T; ++k) {
      Worker& w = workers[static_cast<size_t>(k)];
      w.quota = p.convergence_episodes / T + (k < p.convergence_episodes % T ? 1 : 0);
      w.steps = w.episodes = w.explored = 0;
    }
    pool.run_round();

    // Merge in worker order (see sarsa.h): deterministic whatever the threads' timing.
    merged.clear();
    std::int64_t explored = 0;
    for (Worker& w : workers) {
      explored += w.explored;
      result.steps += w.steps;
      result.episodes += w.episodes;
      for (int idx : w.touched) {
        const size_t i = static_cast<size_t>(idx);
        if (count[i] == 0) merged.push_back(idx);
        acc[i] += w.q[i] - master[i];
        ++count[i];
      }
    }
    changed_states.clear();
    for (int idx : merged) {
      const size_t i = static_cast<size_t>(idx);
      master[i] += acc[i] / static_cast<float>(count[i]);
      master_tried[i / actions] |= std::uint64_t{1} << (i % actions);
      acc[i] = 0.0f;
      count[i] = 0;
      if (!state_flag[i / actions]) {
        state_flag[i / actions] = 1;
        changed_states.push_back(static_cast<int>(i / actions));
      }
    }
    // The convergence count (sarsa.h): states whose committed greedy action was beaten by another allowed
    // action by more than update_tolerance during this round.
    std::int64_t round_updates = 0;
    for (int st : changed_states) {
      const size_t s = static_cast<size_t>(st);
      state_flag[s] = 0;
      const float* row = master.data() + s * actions;
      const int best = greedy_action(env, row, motion_of[s]);
      int& committed = policy[s];
      if (best != committed && row[best] - row[committed] > p.update_tolerance) {
        committed = best;
        ++round_updates;
      }
    }
    for (Worker& w : workers) {
      for (int idx : merged) {
        const size_t i = static_cast<size_t>(idx);
        w.q[i] = master[i];
        w.tried[i / actions] = master_tried[i / actions];
        w.touched_flag[i] = 0;
      }
      w.touched.clear();
    }
    ++result.rounds;

    result.converged = explored == 0 && round_updates < update_limit;
    const bool done = result.converged || result.steps >= p.max_steps;
    if (result.steps >= next_curve || done) {
      record_curve();
      while (next_curve <= result.steps) next_curve += options.curve_every_steps > 0 ? options.curve_every_steps : 1;
    }
    if (options.progress) options.progress({result.steps, p.max_steps, result.episodes, round_updates, update_limit});
    if (done) break;
  }
  result.q = std::move(master);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.cpu_seconds = cpu_now() - cpu_start;
  return result;
}

}  // namespace prep
