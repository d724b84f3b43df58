#pragma once
// The one parallel loop of plumekit: a small pool of threads that persist
// between calls (the inference engine calls it for every layer), used by dataset
// generation, evaluation and the engine alike. Ours rather than oneTBB: docs/own-code.md.
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace plumekit {

// The thread count every command uses when none is given: 0, one per core.
inline constexpr int kDefaultThreads = 0;

// `requested`, or the number of cores for 0 (at least 1).
int resolve_threads(int requested);

class ThreadPool {
 public:
  // `threads` (0: one per core) workers, the calling thread counting as one.
  explicit ThreadPool(int threads = kDefaultThreads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return size_; }

  // Runs body(i) once for each i in [0, count), on the pool's threads and the
  // caller's. If a body throws, no new index is started and, once the running
  // ones finish, the exception of the lowest index that threw is rethrown, so
  // the error reported does not depend on timing. Calls from two threads take
  // turns; a call from inside a body runs inline.
  void parallel_for(std::size_t count, const std::function<void(std::size_t index)>& body);

 private:
  void worker_loop();
  void run_indices();

  int size_ = 1;
  std::vector<std::thread> workers_;
  std::mutex call_mutex_;  // one parallel_for at a time

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(std::size_t)>* body_ = nullptr;
  std::size_t count_ = 0, next_ = 0;
  std::size_t generation_ = 0;  // bumped per call so workers see new work
  int busy_ = 0;                // workers still inside the current call
  bool stop_ = false, failed_ = false;
  std::size_t failed_index_ = 0;
  std::exception_ptr error_;
};

}  // namespace plumekit
