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
    step_.fill(0);
    extent_ = 0;
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
      // cells half as long along axis 0 as a cube and correspondingly wider across: a search
      // visits rows of cells along axis 0, whose points are contiguous, so fewer and longer
      // rows clipped finely along the row beat cubes (front bench: +12-20%)
      const double ha = h * (a == 0 ? 0.5 : std::pow(0.5, -1.0 / static_cast<double>(G - 1)));
      dims_[a] = std::clamp<long>(static_cast<long>(e / ha) + 1, 1, 1 << 20);
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
      step_[a] = e / static_cast<double>(dims_[a]);
      extent_ = std::max(extent_, e);
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
    positions_.assign(ids.empty() ? n_ : 0, 0);
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < n_; ++i) {
      const auto k = fill[cell_of[i]]++;
      ids_[k] = ids.empty() ? static_cast<vertex_id>(i) : ids[i];
      if (ids.empty()) positions_[i] = k;
      xyz_[k] = coords[i];
    }
  }

  /// Cell index along axis a of coordinate x, clamped to the grid (also for huge or infinite x).
  long axis_index(std::size_t a, double x) const {
    const double t = (x - lo_[a]) * inv_[a];
    if (!(t > 0)) return 0;  // also NaN (an infinite x on a flat axis)
    return t >= static_cast<double>(dims_[a]) ? dims_[a] - 1 : static_cast<long>(t);
  }
  std::array<long, G> cell_index(const coord& c) const {
    std::array<long, G> k;
    for (std::size_t a = 0; a < G; ++a) k[a] = axis_index(a, c[a]);
    return k;
  }
  std::size_t linear(const std::array<long, G>& k) const {
    std::size_t r = 0;
    for (std::size_t a = G; a-- > 0;) r = r * static_cast<std::size_t>(dims_[a]) + static_cast<std::size_t>(k[a]);
    return r;
  }
  /// Calls f(vertex_id, const coord&) for every point in grid cells overlapping [lo, hi].
  /// Returns false (and stops) if f returns false.
  /// With Local, f gets the point's position in the grid (see coords()) instead of its id.
  template <bool Local = false, class F>
  bool visit_box(const coord& lo, const coord& hi, F&& f) const {
    return visit_cells(lo, hi, [&](std::size_t cell) { return visit_cell<Local>(cell, f); });
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
  /// Calls g(first, last) for the runs of consecutive grid cells (linear indices first..last, one
  /// run per row of cells along axis 0) that meet the ball (c, r) and the half-space
  /// {x : dot(n, x) >= d} (n = 0, d <= 0: no half-space). Each row is clipped to the ball's slice
  /// and to the half-space. Conservative: cell bounds are padded by 1e-10 of the grid's extent
  /// against rounding in the point-to-cell assignment.
  template <class F>
  bool visit_rows(const coord& c, double r, const coord& n, double d, F&& g) const {
    coord lo, hi;
    for (std::size_t a = 0; a < G; ++a) lo[a] = c[a] - r, hi[a] = c[a] + r;
    const auto ka = cell_index(lo), kb = cell_index(hi);
    const double pad = 1e-10 * extent_;
    const double r2 = (r + pad) * (r + pad);
    const double inv_n0 = n[0] != 0 ? 1.0 / n[0] : 0.0;
    // per higher axis and cell: squared distance of c to the cell's slab, and the largest
    // value of n[a] * x[a] over it
    constexpr long small_span = 64;  // on the stack; larger balls (rare) on the heap
    std::array<std::array<double, small_span>, G> gap2_small, top_small;
    std::vector<double> heap;
    std::array<double*, G> gap2{}, top{};
    long span = 0;
    for (std::size_t a = 1; a < G; ++a) span = std::max(span, kb[a] - ka[a] + 1);
    if (span > small_span) heap.resize(2 * G * static_cast<std::size_t>(span));
    for (std::size_t a = 1; a < G; ++a) {
      gap2[a] = span > small_span ? heap.data() + (2 * a) * static_cast<std::size_t>(span) : gap2_small[a].data();
      top[a] = span > small_span ? heap.data() + (2 * a + 1) * static_cast<std::size_t>(span) : top_small[a].data();
      for (long k = ka[a]; k <= kb[a]; ++k) {
        const double clo = lo_[a] + static_cast<double>(k) * step_[a] - pad, chi = clo + step_[a] + 2 * pad;
        const double e = c[a] < clo ? clo - c[a] : c[a] > chi ? c[a] - chi : 0.0;
        gap2[a][static_cast<std::size_t>(k - ka[a])] = e * e;
        top[a][static_cast<std::size_t>(k - ka[a])] = n[a] * (n[a] > 0 ? chi : clo);
      }
    }
    // one row: rest = r2 minus the higher axes' gaps, m = max of dot(n, x) - d without axis 0
    auto row = [&](double rest, double m, std::size_t base) {
      const double s = std::sqrt(rest);
      double xa = c[0] - s, xb = c[0] + s;
      if (n[0] > 0) xa = std::max(xa, -m * inv_n0 - pad);
      else if (n[0] < 0) xb = std::min(xb, -m * inv_n0 + pad);
      else if (m < 0) return true;
      if (!(xa <= xb)) return true;
      const long x0 = std::max(ka[0], axis_index(0, xa)), x1 = std::min(kb[0], axis_index(0, xb));
      return x0 > x1 || g(base + static_cast<std::size_t>(x0), base + static_cast<std::size_t>(x1));
    };
    if constexpr (G == 2) {
      for (long y = ka[1]; y <= kb[1]; ++y) {
        const auto j = static_cast<std::size_t>(y - ka[1]);
        const double rest = r2 - gap2[1][j];
        if (rest >= 0 && !row(rest, top[1][j] - d, static_cast<std::size_t>(y) * static_cast<std::size_t>(dims_[0])))
          return false;
      }
    } else {
      for (long z = ka[2]; z <= kb[2]; ++z) {
        const auto i = static_cast<std::size_t>(z - ka[2]);
        const double rz = r2 - gap2[2][i];
        if (rz < 0) continue;
        for (long y = ka[1]; y <= kb[1]; ++y) {
          const auto j = static_cast<std::size_t>(y - ka[1]);
          const double rest = rz - gap2[1][j];
          if (rest >= 0 && !row(rest, top[1][j] + top[2][i] - d, linear({0, y, z}))) return false;
        }
      }
    }
    return true;
  }
  /// Calls g(linear cell index) for every cell of the runs visit_rows(c, r, n, d) lists.
  template <class F>
  bool visit_cells(const coord& c, double r, const coord& n, double d, F&& g) const {
    return visit_rows(c, r, n, d, [&](std::size_t first, std::size_t last) {
      for (std::size_t cell = first; cell <= last; ++cell)
        if (!g(cell)) return false;
      return true;
    });
  }
  /// Calls f(vertex_id, const coord&) for every point in the cells visit_rows(c, r, n, d) lists:
  /// the points of a run of cells are contiguous, so each row is one loop.
  template <bool Local = false, class F>
  bool visit_ball(const coord& c, double r, const coord& n, double d, F&& f) const {
    return visit_rows(c, r, n, d, [&](std::size_t first, std::size_t last) {
      for (auto k = start_[first]; k < start_[last + 1]; ++k)
        if (!f(Local ? static_cast<vertex_id>(k) : ids_[k], xyz_[k])) return false;
      return true;
    });
  }
  std::size_t cell_count() const { return start_.size() - 1; }
  /// Number of points in the grid cells overlapping [lo, hi]: at least the points in the box.
  std::size_t count_box(const coord& lo, const coord& hi) const {
    if (n_ == 0) return 0;
    const auto a = cell_index(lo), b = cell_index(hi);
    std::size_t n = 0;
    auto row = [&](std::array<long, G> first) {  // rows are contiguous in the point array
      auto last = first;
      first[0] = a[0], last[0] = b[0];
      n += start_[linear(last) + 1] - start_[linear(first)];
    };
    if constexpr (G == 2) {
      for (long y = a[1]; y <= b[1]; ++y) row({0, y});
    } else {
      for (long z = a[2]; z <= b[2]; ++z)
        for (long y = a[1]; y <= b[1]; ++y) row({0, y, z});
    }
    return n;
  }

  /// Mean edge length of a grid cell over the non-flat axes.
  double mean_step() const {
    double s = 0;
    int k = 0;
    for (std::size_t a = 0; a < G; ++a)
      if (step_[a] > 0) s += step_[a], ++k;
    return k ? s / k : 1.0;
  }
  template <bool Local = false, class F>
  bool visit_cell(std::size_t cell, F& f) const {
    for (auto k = start_[cell]; k < start_[cell + 1]; ++k)
      if (!f(Local ? static_cast<vertex_id>(k) : ids_[k], xyz_[k])) return false;
    return true;
  }
  std::size_t size() const { return n_; }
  /// The grid coordinates in grid order: spatially coherent, which is why the front mesher works
  /// on positions in this array rather than on point ids.
  std::span<const coord> coords() const { return xyz_; }
  /// The id of the point at position k of coords().
  vertex_id id_at(std::size_t k) const { return ids_[k]; }
  /// True if built over points 0..size()-1 (not a subset): position() is available.
  bool dense() const { return positions_.size() == n_; }
  /// The position in coords() of point v (dense grids).
  std::uint32_t position(vertex_id v) const { return positions_[v]; }
  const coord& lower() const { return lo_; }
  const coord& upper() const { return hi_; }
  /// Edge length of a grid cell along axis a.
  double cell_size(std::size_t a) const { return step_[a]; }

 private:
  std::size_t n_ = 0;
  coord lo_{}, hi_{}, inv_{}, step_{};
  double extent_ = 0;
  std::array<long, G> dims_{};
  std::vector<std::uint32_t> start_;
  std::vector<vertex_id> ids_;
  std::vector<std::uint32_t> positions_;  // dense grids: position of point i
  std::vector<coord> xyz_;
};

}  // namespace gsse::front
