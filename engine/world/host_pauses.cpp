#include "engine/world/host_pauses.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>

namespace prep {
namespace {

using Clock = std::chrono::steady_clock;

// The fixed piece: a chain of dependent multiply-adds, each waiting for the one before, so that its time
// is the chain's length times one link's latency (some 15-20 us). The empty asm hands x over through
// memory at every link: the compiler may not fold, reorder or drop any of them.
constexpr int kPieceLength = 4096;
double fixed_piece(double x) {
  for (int i = 0; i < kPieceLength; ++i) {
    x = x * 0.999999 + 1e-6;
#if defined(__GNUC__)
    asm volatile("" : "+m"(x));
#endif
  }
  return x;
}

}  // namespace

PauseCount count_pauses(const std::vector<double>& piece_ms, double limit_ms) {
  PauseCount c;
  for (double ms : piece_ms) {
    c.longest_ms = std::max(c.longest_ms, ms);
    if (ms > limit_ms) {
      ++c.pauses;
      c.paused_ms += ms;
    }
  }
  return c;
}

HostPauseProbe probe_host_pauses(double seconds, int threads, const std::function<void(int, std::int64_t)>& after_piece) {
  threads = std::max(1, threads);
  std::vector<std::vector<double>> piece_ms(static_cast<size_t>(threads));
  std::atomic<double> sink{0.0};  // the pieces' results go somewhere, so that they are computed
  const auto work = [&](int t) {
    std::vector<double>& times = piece_ms[static_cast<size_t>(t)];
    times.reserve(static_cast<size_t>(std::max(0.0, seconds) * 1e5));  // no allocation while timing
    const Clock::time_point end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    double x = 1.0 + t;
    for (std::int64_t piece = 0;; ++piece) {
      const Clock::time_point t0 = Clock::now();
      if (t0 >= end) break;
      x = fixed_piece(x);
      if (after_piece) after_piece(t, piece);
      times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    }
    sink.store(x, std::memory_order_relaxed);
  };
  std::vector<std::thread> helpers;
  for (int t = 1; t < threads; ++t) helpers.emplace_back(work, t);
  work(0);
  for (std::thread& h : helpers) h.join();

  HostPauseProbe probe;
  probe.seconds = seconds;
  probe.threads = threads;
  std::vector<double> all;
  for (const auto& times : piece_ms) all.insert(all.end(), times.begin(), times.end());
  probe.pieces = static_cast<std::int64_t>(all.size());
  probe.paused = count_pauses(all);
  probe.stopped = count_pauses(all, kProbeStopMs);
  if (!all.empty()) {
    std::nth_element(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(all.size() / 2), all.end());
    probe.median_piece_us = 1e3 * all[all.size() / 2];
  }
  return probe;
}

}  // namespace prep
