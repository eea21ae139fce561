#pragma once
// A set of simplices by their sorted vertices: open addressing with linear probing, at most half
// full, built once and then only asked. For "was this face (triangle, edge) there before?" asked
// once per face of a large list: a bisection in a sorted list cost a sort and a cache miss per
// step (the conformer's clean subfacets, the refinement's faces that went and came).
#include <array>
#include <cstdint>
#include <vector>

#include "gsse/topology/simplex.hpp"

namespace gsse {

template <std::size_t N>
class key_set {
 public:
  using key = std::array<vertex_id, N>;  // sorted vertices (any fixed order works if used alike)
  key_set() = default;
  explicit key_set(const std::vector<key>& keys) {
    if (keys.empty()) return;
    std::size_t size = 16;
    while (size < 2 * keys.size()) size *= 2;
    key none;
    none.fill(no_vertex);
    slots_.assign(size, none);
    for (const key& k : keys) {
      std::size_t h = slot(k);
      while (slots_[h][0] != no_vertex && slots_[h] != k) h = (h + 1) & (slots_.size() - 1);
      slots_[h] = k;
    }
  }
  bool empty() const { return slots_.empty(); }
  bool contains(const key& k) const {
    if (slots_.empty()) return false;
    for (std::size_t h = slot(k);; h = (h + 1) & (slots_.size() - 1)) {
      if (slots_[h] == k) return true;
      if (slots_[h][0] == no_vertex) return false;
    }
  }

 private:
  std::size_t slot(const key& k) const {
    constexpr std::uint64_t mix[3] = {0x9E3779B97F4A7C15ull, 0xC2B2AE3D27D4EB4Full, 0x165667B19E3779F9ull};
    std::uint64_t x = 0;
    for (std::size_t i = 0; i < N; ++i) x ^= std::uint64_t{k[i]} * mix[i % 3] + i;
    return static_cast<std::size_t>(x >> 20) & (slots_.size() - 1);
  }
  std::vector<key> slots_;
};

}  // namespace gsse
