#pragma once
// Deterministic parallel loops: the result never depends on the thread count as long as each
// index writes only its own output.

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace sketchsurf {

/// Number of worker threads to use for a request of `threads` (0 = all hardware threads).
inline unsigned resolve_threads(unsigned threads) {
  if (threads != 0) return threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

/// The exception a parallel loop rethrows: the first one thrown, in time. A call that fails
/// because another one did (a run cancelled when a sibling run failed) must not hide the cause.
class FirstError {
 public:
  void keep(std::exception_ptr e) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!first_) first_ = std::move(e);
  }
  void rethrow() const {
    if (first_) std::rethrow_exception(first_);
  }

 private:
  std::mutex mutex_;
  std::exception_ptr first_;
};

/// Calls fn(i) for i in chunk w of [begin, end) split into `parts` contiguous chunks: the chunks
/// of parallel_for() and WorkerTeam::for_each().
template <class Fn>
void for_chunk(std::size_t begin, std::size_t end, std::size_t parts, std::size_t w, Fn& fn) {
  const std::size_t n = end - begin;
  for (std::size_t i = begin + n * w / parts; i < begin + n * (w + 1) / parts; ++i) fn(i);
}

/// Calls fn(i) for every i in [begin, end) on up to `threads` threads (0 = all), in contiguous
/// chunks. The first exception thrown by any call (FirstError) is rethrown on the calling thread.
template <class Fn>
void parallel_for(std::size_t begin, std::size_t end, unsigned threads, Fn&& fn) {
  if (end <= begin) return;
  const std::size_t workers = std::min<std::size_t>(resolve_threads(threads), end - begin);
  if (workers <= 1) {
    for (std::size_t i = begin; i < end; ++i) fn(i);
    return;
  }
  FirstError error;
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  auto run_chunk = [&](std::size_t w) {
    try {
      for_chunk(begin, end, workers, w, fn);
    } catch (...) {
      error.keep(std::current_exception());
    }
  };
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(run_chunk, w);
  run_chunk(0);
  for (auto& t : pool) t.join();
  error.rethrow();
}

/// Worker threads kept for many loops (an extraction runs thousands, where parallel_for() would
/// start and join threads at each: ~50 us of CPU apiece).
/// for_each() runs parallel_for()'s chunks, so the same results whatever the thread count; the
/// calling thread runs chunk 0. Between loops the workers spin a little while for the next one
/// before they sleep on a condition variable, and the caller spins a little while for them to end:
/// a loop then costs about a microsecond instead of a sleep and a wake-up (tens of microseconds on
/// a virtual machine). The first exception thrown in a loop (FirstError) is rethrown on the
/// calling thread once every chunk has ended. One loop at a time.
class WorkerTeam {
 public:
  /// `threads` as for parallel_for() (0 = all).
  explicit WorkerTeam(unsigned threads) : size_(resolve_threads(threads)) {
    for (unsigned w = 1; w < size_; ++w) workers_.emplace_back([this, w] { serve(w); });
  }
  ~WorkerTeam() {
    stop_ = true;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
  }
  WorkerTeam(const WorkerTeam&) = delete;
  WorkerTeam& operator=(const WorkerTeam&) = delete;

  /// parallel_for(begin, end, threads, fn) on the team.
  template <class Fn>
  void for_each(std::size_t begin, std::size_t end, Fn&& fn) const {
    if (end <= begin) return;
    const std::size_t parts = std::min<std::size_t>(size_, end - begin);
    run(parts, [&](std::size_t w) { for_chunk(begin, end, parts, w, fn); });
  }

  /// Calls fn(c, lo, hi) for the fixed chunks c of [0, n), each [lo, hi) of `chunk` indices (the
  /// last one shorter). The chunks do not depend on the thread count: sums kept per chunk and
  /// added in chunk order are the same whatever the threads.
  template <class Fn>
  void chunks(std::size_t n, std::size_t chunk, Fn&& fn) const {
    for_each(0, (n + chunk - 1) / chunk, [&](std::size_t c) { fn(c, c * chunk, std::min(n, (c + 1) * chunk)); });
  }

 private:
  // How long a waiting thread polls before it sleeps: some tens of microseconds.
  static constexpr int kSpins = 2048;

  static void pause() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }

  // Polls `ready` for a while; then sleeps on `cv` until it holds, counted in `sleepers` so that
  // whoever makes it hold knows to notify (it reads `sleepers` after making it hold; this thread
  // counts itself before its last test under the mutex, so one of the two sees the other).
  template <class Ready>
  void wait_for(std::condition_variable& cv, std::atomic<int>& sleepers, Ready&& ready) const {
    for (int i = 0; i < kSpins; ++i) {
      if (ready()) return;
      pause();
    }
    std::unique_lock<std::mutex> lock(mutex_);
    ++sleepers;
    cv.wait(lock, ready);
    --sleepers;
  }
  void notify(std::condition_variable& cv, const std::atomic<int>& sleepers) const {
    if (sleepers.load() == 0) return;
    { const std::lock_guard<std::mutex> lock(mutex_); }
    cv.notify_all();
  }

  // part(w) for w in [0, parts), part 0 on the calling thread.
  template <class Part>
  void run(std::size_t parts, const Part& part) const {
    if (parts <= 1) return part(0);
    FirstError error;
    job_ = [](const void* p, std::size_t w) { (*static_cast<const Part*>(p))(w); };
    context_ = &part;
    error_ = &error;
    parts_ = parts;
    pending_ = workers_.size();  // every worker, also one without a part, answers each loop
    ++generation_;               // publishes the loop above to the workers
    notify(wake_, sleeping_workers_);
    try {
      part(0);
    } catch (...) {
      error.keep(std::current_exception());
    }
    wait_for(done_, sleeping_caller_, [&] { return pending_.load() == 0; });
    error.rethrow();
  }

  void serve(std::size_t w) const {
    std::uint64_t seen = 0;
    for (;;) {
      wait_for(wake_, sleeping_workers_, [&] { return stop_.load() || generation_.load() != seen; });
      if (stop_) return;
      seen = generation_;
      if (w < parts_) {
        try {
          job_(context_, w);
        } catch (...) {
          error_->keep(std::current_exception());
        }
      }
      if (--pending_ == 0) notify(done_, sleeping_caller_);
    }
  }

  unsigned size_;
  std::vector<std::thread> workers_;
  mutable std::mutex mutex_;  // only for the sleeps
  mutable std::condition_variable wake_, done_;
  mutable std::atomic<int> sleeping_workers_{0}, sleeping_caller_{0};
  // The current loop: written by the caller before it bumps generation_, read by the workers after
  // they see the new generation; the caller writes the next one only when every worker answered.
  mutable void (*job_)(const void*, std::size_t) = nullptr;
  mutable const void* context_ = nullptr;
  mutable FirstError* error_ = nullptr;
  mutable std::size_t parts_ = 0;
  mutable std::atomic<std::size_t> pending_{0};
  mutable std::atomic<std::uint64_t> generation_{0};
  std::atomic<bool> stop_{false};
};

/// Calls fn(i) for every i in [0, n) on up to `threads` threads (0 = all), each thread taking the
/// next index when it is free, the calling thread one of them: for few calls of uneven length.
/// The first exception thrown is rethrown on the calling thread once every thread has stopped;
/// the others stop after their current index.
template <class Fn>
void parallel_dynamic(std::size_t n, unsigned threads, Fn&& fn) {
  const std::size_t workers = std::min<std::size_t>(resolve_threads(threads), n);
  std::atomic<std::size_t> next{0};
  FirstError error;
  auto work = [&] {
    try {
      for (std::size_t i; (i = next++) < n;) fn(i);
    } catch (...) {
      error.keep(std::current_exception());
      next = n;
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  error.rethrow();
}

}  // namespace sketchsurf
