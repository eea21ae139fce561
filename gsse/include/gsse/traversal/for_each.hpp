#pragma once
// Segment traversal: for_each over the segments of a domain, sequential or parallel. The parallel
// policy hands elements to threads as they come free, most expensive first (by a cost estimate):
// GSSE's "for_each over segments" that makes per-segment meshing embarrassingly parallel. The
// function must not touch other segments; results then do not depend on the thread count or on
// which thread ran which element.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <numeric>
#include <ranges>
#include <thread>
#include <vector>

#include "gsse/traversal/worker_pool.hpp"

namespace gsse::execution {
struct sequenced_policy {};
struct parallel_policy {
  unsigned threads = 0;  // 0: std::thread::hardware_concurrency()
  parallel_policy operator()(unsigned n) const { return {n}; }
};
inline constexpr sequenced_policy seq{};
inline constexpr parallel_policy par{};
/// The one meaning of a thread count across the library (for_each, parallel sort, the writers,
/// pipeline::options::threads): n threads, 0 = every hardware thread.
inline unsigned thread_count(unsigned n) { return n ? n : std::max(1u, std::thread::hardware_concurrency()); }
}  // namespace gsse::execution

namespace gsse {

template <std::ranges::random_access_range R, class F>
void for_each(execution::sequenced_policy, R&& range, F&& f) {
  for (auto&& s : range) std::invoke(f, s);
}

/// Parallel for_each over a random-access range (e.g. segments(d)). `cost(s)` estimates the work
/// of an element (default 1): elements are handed out most expensive first, each to the next free
/// thread, so one long element overlaps many short ones (beyond 64 per thread, the cheap ones in
/// short runs). The first exception thrown by any worker is rethrown after all workers have joined.
template <std::ranges::random_access_range R, class F, class Cost>
void for_each(execution::parallel_policy p, R&& range, F&& f, Cost&& cost) {
  const std::size_t n = std::ranges::size(range);
  const unsigned threads = execution::thread_count(p.threads);
  if (threads <= 1 || n <= 1) return for_each(execution::seq, range, f);
  std::vector<double> costs(n);
  for (std::size_t i = 0; i < n; ++i) costs[i] = static_cast<double>(std::invoke(cost, std::ranges::begin(range)[i]));
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return costs[a] > costs[b]; });
  // many elements: handed out in runs of that order, not one at a time. A claim is an atomic
  // increment on a line both threads write, about what a quiet element's work costs (the
  // conformer's check of 32,000 one-triangle facet pieces took 6 ms a round on the Gmsh torus,
  // docs/benchmarks.md, seventieth part). A run holds at most 1/(32 x threads) of the estimated
  // total and of the elements; an element above that goes alone. Which thread runs an element
  // never changes a result (above), so neither does this
  std::vector<std::size_t> runs;  // run k: order[runs[k], runs[k + 1])
  if (n > 64 * static_cast<std::size_t>(threads)) {
    double total = 0;
    for (double x : costs) total += x;
    const double most = total / (32.0 * threads);
    const std::size_t longest = n / (32 * static_cast<std::size_t>(threads));
    for (std::size_t i = 0; i < n;) {
      runs.push_back(i);
      double sum = costs[order[i]];
      const std::size_t first = i++;
      while (i < n && i - first < longest && sum + costs[order[i]] <= most) sum += costs[order[i++]];
    }
  } else {
    runs.resize(n);
    std::iota(runs.begin(), runs.end(), std::size_t{0});
  }
  runs.push_back(n);
  struct context {
    R& range;
    F& f;
    const std::vector<std::size_t>& order;
    const std::vector<std::size_t>& runs;
    detail::worker_pool::job job;
    std::exception_ptr error;
    std::mutex m;
  } c{range, f, order, runs, {}, {}, {}};
  c.job.n = runs.size() - 1;
  c.job.helpers = static_cast<unsigned>(std::min<std::size_t>(threads, c.job.n)) - 1;
  c.job.context = &c;
  c.job.body = [](void* self, std::size_t k) {
    auto& x = *static_cast<context*>(self);
    try {
      for (std::size_t i = x.runs[k]; i < x.runs[k + 1]; ++i) std::invoke(x.f, std::ranges::begin(x.range)[x.order[i]]);
    } catch (...) {
      std::lock_guard lock(x.m);
      if (!x.error) x.error = std::current_exception();
      x.job.next.store(x.job.n);  // stop handing out work
    }
  };
  detail::worker_pool::instance().run(c.job);
  if (c.error) std::rethrow_exception(c.error);
}

template <std::ranges::random_access_range R, class F>
void for_each(execution::parallel_policy p, R&& range, F&& f) {
  for_each(p, std::forward<R>(range), std::forward<F>(f), [](const auto&) { return 1.0; });
}

}  // namespace gsse
