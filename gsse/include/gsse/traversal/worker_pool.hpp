#pragma once
// Threads kept for the parallel for_each. A meshing run makes a hundred parallel loops, many of a
// millisecond or less (one per conformer round and phase); starting and joining a thread for each
// cost 20-40 us and the helper started late. Pool threads wait briefly spinning after a loop, then
// sleep, so back-to-back loops find them awake.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

namespace gsse::detail {

class worker_pool {
 public:
  /// A loop over items [0, n): claimed one at a time by the caller and by up to `helpers` threads.
  struct job {
    std::size_t n = 0;
    unsigned helpers = 0;     // pool threads wanted
    unsigned joined = 0;      // pool threads that took it (under the pool's mutex)
    unsigned inside = 0;      // of those, still working (under the pool's mutex)
    std::atomic<std::size_t> next{0};
    void (*body)(void*, std::size_t) = nullptr;
    void* context = nullptr;
    void work() {
      for (std::size_t k; (k = next.fetch_add(1, std::memory_order_relaxed)) < n;) body(context, k);
    }
  };

  static worker_pool& instance() {
    static worker_pool pool;
    return pool;
  }

  /// Runs the job on the calling thread and on up to job.helpers pool threads; returns when every
  /// item is done. The body must not throw (for_each catches inside it). A body may itself run a
  /// job: pool threads busy elsewhere simply do not join, and the caller does the items alone.
  void run(job& j) {
    if (j.helpers == 0) return j.work();
    {
      std::lock_guard lock(m_);
      while (threads_.size() < j.helpers) threads_.emplace_back([this] { loop(); });
      queue_.push_back(&j);
      posted_.fetch_add(1, std::memory_order_relaxed);
    }
    wake_.notify_all();
    j.work();
    std::unique_lock lock(m_);
    // no thread joins once the job is out of the queue; wait for those that did
    for (auto it = queue_.begin(); it != queue_.end(); ++it)
      if (*it == &j) {
        queue_.erase(it);
        break;
      }
    done_.wait(lock, [&] { return j.inside == 0; });
  }

  ~worker_pool() {
    {
      std::lock_guard lock(m_);
      stop_ = true;
    }
    wake_.notify_all();
    threads_.clear();  // joins
  }

 private:
  worker_pool() = default;

  void loop() {
    std::unique_lock lock(m_);
    for (;;) {
      if (queue_.empty() && !stop_) {
        // spin a little (unlocked) before sleeping: the next loop usually follows within microseconds
        const auto seen = posted_.load(std::memory_order_relaxed);
        lock.unlock();
        const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(spin_us);
        while (std::chrono::steady_clock::now() < until && posted_.load(std::memory_order_relaxed) == seen)
          std::this_thread::yield();
        lock.lock();
        wake_.wait(lock, [&] { return !queue_.empty() || stop_; });
      }
      if (stop_) return;
      job* j = queue_.front();
      if (++j->joined >= j->helpers) queue_.pop_front();
      ++j->inside;
      lock.unlock();
      j->work();
      lock.lock();
      if (--j->inside == 0) done_.notify_all();
    }
  }

  static constexpr int spin_us = 200;
  std::mutex m_;
  std::condition_variable wake_, done_;
  std::deque<job*> queue_;
  std::atomic<std::size_t> posted_{0};  // jobs ever posted: what a spinning thread watches
  bool stop_ = false;
  std::vector<std::jthread> threads_;
};

}  // namespace gsse::detail
