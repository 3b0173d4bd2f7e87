#pragma once
// Deterministic parallel loops: the result never depends on the thread count as long as each
// index writes only its own output.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
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

/// Calls fn(i) for every i in [begin, end) on up to `threads` threads (0 = all), in contiguous
/// chunks. The first exception thrown by any call (FirstError) is rethrown on the calling thread.
template <class Fn>
void parallel_for(std::size_t begin, std::size_t end, unsigned threads, Fn&& fn) {
  if (end <= begin) return;
  const std::size_t n = end - begin;
  const std::size_t workers = std::min<std::size_t>(resolve_threads(threads), n);
  if (workers <= 1) {
    for (std::size_t i = begin; i < end; ++i) fn(i);
    return;
  }
  FirstError error;
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  auto run_chunk = [&](std::size_t w) {
    const std::size_t lo = begin + n * w / workers, hi = begin + n * (w + 1) / workers;
    try {
      for (std::size_t i = lo; i < hi; ++i) fn(i);
    } catch (...) {
      error.keep(std::current_exception());
    }
  };
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(run_chunk, w);
  run_chunk(0);
  for (auto& t : pool) t.join();
  error.rethrow();
}

/// Calls fn(c, lo, hi) for the fixed chunks c of [0, n), each [lo, hi) of `chunk` indices (the
/// last one shorter), on up to `threads` threads. The chunks do not depend on the thread count:
/// sums kept per chunk and added in chunk order are the same whatever the threads.
template <class Fn>
void parallel_chunks(std::size_t n, std::size_t chunk, unsigned threads, Fn&& fn) {
  parallel_for(0, (n + chunk - 1) / chunk, threads,
               [&](std::size_t c) { fn(c, c * chunk, std::min(n, (c + 1) * chunk)); });
}

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
