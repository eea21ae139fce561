#pragma once
// Dynamic uniform grid (hashed cells) over a growing point set: the conformer inserts points as it
// refines, so the static CSR grid of the front mesher does not fit here. Cells live in an
// open-addressing table (key -> bucket), probed once per cell a scan meets.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "gsse/geometry/point.hpp"
#include "gsse/topology/simplex.hpp"

namespace gsse::conformer::detail {

template <std::size_t D>
class spatial_hash {
 public:
  spatial_hash(const point<D>& origin, double h) : o_(origin), inv_(1.0 / h) { rehash(64); }
  void insert(vertex_id v, const point<D>& p) {
    const std::uint64_t k = key(cell(p));
    std::size_t i = slot(k);
    if (keys_[i] == empty) {
      keys_[i] = k;
      vals_[i] = static_cast<std::uint32_t>(buckets_.size());
      buckets_.emplace_back();
      if (2 * buckets_.size() > keys_.size()) {
        rehash(2 * keys_.size());
        i = slot(k);
      }
    }
    buckets_[vals_[i]].push_back(v);
  }
  /// Calls f(v) for the points in cells overlapping [lo, hi], cells in a fixed order.
  template <class F>
  void visit(const point<D>& lo, const point<D>& hi, F&& f) const {
    const auto a = cell(lo), b = cell(hi);
    std::size_t count = 1;
    for (std::size_t k = 0; k < D; ++k) count *= static_cast<std::size_t>(b[k] - a[k] + 1);
    if (count > 4 * buckets_.size() + 64) {  // huge box: scan occupied cells instead, by key
      std::vector<std::pair<std::uint64_t, std::uint32_t>> order;
      for (std::size_t i = 0; i < keys_.size(); ++i)
        if (keys_[i] != empty) order.push_back({keys_[i], vals_[i]});
      std::sort(order.begin(), order.end());
      for (auto [k, b] : order)
        for (vertex_id v : buckets_[b]) f(v);
      return;
    }
    std::array<long, D> c = a;
    for (;;) {
      const std::uint64_t k = key(c);
      const std::size_t i = slot(k);
      if (keys_[i] == k)
        for (vertex_id v : buckets_[vals_[i]]) f(v);
      std::size_t j = 0;
      while (j < D && ++c[j] > b[j]) c[j] = a[j], ++j;
      if (j == D) break;
    }
  }

 private:
  static constexpr std::uint64_t empty = ~std::uint64_t{0};
  std::array<long, D> cell(const point<D>& p) const {
    std::array<long, D> c;
    for (std::size_t k = 0; k < D; ++k) {
      const double x = std::floor((p[k] - o_[k]) * inv_);
      c[k] = static_cast<long>(std::clamp(x, -1e9, 1e9));
    }
    return c;
  }
  /// Cell coordinates packed in 21 bits each (offset by 2^20), never equal to `empty`.
  static std::uint64_t key(const std::array<long, D>& c) {
    std::uint64_t h = 0;
    for (std::size_t k = 0; k < D; ++k) h = (h << 21) | (static_cast<std::uint64_t>(c[k] + (1l << 20)) & 0x1FFFFF);
    return h;
  }
  /// The slot holding key k, or the empty slot where it belongs.
  std::size_t slot(std::uint64_t k) const {
    std::uint64_t h = k * 0x9E3779B97F4A7C15ull;
    for (std::size_t i = (h ^ (h >> 31)) & mask_;; i = (i + 1) & mask_)
      if (keys_[i] == k || keys_[i] == empty) return i;
  }
  void rehash(std::size_t n) {
    std::vector<std::uint64_t> old_keys = std::move(keys_);
    std::vector<std::uint32_t> old_vals = std::move(vals_);
    keys_.assign(n, empty);
    vals_.assign(n, 0);
    mask_ = n - 1;
    for (std::size_t i = 0; i < old_keys.size(); ++i)
      if (old_keys[i] != empty) {
        const std::size_t j = slot(old_keys[i]);
        keys_[j] = old_keys[i];
        vals_[j] = old_vals[i];
      }
  }
  point<D> o_;
  double inv_;
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> vals_;
  std::size_t mask_ = 0;
  std::vector<std::vector<vertex_id>> buckets_;
};

}  // namespace gsse::conformer::detail
