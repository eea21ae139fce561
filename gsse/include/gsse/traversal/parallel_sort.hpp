#pragma once
// Stable sort on several threads: equal pieces are stable-sorted concurrently, then merged pairwise
// (the merges of one level concurrently too). Piece boundaries depend on the thread count, but a
// stable sort's result does not, so the output is std::stable_sort's for any number of threads.
#include <algorithm>
#include <cstddef>
#include <functional>
#include <iterator>
#include <thread>
#include <vector>

#include "gsse/traversal/for_each.hpp"

namespace gsse {

template <std::random_access_iterator It, class Compare = std::less<>>
void stable_sort(execution::parallel_policy p, It first, It last, Compare comp = {}) {
  const auto n = static_cast<std::size_t>(last - first);
  const unsigned threads = execution::thread_count(p.threads);
  constexpr std::size_t min_piece = 1 << 12;  // below this, threads cost more than they save
  const std::size_t pieces = std::min<std::size_t>(threads, n / min_piece);
  if (pieces <= 1) return std::stable_sort(first, last, comp);
  std::vector<It> cut(pieces + 1);
  for (std::size_t i = 0; i <= pieces; ++i) cut[i] = first + static_cast<std::ptrdiff_t>(n * i / pieces);
  std::vector<std::size_t> ids(pieces);
  for (std::size_t i = 0; i < pieces; ++i) ids[i] = i;
  for_each(p, ids, [&](std::size_t i) { std::stable_sort(cut[i], cut[i + 1], comp); });
  // merge neighbouring runs until one is left; a run [cut[i], cut[i+1]) stays sorted and stable
  for (std::size_t width = 1; width < pieces; width *= 2) {
    std::vector<std::size_t> left;
    for (std::size_t i = 0; i + width < pieces; i += 2 * width) left.push_back(i);
    for_each(p, left, [&](std::size_t i) {
      const std::size_t end = std::min(pieces, i + 2 * width);
      std::inplace_merge(cut[i], cut[i + width], cut[end], comp);
    });
  }
}

}  // namespace gsse
