#pragma once
// Segment traversal: for_each over the segments of a domain, sequential or parallel. The parallel
// policy partitions the segment range into one part per thread, balanced by a cost estimate
// (longest-first greedy assignment);
// GSSE's "for_each over segments" that makes per-segment meshing embarrassingly parallel. The
// function must not touch other segments; results then do not depend on the thread count.
#include <algorithm>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <numeric>
#include <ranges>
#include <thread>
#include <vector>

namespace gsse::execution {
struct sequenced_policy {};
struct parallel_policy {
  unsigned threads = 0;  // 0: std::thread::hardware_concurrency()
  parallel_policy operator()(unsigned n) const { return {n}; }
};
inline constexpr sequenced_policy seq{};
inline constexpr parallel_policy par{};
}  // namespace gsse::execution

namespace gsse {

template <std::ranges::random_access_range R, class F>
void for_each(execution::sequenced_policy, R&& range, F&& f) {
  for (auto&& s : range) std::invoke(f, s);
}

/// Parallel for_each over a random-access range (e.g. segments(d)). `cost(s)` estimates the work
/// of an element (default 1); blocks are balanced by it. The first exception thrown by any
/// worker is rethrown after all workers have joined.
template <std::ranges::random_access_range R, class F, class Cost>
void for_each(execution::parallel_policy p, R&& range, F&& f, Cost&& cost) {
  const std::size_t n = std::ranges::size(range);
  unsigned threads = p.threads ? p.threads : std::max(1u, std::thread::hardware_concurrency());
  if (threads <= 1 || n <= 1) return for_each(execution::seq, range, f);
  std::vector<double> costs(n);
  for (std::size_t i = 0; i < n; ++i) costs[i] = static_cast<double>(std::invoke(cost, std::ranges::begin(range)[i]));
  // Order by cost so the most expensive elements start first, then deal blocks from that order.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return costs[a] > costs[b]; });
  std::vector<double> sorted(n);
  for (std::size_t i = 0; i < n; ++i) sorted[i] = costs[order[i]];
  // Greedy longest-processing-time assignment gives balanced partitions of the range.
  std::vector<std::vector<std::size_t>> parts(std::min<std::size_t>(threads, n));
  std::vector<double> load(parts.size(), 0.0);
  for (std::size_t i : order) {
    auto k = static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    parts[k].push_back(i);
    load[k] += costs[i];
  }
  std::exception_ptr error;
  std::mutex m;
  {
    std::vector<std::jthread> pool;
    for (auto& part : parts)
      pool.emplace_back([&, part] {
        try {
          for (std::size_t i : part) std::invoke(f, std::ranges::begin(range)[i]);
        } catch (...) {
          std::lock_guard lock(m);
          if (!error) error = std::current_exception();
        }
      });
  }
  if (error) std::rethrow_exception(error);
}

template <std::ranges::random_access_range R, class F>
void for_each(execution::parallel_policy p, R&& range, F&& f) {
  for_each(p, std::forward<R>(range), std::forward<F>(f), [](const auto&) { return 1.0; });
}

}  // namespace gsse
