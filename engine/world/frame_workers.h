// A frame's work split over the machine's cores: run(job) calls job(block) for every block, block 0 on the
// calling thread and each other block on a helper thread that lives as long as the FrameWorkers, so a frame
// costs one wake-up per helper, not a thread start. The job is referenced, not copied: nothing is allocated
// per frame. The crowd benchmark and the crowd demo step their worlds through it.
#pragma once

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

  // The half-open range [first, last) of `count` items that block `block` of `blocks` takes: contiguous
  // blocks, sizes differing by one at most.
  static void block_range(size_t count, int block, int blocks, size_t& first, size_t& last);

 private:
  void loop(int block);

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int)>* job_ = nullptr;
  int pending_ = 0;
  std::uint64_t generation_ = 0;
  bool stop_ = false;
};

}  // namespace prep
