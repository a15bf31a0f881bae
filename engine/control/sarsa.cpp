#include "engine/control/sarsa.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <condition_variable>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace prep {
namespace {

// The tables' layout while training. A Q row is padded to a multiple of four actions (the paper's 24 need
// none) and every action a row's state does not allow (its last motion's Next(m)), and the padding, holds
// -infinity: the greedy choice is then a plain maximum over the row, four actions at a time, with no mask
// to apply. Training never reads or writes those entries otherwise (it takes allowed actions only), and the
// result is handed out unpadded with them 0, as they were never changed (train_sarsa).
struct Layout {
  size_t actions = 0;  // the action space's size
  size_t stride = 0;   // floats per row: actions rounded up to a multiple of 4
  int blocks = 0;      // stride / 4
};

constexpr float kNever = -std::numeric_limits<float>::infinity();

// The greedy action of a padded row holding -infinity where not allowed: the same choice as greedy_action
// on the unpadded row (the maximum over the allowed actions, the first allowed one holding it; all of them
// NaN: the lowest allowed). kBlocks > 0 fixes the number of four-action blocks at compile time, so that
// the loops unroll; 0 takes `blocks`.
template <int kBlocks>
inline int greedy_in_padded_row(const float* row, std::uint64_t allowed, int blocks) {
  if (kBlocks > 0) blocks = kBlocks;
  std::uint64_t holding = 0;  // bit a: row[a] == the maximum
#if defined(__SSE2__)
  __m128 best = _mm_set1_ps(kNever);
  for (int b = 0; b < blocks; ++b) best = _mm_max_ps(_mm_loadu_ps(row + 4 * b), best);  // v > m ? v : m: NaN keeps m
  best = _mm_max_ps(best, _mm_shuffle_ps(best, best, _MM_SHUFFLE(1, 0, 3, 2)));
  best = _mm_max_ps(best, _mm_shuffle_ps(best, best, _MM_SHUFFLE(2, 3, 0, 1)));
  for (int b = 0; b < blocks; ++b)
    holding |= static_cast<std::uint64_t>(_mm_movemask_ps(_mm_cmpeq_ps(_mm_loadu_ps(row + 4 * b), best))) << (4 * b);
#else
  float best = kNever;
  for (int a = 0; a < 4 * blocks; ++a) best = row[a] > best ? row[a] : best;
  for (int a = 0; a < 4 * blocks; ++a) holding |= static_cast<std::uint64_t>(row[a] == best) << a;
#endif
  const std::uint64_t found = holding & allowed;
  return __builtin_ctzll(found != 0 ? found : allowed);
}

// One worker's replica and counters.
struct Worker {
  Rng rng;
  std::vector<float> q;                 // states x Layout::stride
  std::vector<std::uint64_t> tried;     // per state, bit a = action a has been taken there
  std::vector<std::uint64_t> touched;   // per state, bit a = Q(s, a) changed this round
  std::vector<int> touched_states;      // the states with a touched bit, in the order first touched
  std::int64_t steps = 0, episodes = 0, explored = 0;  // explored: untried actions taken
  int quota = 0;                        // episodes this round
  // The next episode's exploring start, drawn one episode ahead so that its Q row and tried flags (a
  // random state: a cache miss) are fetched while the current episode runs. Episodes last only a few
  // actions of a gait cycle, so these misses would otherwise cost as much as the steps.
  Situation next_start;
  int next_state = -1;
};

// What the round's merge hands back to every worker (see train_sarsa): the merged table and the states
// it changed. Each worker brings its replica up to date from it at the start of its next round, in
// parallel with the others, instead of the merge doing it for all of them while the other core waits.
struct Merged {
  const std::vector<float>* master = nullptr;
  const std::vector<std::uint64_t>* master_tried = nullptr;
  std::vector<int> states;
};

class Sarsa {
 public:
  Sarsa(const Environment& env, const Layout& layout, const SarsaParams& p)
      : env_(env),
        layout_(layout),
        lr_(p.learning_rate),
        gamma_(p.discount),
        epsilon_(p.epsilon),
        source_at_goal_(p.source_at_goal_fraction),
        far_start_range_(p.far_start_range),
        max_episode_steps_(p.max_episode_steps),
        goal_value_(env.reward().max_reward() / (1.0f - p.discount)) {}  // the absorbing goal (reward.h)

  // One round of worker w: its replica brought up to date with the last merge, then its episodes.
  void run(Worker& w, const Merged& merged) const {
    const size_t stride = layout_.stride;
    for (int st : merged.states) {
      const size_t s = static_cast<size_t>(st), row = s * stride;
      std::copy_n(merged.master->data() + row, stride, w.q.data() + row);  // untouched entries are equal already
      w.tried[s] = (*merged.master_tried)[s];
    }
    for (int st : w.touched_states) w.touched[static_cast<size_t>(st)] = 0;
    w.touched_states.clear();
    // The paper's 24 actions with unrolled greedy choices (more instantiations keep the compiler from
    // inlining the environment's step into them, which costs more than the unrolling gains).
    if (layout_.blocks == 6) return episodes<6>(w);
    episodes<0>(w);
  }

 private:
  template <int kBlocks>
  int greedy(const Worker& w, int state, std::uint64_t allowed) const {
    return greedy_in_padded_row<kBlocks>(w.q.data() + static_cast<size_t>(state) * layout_.stride, allowed, layout_.blocks);
  }

  template <int kBlocks>
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
    return greedy<kBlocks>(w, state, allowed);
  }

  void update(Worker& w, int state, int action, float target) const {
    const size_t idx = static_cast<size_t>(state) * layout_.stride + static_cast<size_t>(action);
    const float delta = lr_ * (target - w.q[idx]);  // Eq. 19
    w.q[idx] += delta;
    const std::uint64_t bit = std::uint64_t{1} << action;
    w.tried[static_cast<size_t>(state)] |= bit;
    std::uint64_t& touched = w.touched[static_cast<size_t>(state)];
    if (touched == 0) w.touched_states.push_back(state);
    touched |= bit;
  }

  void draw_start(Worker& w) const {
    env_.exploring_start(w.rng, source_at_goal_, far_start_range_, w.next_start);
    w.next_state = env_.quantize(w.next_start);
    const size_t row = static_cast<size_t>(w.next_state) * layout_.stride;
    __builtin_prefetch(w.q.data() + row);
    __builtin_prefetch(w.q.data() + row + layout_.stride - 1);
    __builtin_prefetch(w.tried.data() + w.next_state);
    __builtin_prefetch(w.touched.data() + w.next_state);
  }

  template <int kBlocks>
  void episodes(Worker& w) const {
    for (int e = 0; e < w.quota; ++e) episode<kBlocks>(w);
  }

  template <int kBlocks>
  void episode(Worker& w) const {
    if (w.next_state < 0) draw_start(w);
    Situation s = w.next_start;
    int state = w.next_state;
    draw_start(w);
    bool exploring = false;
    int action = choose<kBlocks>(w, state, s.motion, exploring);
    for (int t = 0; t < max_episode_steps_; ++t) {
      const StepOutcome out = env_.step(s, action);
      ++w.steps;
      if (out.at_goal) {
        update(w, state, action, out.reward + gamma_ * goal_value_);
        break;
      }
      const int next_state = env_.quantize(s);
      bool exploring = false;
      const int next_action = choose<kBlocks>(w, next_state, s.motion, exploring);
      const float* next_row = w.q.data() + static_cast<size_t>(next_state) * layout_.stride;
      // Eq. 19 bootstraps on the action taken next; an exploratory one (untried, or the epsilon draw) is
      // not a sample of what the policy does there, so its place is taken by the greedy action's value.
      const int bootstrap = exploring ? greedy<kBlocks>(w, next_state, env_.actions().allowed_mask(s.motion)) : next_action;
      update(w, state, action, out.reward + gamma_ * next_row[bootstrap]);
      state = next_state;
      action = next_action;
    }
    ++w.episodes;
  }

  const Environment& env_;
  Layout layout_;
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
  Layout layout;
  layout.actions = static_cast<size_t>(env.actions().size());
  layout.stride = (layout.actions + 3) / 4 * 4;
  layout.blocks = static_cast<int>(layout.stride / 4);
  const size_t stride = layout.stride;

  // The committed greedy action, the last motion and the allowed actions per state; the master table with
  // -infinity where not allowed (Layout).
  std::vector<int> policy(states), motion_of(states);
  std::vector<std::uint64_t> allowed_of(states);
  std::vector<float> master(states * stride, 0.0f);
  for (size_t s = 0; s < states; ++s) {
    motion_of[s] = env.states().decode(static_cast<int>(s)).motion;
    allowed_of[s] = env.actions().allowed_mask(motion_of[s]);
    for (size_t a = 0; a < stride; ++a)
      if (!(a < layout.actions && (allowed_of[s] >> a & 1u))) master[s * stride + a] = kNever;
    policy[s] = greedy_in_padded_row<0>(master.data() + s * stride, allowed_of[s], layout.blocks);
  }
  std::vector<std::uint64_t> master_tried(states, 0);
  std::vector<Worker> workers(static_cast<size_t>(T));
  for (int k = 0; k < T; ++k) {
    Worker& w = workers[static_cast<size_t>(k)];
    std::uint64_t sm = p.seed ^ (0x5851F42D4C957F2Dull * static_cast<std::uint64_t>(k + 1));
    w.rng.reseed(splitmix64(sm));
    w.q = master;
    w.tried = master_tried;
    w.touched.assign(states, 0);
    w.touched_states.reserve(1 << 14);
  }

  SarsaParams sp = p;
  Sarsa sarsa(env, layout, sp);
  Merged merged;
  merged.master = &master;
  merged.master_tried = &master_tried;
  merged.states.reserve(1 << 14);
  RoundPool pool(T, [&](int k) { sarsa.run(workers[static_cast<size_t>(k)], merged); });

  // Fig. 10's average return per state over the padded master (the same sum as average_return_per_state).
  auto average_return = [&] {
    double sum = 0.0;
    for (size_t s = 0; s < states; ++s) {
      const float* row = master.data() + s * stride;
      sum += row[greedy_in_padded_row<0>(row, allowed_of[s], layout.blocks)];
    }
    return states > 0 ? sum / static_cast<double>(states) : 0.0;
  };

  TrainingResult result;
  const std::int64_t update_limit =
      static_cast<std::int64_t>(std::floor(static_cast<double>(p.convergence_fraction) * static_cast<double>(states)));
  std::int64_t next_curve = 0;
  auto record_curve = [&] { result.curve.push_back({result.steps, result.episodes, average_return()}); };
  record_curve();
  next_curve = options.curve_every_steps;

  while (true) {
    for (int k = 0; k < T; ++k) {
      Worker& w = workers[static_cast<size_t>(k)];
      w.quota = p.convergence_episodes / T + (k < p.convergence_episodes % T ? 1 : 0);
      w.steps = w.episodes = w.explored = 0;
    }
    pool.run_round();

    // Merge in worker order (see sarsa.h): deterministic whatever the threads' timing. Each touched state
    // is merged once, at the first worker that touched it; each of its touched values becomes the master
    // value plus the mean of the changes of the workers that touched it, summed in worker order.
    merged.states.clear();
    std::int64_t explored = 0, round_updates = 0;
    for (const Worker& w : workers) {
      explored += w.explored;
      result.steps += w.steps;
      result.episodes += w.episodes;
    }
    for (int k = 0; k < T; ++k) {
      for (int st : workers[static_cast<size_t>(k)].touched_states) {
        const size_t s = static_cast<size_t>(st);
        bool earlier = false;
        for (int j = 0; j < k; ++j) earlier |= workers[static_cast<size_t>(j)].touched[s] != 0;
        if (earlier) continue;  // merged at that worker
        std::uint64_t any = 0;
        for (int j = k; j < T; ++j) any |= workers[static_cast<size_t>(j)].touched[s];
        float* row = master.data() + s * stride;
        for (std::uint64_t bits = any; bits != 0; bits &= bits - 1) {
          const int a = __builtin_ctzll(bits);
          float change = 0.0f;
          int count = 0;
          for (int j = k; j < T; ++j) {
            const Worker& w = workers[static_cast<size_t>(j)];
            if (w.touched[s] >> a & 1u) {
              change += w.q[s * stride + static_cast<size_t>(a)] - row[a];
              ++count;
            }
          }
          row[a] += change / static_cast<float>(count);
        }
        master_tried[s] |= any;
        merged.states.push_back(st);
        // The convergence count (sarsa.h): states whose committed greedy action was beaten by another
        // allowed action by more than update_tolerance during this round.
        const int best = greedy_in_padded_row<0>(row, allowed_of[s], layout.blocks);
        int& committed = policy[s];
        if (best != committed && row[best] - row[committed] > p.update_tolerance) {
          committed = best;
          ++round_updates;
        }
      }
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
  // Unpadded, with the never-allowed entries at the 0 they started from.
  result.q.assign(states * layout.actions, 0.0f);
  for (size_t s = 0; s < states; ++s)
    for (size_t a = 0; a < layout.actions; ++a)
      if (allowed_of[s] >> a & 1u) result.q[s * layout.actions + a] = master[s * stride + a];
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.cpu_seconds = cpu_now() - cpu_start;
  return result;
}

}  // namespace prep
