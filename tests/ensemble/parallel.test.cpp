// tumble::RunPool and tumble::for_each_run (include/tumble/ensemble/parallel.hpp): every run done
// once; one worker per thread, kept from one for_each to the next; threads = 1 runs in order in
// the calling thread; threads = 2 uses at most two threads, and a second one does take part.

#include "tumble/ensemble/parallel.hpp"

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "support/catch.hpp"

namespace {

/// A worker that counts how many were made.
struct Counted {
  static inline std::atomic<int> made{0};
  int runs = 0;
  Counted() { ++made; }
};

}  // namespace

TEST_CASE("parallel: threads = 1 runs in order in the calling thread, one worker",
          "[ensemble][parallel]") {
  Counted::made = 0;
  std::vector<std::size_t> order;
  const auto caller = std::this_thread::get_id();
  bool elsewhere = false;
  tumble::for_each_run<Counted>(50, {.threads = 1}, [&](Counted& w, std::size_t i) {
    order.push_back(i);
    ++w.runs;
    elsewhere = elsewhere || std::this_thread::get_id() != caller;
  });
  REQUIRE(order.size() == 50);
  for (std::size_t i = 0; i < order.size(); ++i) {
    CHECK(order[i] == i);
  }
  CHECK_FALSE(elsewhere);
  CHECK(Counted::made == 1);
}

TEST_CASE("parallel: threads = 2 does every run once on at most two threads, both taking part",
          "[ensemble][parallel]") {
  Counted::made = 0;
  constexpr std::size_t n = 200;
  std::vector<std::atomic<int>> done(n);
  std::mutex m;
  std::set<std::thread::id> ids;
  std::atomic<bool> second_seen{false};
  tumble::RunPool<Counted> pool({.threads = 2, .grain = 1});
  pool.for_each(0, n, [&](Counted& w, std::size_t i) {
    ++done[i];
    ++w.runs;
    {
      const std::lock_guard<std::mutex> lock(m);
      ids.insert(std::this_thread::get_id());
      if (ids.size() > 1) {
        second_seen = true;
      }
    }
    // Run 0 waits (at most 10 s) for another thread to take a run, so that a second thread
    // is seen to work whatever the load of the machine.
    if (i == 0) {
      const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (!second_seen && std::chrono::steady_clock::now() < until) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    }
  });
  for (std::size_t i = 0; i < n; ++i) {
    CHECK(done[i] == 1);
  }
  CHECK(ids.size() == 2);
  const int workers = Counted::made;
  CHECK(workers >= 1);
  CHECK(workers <= 2);
  // The workers are kept: a second for_each makes no new one.
  pool.for_each(0, n, [&](Counted&, std::size_t i) { ++done[i]; });
  CHECK(Counted::made == workers);
  for (std::size_t i = 0; i < n; ++i) {
    CHECK(done[i] == 2);
  }
}

TEST_CASE("parallel: an exception that leaves a run is rethrown; bad options throw",
          "[ensemble][parallel]") {
  for (const int threads : {1, 2}) {
    INFO(threads << " threads");
    CHECK_THROWS_AS(tumble::for_each_run<int>(20, {.threads = threads},
                                              [](int&, std::size_t i) {
                                                if (i == 7) {
                                                  throw std::runtime_error("run 7");
                                                }
                                              }),
                    std::runtime_error);
  }
  const auto nothing = [](int&, std::size_t) {};
  CHECK_THROWS_AS(tumble::for_each_run<int>(1, {.threads = -1}, nothing), std::invalid_argument);
  CHECK_THROWS_AS(tumble::for_each_run<int>(1, {.grain = 0}, nothing), std::invalid_argument);
}
