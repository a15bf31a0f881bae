#include "engine/world/frame_workers.h"

#include <algorithm>

namespace prep {

FrameWorkers::FrameWorkers(int blocks) : take_chunks_([this](int block) { take_chunks(block); }) {
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

void FrameWorkers::run_chunks(size_t count, size_t chunk, const std::function<void(size_t, size_t, int)>& work) {
  chunk_count_ = count;
  chunk_size_ = chunk > 0 ? chunk : 1;
  chunk_work_ = &work;
  next_item_.store(0, std::memory_order_relaxed);
  run(take_chunks_);  // the helpers see these fields after run()'s lock, which orders them
  chunk_work_ = nullptr;
}

void FrameWorkers::take_chunks(int block) {
  for (;;) {
    const size_t first = next_item_.fetch_add(chunk_size_, std::memory_order_relaxed);
    if (first >= chunk_count_) return;
    (*chunk_work_)(first, std::min(first + chunk_size_, chunk_count_), block);
  }
}

}  // namespace prep
