#pragma once
// Disjoint sets over 0..n-1 (path halving; the smaller index becomes the root, so roots, and
// anything numbered by them, do not depend on the order of the unions' arguments).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace gsse {

template <class Index = std::uint32_t>
struct union_find {
  std::vector<Index> up;
  explicit union_find(std::size_t n) : up(n) { std::iota(up.begin(), up.end(), Index{0}); }
  Index find(Index x) {
    while (up[x] != x) x = up[x] = up[up[x]];
    return x;
  }
  void unite(Index a, Index b) {
    a = find(a), b = find(b);
    if (a != b) up[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace gsse
