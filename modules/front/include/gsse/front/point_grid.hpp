#pragma once
// Uniform grid over a point set (G = 2 or 3 grid coordinates), in CSR form: the candidate index of
// the gift-wrapping search. Built once per point set and shared read-only by every segment.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "gsse/topology/simplex.hpp"

namespace gsse::front {

template <std::size_t G>
class point_grid {
 public:
  using coord = std::array<double, G>;

  point_grid() = default;
  /// `coords[i]` are the grid coordinates of point i; `per_cell` is the target occupancy.
  explicit point_grid(std::span<const coord> coords, double per_cell = 2.0) { build(coords, {}, per_cell); }
  /// Grid over a subset: coords[i] belongs to vertex ids[i].
  point_grid(std::span<const coord> coords, std::span<const vertex_id> ids, double per_cell = 2.0) {
    build(coords, ids, per_cell);
  }

  void build(std::span<const coord> coords, std::span<const vertex_id> ids, double per_cell = 2.0) {
    n_ = coords.size();
    lo_.fill(0);
    hi_.fill(0);
    if (coords.empty()) {
      dims_.fill(1);
      start_.assign(2, 0);
      return;
    }
    lo_ = hi_ = coords[0];
    for (const auto& c : coords)
      for (std::size_t a = 0; a < G; ++a) {
        lo_[a] = std::min(lo_[a], c[a]);
        hi_[a] = std::max(hi_[a], c[a]);
      }
    double volume = 1;
    int flat = 0;
    for (std::size_t a = 0; a < G; ++a) {
      const double e = hi_[a] - lo_[a];
      if (e > 0) volume *= e; else ++flat;
    }
    const double cells = std::max(1.0, static_cast<double>(n_) / per_cell);
    double h = std::pow(volume / cells, 1.0 / static_cast<double>(G - static_cast<std::size_t>(flat)));
    if (!(h > 0) || !std::isfinite(h)) h = 1;
    std::size_t total = 1;
    for (std::size_t a = 0; a < G; ++a) {
      const double e = hi_[a] - lo_[a];
      dims_[a] = std::clamp<long>(static_cast<long>(e / h) + 1, 1, 1 << 20);
      total *= static_cast<std::size_t>(dims_[a]);
    }
    while (total > 4 * n_ + 16) {  // guard against degenerate extents
      total = 1;
      for (std::size_t a = 0; a < G; ++a) {
        dims_[a] = std::max<long>(1, dims_[a] / 2);
        total *= static_cast<std::size_t>(dims_[a]);
      }
    }
    for (std::size_t a = 0; a < G; ++a) {
      const double e = hi_[a] - lo_[a];
      inv_[a] = e > 0 ? static_cast<double>(dims_[a]) / e : 0.0;
    }
    start_.assign(total + 1, 0);
    std::vector<std::uint32_t> cell_of(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      cell_of[i] = static_cast<std::uint32_t>(linear(cell_index(coords[i])));
      ++start_[cell_of[i] + 1];
    }
    for (std::size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
    ids_.resize(n_);
    xyz_.resize(n_);
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < n_; ++i) {
      const auto k = fill[cell_of[i]]++;
      ids_[k] = ids.empty() ? static_cast<vertex_id>(i) : ids[i];
      xyz_[k] = coords[i];
    }
  }

  std::array<long, G> cell_index(const coord& c) const {
    std::array<long, G> k;
    for (std::size_t a = 0; a < G; ++a)
      k[a] = std::clamp<long>(static_cast<long>(std::floor((c[a] - lo_[a]) * inv_[a])), 0, dims_[a] - 1);
    return k;
  }
  std::size_t linear(const std::array<long, G>& k) const {
    std::size_t r = 0;
    for (std::size_t a = G; a-- > 0;) r = r * static_cast<std::size_t>(dims_[a]) + static_cast<std::size_t>(k[a]);
    return r;
  }
  /// Calls f(vertex_id, const coord&) for every point in grid cells overlapping [lo, hi].
  /// Returns false (and stops) if f returns false.
  template <class F>
  bool visit_box(const coord& lo, const coord& hi, F&& f) const {
    return visit_cells(lo, hi, [&](std::size_t cell) { return visit_cell(cell, f); });
  }
  /// Calls g(linear cell index) for every grid cell overlapping [lo, hi]; stops if g returns false.
  template <class F>
  bool visit_cells(const coord& lo, const coord& hi, F&& g) const {
    const auto a = cell_index(lo), b = cell_index(hi);
    if constexpr (G == 2) {
      for (long y = a[1]; y <= b[1]; ++y)
        for (long x = a[0]; x <= b[0]; ++x)
          if (!g(linear({x, y}))) return false;
    } else {
      for (long z = a[2]; z <= b[2]; ++z)
        for (long y = a[1]; y <= b[1]; ++y)
          for (long x = a[0]; x <= b[0]; ++x)
            if (!g(linear({x, y, z}))) return false;
    }
    return true;
  }
  std::size_t cell_count() const { return start_.size() - 1; }
  template <class F>
  bool visit_cell(std::size_t cell, F& f) const {
    for (auto k = start_[cell]; k < start_[cell + 1]; ++k)
      if (!f(ids_[k], xyz_[k])) return false;
    return true;
  }
  std::size_t size() const { return n_; }
  const coord& lower() const { return lo_; }
  const coord& upper() const { return hi_; }
  /// Edge length of a grid cell along axis a.
  double cell_size(std::size_t a) const { return inv_[a] > 0 ? 1.0 / inv_[a] : 0.0; }

 private:
  std::size_t n_ = 0;
  coord lo_{}, hi_{}, inv_{};
  std::array<long, G> dims_{};
  std::vector<std::uint32_t> start_;
  std::vector<vertex_id> ids_;
  std::vector<coord> xyz_;
};

}  // namespace gsse::front
