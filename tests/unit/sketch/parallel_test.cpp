// surfacing/parallel.h: the loops' results do not depend on the thread count, and a failure is
// reported by its cause, not by the runs it cancelled.
#include "surfacing/parallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace sketchsurf {
namespace {

using namespace std::chrono_literals;

// fn(i) for a loop of n calls: call `cause` throws "cause"; every other call waits until it has
// (up to 10 s), then a little longer, and throws "cancelled", as a sibling run stopped by the
// failure would.
struct FailingRuns {
  std::size_t cause;
  std::atomic<bool> failed{false};
  void operator()(std::size_t i) {
    if (i == cause) {
      failed = true;
      throw std::runtime_error("cause");
    }
    for (int k = 0; k < 1000 && !failed; ++k) std::this_thread::sleep_for(10ms);
    std::this_thread::sleep_for(50ms);
    throw std::runtime_error("cancelled");
  }
};

std::string message_of(const auto& loop) {
  try {
    loop();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "nothing thrown";
}

TEST(ParallelLoops, EveryIndexOnceWhateverTheThreadCount) {
  for (unsigned threads : {1u, 2u, 3u, 8u}) {
    std::vector<int> hits(101, 0);
    parallel_for(0, hits.size(), threads, [&](std::size_t i) { ++hits[i]; });
    EXPECT_EQ(std::vector<int>(101, 1), hits) << threads << " threads";
    std::vector<int> dynamic_hits(7, 0);
    parallel_dynamic(dynamic_hits.size(), threads, [&](std::size_t i) { ++dynamic_hits[i]; });
    EXPECT_EQ(std::vector<int>(7, 1), dynamic_hits) << threads << " threads";
  }
}

TEST(ParallelLoops, WorkerTeamRunsParallelForChunksLoopAfterLoop) {
  // Each index once, on the thread parallel_for() gives it (the same chunks), for many loops of
  // different lengths on one team; chunks() covers [0, n) in fixed chunks.
  for (unsigned threads : {1u, 2u, 3u}) {
    const WorkerTeam team(threads);
    for (std::size_t n : {0u, 1u, 2u, 5u, 101u}) {
      std::vector<std::thread::id> ours(n), reference(n);
      std::vector<int> hits(n, 0);
      team.for_each(0, n, [&](std::size_t i) {
        ++hits[i];
        ours[i] = std::this_thread::get_id();
      });
      parallel_for(0, n, threads, [&](std::size_t i) { reference[i] = std::this_thread::get_id(); });
      EXPECT_EQ(std::vector<int>(n, 1), hits) << threads << " threads, n " << n;
      for (std::size_t i = 1; i < n; ++i)  // same chunk boundaries
        EXPECT_EQ(ours[i] == ours[i - 1], reference[i] == reference[i - 1]) << threads << " threads, n " << n;
    }
    std::vector<int> covered(10, 0);
    team.chunks(10, 4, [&](std::size_t c, std::size_t lo, std::size_t hi) {
      EXPECT_EQ(lo, 4 * c);
      EXPECT_EQ(hi, std::min<std::size_t>(10, 4 * c + 4));
      for (std::size_t i = lo; i < hi; ++i) ++covered[i];
    });
    EXPECT_EQ(std::vector<int>(10, 1), covered);
  }
}

TEST(ParallelLoops, WorkerTeamLoopsBackToBackAndAfterPauses) {
  // Loops that follow each other at once (the workers still polling), loops after a pause (the
  // workers asleep), and loops with fewer indices than threads, on more threads than cores: each
  // index once per loop, every loop.
  for (unsigned threads : {2u, 3u, 5u}) {
    const WorkerTeam team(threads);
    std::vector<int> hits(7, 0);
    int loops = 0;
    for (int k = 0; k < 3000; ++k) {
      const std::size_t n = 1 + static_cast<std::size_t>(k) % hits.size();
      team.for_each(0, n, [&](std::size_t i) { ++hits[i]; });
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(hits[i], 1) << threads << " threads, loop " << k;
      std::fill(hits.begin(), hits.end(), 0);
      ++loops;
      if (k % 500 == 0) std::this_thread::sleep_for(5ms);
    }
    EXPECT_EQ(loops, 3000);
  }
}

TEST(ParallelLoops, RethrowTheFirstFailureNotTheRunsItCancelled) {
  // The failing call is on the second thread's share in both loops: the calling thread's own
  // (later) "cancelled" must not hide it.
  for (std::size_t cause : {1u, 0u}) {
    FailingRuns dynamic_runs{cause};
    EXPECT_EQ("cause", message_of([&] { parallel_dynamic(2, 2, std::ref(dynamic_runs)); }))
        << "parallel_dynamic, cause " << cause;
  }
  FailingRuns chunks{1};
  EXPECT_EQ("cause", message_of([&] { parallel_for(0, 2, 2, std::ref(chunks)); }));
  const WorkerTeam team(2);
  FailingRuns team_runs{1};
  EXPECT_EQ("cause", message_of([&] { team.for_each(0, 2, std::ref(team_runs)); }));
  std::vector<int> hits(4, 0);  // the team still works after a failure
  team.for_each(0, 4, [&](std::size_t i) { ++hits[i]; });
  EXPECT_EQ(std::vector<int>(4, 1), hits);
}

}  // namespace
}  // namespace sketchsurf
