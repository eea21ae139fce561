#pragma once
// Dynamic uniform grid (hashed cells) over a growing point set: the conformer inserts points as it
// refines, so the static CSR grid of the front mesher does not fit here.
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "gsse/geometry/point.hpp"
#include "gsse/topology/simplex.hpp"

namespace gsse::conformer::detail {

template <std::size_t D>
class spatial_hash {
 public:
  spatial_hash(const point<D>& origin, double h) : o_(origin), inv_(1.0 / h) {}
  void insert(vertex_id v, const point<D>& p) { cells_[key(cell(p))].push_back(v); }
  /// Calls f(v) for the points in cells overlapping [lo, hi], cells in a fixed order.
  template <class F>
  void visit(const point<D>& lo, const point<D>& hi, F&& f) const {
    const auto a = cell(lo), b = cell(hi);
    std::size_t count = 1;
    for (std::size_t k = 0; k < D; ++k) count *= static_cast<std::size_t>(b[k] - a[k] + 1);
    if (count > 4 * cells_.size() + 64) {  // huge box: scan occupied cells instead
      std::vector<std::uint64_t> keys;
      for (const auto& [k, ids] : cells_) keys.push_back(k);
      std::sort(keys.begin(), keys.end());
      for (auto k : keys)
        for (vertex_id v : cells_.at(k)) f(v);
      return;
    }
    std::array<long, D> c = a;
    for (;;) {
      if (auto it = cells_.find(key(c)); it != cells_.end())
        for (vertex_id v : it->second) f(v);
      std::size_t k = 0;
      while (k < D && ++c[k] > b[k]) c[k] = a[k], ++k;
      if (k == D) break;
    }
  }

 private:
  std::array<long, D> cell(const point<D>& p) const {
    std::array<long, D> c;
    for (std::size_t k = 0; k < D; ++k) {
      const double x = std::floor((p[k] - o_[k]) * inv_);
      c[k] = static_cast<long>(std::clamp(x, -1e9, 1e9));
    }
    return c;
  }
  static std::uint64_t key(const std::array<long, D>& c) {
    std::uint64_t h = 0;
    for (std::size_t k = 0; k < D; ++k) h = h * 0x100000001B3ull ^ static_cast<std::uint64_t>(c[k] + (1l << 30));
    return h;
  }
  point<D> o_;
  double inv_;
  std::unordered_map<std::uint64_t, std::vector<vertex_id>> cells_;
};

}  // namespace gsse::conformer::detail
