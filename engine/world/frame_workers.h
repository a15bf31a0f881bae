// A frame's work split over the machine's cores: run(job) calls job(block) for every block, block 0 on the
// calling thread and each other block on a helper thread that lives as long as the FrameWorkers, so a frame
// costs one wake-up per helper, not a thread start. The job is referenced, not copied: nothing is allocated
// per frame. The crowd benchmark and the crowd demo step their worlds through it.
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace prep {

class FrameWorkers {
 public:
  explicit FrameWorkers(int blocks);
  ~FrameWorkers();
  FrameWorkers(const FrameWorkers&) = delete;
  FrameWorkers& operator=(const FrameWorkers&) = delete;

  int blocks() const { return static_cast<int>(threads_.size()) + 1; }
  // Returns when job(0) .. job(blocks() - 1) have all returned. `job` must outlive the call.
  void run(const std::function<void(int)>& job);

  // work(first, last, block) over items [0, count) in runs of `chunk`, each run taken by whichever thread
  // is free next. With fixed halves a frame waits for the slower half: one whose core the system lent
  // elsewhere for a while, or whose items had more to do that frame. `work` must outlive the call.
  void run_chunks(size_t count, size_t chunk, const std::function<void(size_t, size_t, int)>& work);
  // A run length for `count` items over `blocks` threads: about 32 runs per thread, so the last runs to
  // be taken are short next to a frame, while taking one stays rare.
  static size_t chunk_for(size_t count, int blocks) {
    return std::max<size_t>(1, count / (32 * static_cast<size_t>(std::max(1, blocks))));
  }

 private:
  void loop(int block);
  void take_chunks(int block);

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int)>* job_ = nullptr;
  int pending_ = 0;
  std::uint64_t generation_ = 0;
  bool stop_ = false;
  // run_chunks' frame: the next item not yet taken, and what to do with a run of them.
  std::atomic<size_t> next_item_{0};
  size_t chunk_count_ = 0, chunk_size_ = 1;
  const std::function<void(size_t, size_t, int)>* chunk_work_ = nullptr;
  std::function<void(int)> take_chunks_;
};

}  // namespace prep
