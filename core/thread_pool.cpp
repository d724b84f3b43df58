#include "core/thread_pool.hpp"

#include <algorithm>

namespace plumekit {

namespace {
// Set while a thread runs a body, so nested calls run inline instead of
// waiting for workers that are busy with the outer call.
thread_local bool inside_body = false;
}  // namespace

int resolve_threads(int requested) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

ThreadPool::ThreadPool(int threads) : size_(resolve_threads(threads)) {
  workers_.reserve(size_ - 1);
  for (int t = 1; t < size_; ++t)
    workers_.emplace_back([this] { worker_loop(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_)
    t.join();
}

// Takes indices until none are left (or one failed); records the lowest failure.
void ThreadPool::run_indices() {
  const bool was_inside = inside_body;
  inside_body = true;
  for (;;) {
    std::size_t i;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (failed_ || next_ >= count_) break;
      i = next_++;
    }
    try {
      (*body_)(i);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!failed_ || i < failed_index_) {
        failed_index_ = i;
        error_ = std::current_exception();
      }
      failed_ = true;
    }
  }
  inside_body = was_inside;
}

void ThreadPool::worker_loop() {
  std::size_t seen = 0;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
    }
    run_indices();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      --busy_;
    }
    done_.notify_all();
  }
}

void ThreadPool::parallel_for(std::size_t count,
                              const std::function<void(std::size_t index)>& body) {
  if (count == 0) return;
  if (workers_.empty() || inside_body || count == 1) {
    // Inline: same contract (stop at the first failure, which is the lowest index).
    for (std::size_t i = 0; i < count; ++i)
      body(i);
    return;
  }
  std::lock_guard<std::mutex> call(call_mutex_);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    body_ = &body;
    count_ = count;
    next_ = 0;
    failed_ = false;
    error_ = nullptr;
    busy_ = static_cast<int>(workers_.size());
    ++generation_;
  }
  wake_.notify_all();
  run_indices();
  std::exception_ptr error;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return busy_ == 0; });
    body_ = nullptr;
    error = error_;
    error_ = nullptr;
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace plumekit
