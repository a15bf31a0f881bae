// Pauses of a busy thread that its own work does not explain, told apart from slow work.
//
// On a virtual machine the host can stop a virtual core for a while (on this 2-core machine: 100 ms at a
// time, every few seconds of full load). The guest's clocks run on meanwhile, and a guest that reports no
// steal time counts the pause as CPU time of the thread it stopped: neither the wall clock nor the thread's
// CPU clock tells such a pause from work. What does is the size of the work: a piece of work that usually
// takes a millisecond and once takes a hundred did not do a hundred times as much.
//
// - probe_host_pauses: a fixed piece of arithmetic (one number, no calls, no branch on data), some 15-20 us,
//   repeated on every thread and timed; a piece that takes over kPauseMs was paused, and one over
//   kProbeStopMs was stopped for a shorter while. It measures the machine alone, before a benchmark, so
//   that a benchmark's slowest frames can be read against it.
// - count_pauses: the same rule over a benchmark's own timed pieces (a crowd frame's runs of worlds).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace prep {

// A piece of work that a crowd or the probe times takes a few microseconds to a few milliseconds; one that
// takes over this was stopped (a pause of the host or of the guest's scheduler), not slow.
constexpr double kPauseMs = 20.0;
// The probe's piece takes some 15-20 us: one that takes over this, fifty times as long, was stopped too.
// Stops this short hide inside a crowd's runs of worlds (a millisecond or less each), which no absolute limit
// tells from slow work; the probe counts them on the machine alone.
constexpr double kProbeStopMs = 1.0;

struct PauseCount {
  int pauses = 0;            // pieces over the limit
  double longest_ms = 0.0;   // the longest piece, paused or not
  double paused_ms = 0.0;    // the time the paused pieces took, all told
};
// The pieces (ms each) that took over `limit_ms`.
PauseCount count_pauses(const std::vector<double>& piece_ms, double limit_ms = kPauseMs);

struct HostPauseProbe {
  double seconds = 0.0;            // how long each thread ran
  int threads = 0;
  std::int64_t pieces = 0;         // pieces timed, all threads
  double median_piece_us = 0.0;    // what an unpaused piece takes
  PauseCount paused;               // over kPauseMs
  PauseCount stopped;              // over kProbeStopMs (the pauses among them)
};
// `threads` threads each repeat the fixed piece for `seconds`. `after_piece(thread, piece)`, when given,
// runs after each piece inside its timing (for tests: a sleep there is a pause the probe must find).
HostPauseProbe probe_host_pauses(double seconds, int threads,
                                 const std::function<void(int, std::int64_t)>& after_piece = nullptr);

}  // namespace prep
