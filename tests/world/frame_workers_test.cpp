#include "engine/world/frame_workers.h"

#include <doctest/doctest.h>

#include <atomic>
#include <thread>
#include <vector>

using namespace prep;

TEST_CASE("frame workers: run_chunks hands every item to exactly one thread, in runs, frame after frame") {
  for (int blocks : {1, 2, 3}) {
    FrameWorkers workers(blocks);
    for (size_t count : {size_t{0}, size_t{1}, size_t{7}, size_t{1000}}) {
      for (size_t chunk : {size_t{1}, size_t{3}, size_t{64}, size_t{5000}}) {
        CAPTURE(blocks);
        CAPTURE(count);
        CAPTURE(chunk);
        std::vector<std::atomic<int>> taken(count);
        std::vector<std::atomic<int>> by_block(static_cast<size_t>(blocks));
        std::atomic<int> runs{0}, too_long{0}, bad_block{0};
        const std::function<void(size_t, size_t, int)> work = [&](size_t first, size_t last, int block) {
          ++runs;
          if (last - first > chunk || last <= first) ++too_long;
          if (block < 0 || block >= blocks) ++bad_block;
          else by_block[static_cast<size_t>(block)] += static_cast<int>(last - first);
          for (size_t i = first; i < last; ++i) ++taken[i];
        };
        for (int frame = 0; frame < 3; ++frame) workers.run_chunks(count, chunk, work);
        for (size_t i = 0; i < count; ++i) REQUIRE(taken[i] == 3);
        CHECK(runs == 3 * static_cast<int>((count + chunk - 1) / chunk));
        CHECK(too_long == 0);
        CHECK(bad_block == 0);
        int total = 0;
        for (auto& b : by_block) total += b;
        CHECK(total == 3 * static_cast<int>(count));
      }
    }
  }
}

TEST_CASE("frame workers: a thread held up leaves its share to the others") {
  // Block 0 sleeps on its first run: with fixed halves the frame would wait for its whole half; taken in
  // runs, the other thread does most of the items meanwhile.
  FrameWorkers workers(2);
  std::atomic<int> done_by_helper{0};
  std::atomic<bool> slept{false};
  const std::function<void(size_t, size_t, int)> work = [&](size_t first, size_t last, int block) {
    if (block == 0 && !slept.exchange(true)) std::this_thread::sleep_for(std::chrono::milliseconds(200));
    if (block == 1) done_by_helper += static_cast<int>(last - first);
    // A little work per item, so the helper does not finish before block 0 takes its first run.
    volatile double x = 0;
    for (size_t i = first; i < last; ++i)
      for (int k = 0; k < 20000; ++k) x = x + static_cast<double>(k);
  };
  workers.run_chunks(256, 4, work);
  CHECK(slept);
  CHECK(done_by_helper > 256 / 2 + 64);
  CHECK(FrameWorkers::chunk_for(20000, 2) == 312);
  CHECK(FrameWorkers::chunk_for(10, 2) == 1);
}
