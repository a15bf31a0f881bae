#include "engine/world/frame_workers.h"

namespace prep {

FrameWorkers::FrameWorkers(int blocks) {
  for (int b = 1; b < blocks; ++b) threads_.emplace_back([this, b] { loop(b); });
}

FrameWorkers::~FrameWorkers() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    ++generation_;
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void FrameWorkers::run(const std::function<void(int)>& job) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    job_ = &job;
    pending_ = static_cast<int>(threads_.size());
    ++generation_;
  }
  wake_.notify_all();
  job(0);
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [&] { return pending_ == 0; });
  job_ = nullptr;
}

void FrameWorkers::loop(int block) {
  std::uint64_t seen = 0;
  for (;;) {
    const std::function<void(int)>* job = nullptr;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return generation_ != seen; });
      seen = generation_;
      if (stop_) return;
      job = job_;
    }
    (*job)(block);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (--pending_ == 0) done_.notify_one();
    }
  }
}

void FrameWorkers::block_range(size_t count, int block, int blocks, size_t& first, size_t& last) {
  first = count * static_cast<size_t>(block) / static_cast<size_t>(blocks);
  last = count * static_cast<size_t>(block + 1) / static_cast<size_t>(blocks);
}

}  // namespace prep
