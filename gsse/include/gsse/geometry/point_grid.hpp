#pragma once
// Grid over a point set (G = 2 or 3 grid coordinates), in CSR form: the candidate index of the
// front mesher's gift-wrapping search (built once per point set and shared read-only by every
// segment) and of the verifier's empty-ball check.
//
// Uniform where the points are: a grid sized for the mean density. Where they crowd (a conforming
// mesh grades its boundary points towards small input angles by powers of two, so a single cell of
// the uniform grid can hold most of the points: 15,929 of 21,000 on a CAD hammer), a cell holding
// more than `crowded` points carries a grid of its own over its points, recursively: the searches
// descend into it and read only its cells that meet their ball or box. The points of a cell stay
// contiguous (in its own grid's order), so a cell's range and a row's are unchanged.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "gsse/topology/simplex.hpp"

namespace gsse::geometry {

template <std::size_t G>
class point_grid {
 public:
  using coord = std::array<double, G>;

  point_grid() { build({}, {}); }
  /// `coords[i]` are the grid coordinates of point i; `per_cell` is the target occupancy.
  explicit point_grid(std::span<const coord> coords, double per_cell = 2.0) { build(coords, {}, per_cell); }
  /// Grid over a subset: coords[i] belongs to vertex ids[i].
  point_grid(std::span<const coord> coords, std::span<const vertex_id> ids, double per_cell = 2.0) {
    build(coords, ids, per_cell);
  }

  void build(std::span<const coord> coords, std::span<const vertex_id> ids, double per_cell = 2.0) {
    n_ = coords.size();
    levels_.assign(1, level{});
    extent_ = 0;
    ids_.resize(n_);
    xyz_.resize(n_);
    positions_.assign(ids.empty() ? n_ : 0, 0);
    for (std::size_t i = 0; i < n_; ++i) {
      ids_[i] = ids.empty() ? static_cast<vertex_id>(i) : ids[i];
      xyz_[i] = coords[i];
    }
    split(0, 0, static_cast<std::uint32_t>(n_), per_cell);
    for (std::size_t a = 0; a < G; ++a) extent_ = std::max(extent_, levels_[0].hi[a] - levels_[0].lo[a]);
    // cells too crowded for the uniform grid get their own, breadth first (levels_ grows)
    const std::size_t crowded = std::max<std::size_t>(32, static_cast<std::size_t>(16 * per_cell));
    std::vector<int> depth(1, 0);
    for (std::size_t L = 0; L < levels_.size(); ++L) {
      if (depth[L] >= max_depth) continue;
      const std::size_t cells = levels_[L].start.size() - 1;
      for (std::size_t cell = 0; cell < cells; ++cell) {
        const auto b = levels_[L].start[cell], e = levels_[L].start[cell + 1];
        if (e - b <= crowded) continue;
        const auto child = static_cast<std::int32_t>(levels_.size());
        levels_.emplace_back();
        if (!split(levels_.size() - 1, b, e, per_cell)) {  // one cell: nothing gained
          levels_.pop_back();
          continue;
        }
        if (levels_[L].child.empty()) levels_[L].child.assign(cells, -1);
        levels_[L].child[cell] = child;
        depth.push_back(depth[L] + 1);
      }
    }
    if (!ids.empty()) return;
    for (std::size_t k = 0; k < n_; ++k) positions_[ids_[k]] = static_cast<std::uint32_t>(k);
  }

  /// Cell index along axis a of coordinate x, clamped to the grid (also for huge or infinite x).
  long axis_index(std::size_t a, double x) const { return axis_index(levels_[0], a, x); }
  std::array<long, G> cell_index(const coord& c) const {
    std::array<long, G> k;
    for (std::size_t a = 0; a < G; ++a) k[a] = axis_index(a, c[a]);
    return k;
  }
  std::size_t linear(const std::array<long, G>& k) const { return linear(levels_[0], k); }
  /// Calls f(vertex_id, const coord&) for every point in grid cells overlapping [lo, hi] (the
  /// finest cells: a crowded cell's own grid is read where it overlaps the box).
  /// Returns false (and stops) if f returns false.
  /// With Local, f gets the point's position in the grid (see coords()) instead of its id.
  template <bool Local = false, class F>
  bool visit_box(const coord& lo, const coord& hi, F&& f) const {
    return box_ranges(levels_[0], lo, hi, [&](std::uint32_t b, std::uint32_t e) { return visit_range<Local>(b, e, f); });
  }
  /// Calls g(linear cell index) for every cell of the uniform (top) grid overlapping [lo, hi];
  /// stops if g returns false.
  template <class F>
  bool visit_cells(const coord& lo, const coord& hi, F&& g) const {
    return cells_of(levels_[0], lo, hi, g);
  }
  /// Calls g(first, last) for the runs of consecutive cells of the top grid (linear indices
  /// first..last, one run per row of cells along axis 0) that meet the ball (c, r) and the
  /// half-space {x : dot(n, x) >= d} (n = 0, d <= 0: no half-space). Each row is clipped to the
  /// ball's slice and to the half-space. Conservative: cell bounds are padded by 1e-10 of the
  /// grid's extent against rounding in the point-to-cell assignment.
  template <class F>
  bool visit_rows(const coord& c, double r, const coord& n, double d, F&& g) const {
    return rows(levels_[0], c, r, n, d, g);
  }
  /// Calls g(linear cell index) for every cell of the top grid the runs visit_rows lists.
  template <class F>
  bool visit_cells(const coord& c, double r, const coord& n, double d, F&& g) const {
    return visit_rows(c, r, n, d, [&](std::size_t first, std::size_t last) {
      for (std::size_t cell = first; cell <= last; ++cell)
        if (!g(cell)) return false;
      return true;
    });
  }
  /// Calls f(vertex_id, const coord&) for every point in the cells visit_rows(c, r, n, d) lists,
  /// descending into crowded cells' own grids the same way: the points of a run of cells are
  /// contiguous, so each row is one loop.
  template <bool Local = false, class F>
  bool visit_ball(const coord& c, double r, const coord& n, double d, F&& f) const {
    return ball_ranges(levels_[0], c, r, n, d, [&](std::uint32_t b, std::uint32_t e) { return visit_range<Local>(b, e, f); });
  }
  /// visit_ball without a half-space: every point of the cells meeting the ball (c, r).
  template <bool Local = false, class F>
  bool visit_ball(const coord& c, double r, F&& f) const {
    return visit_ball<Local>(c, r, coord{}, 0.0, std::forward<F>(f));
  }
  std::size_t cell_count() const { return levels_[0].start.size() - 1; }
  /// Number of points in the finest cells overlapping [lo, hi]: at least the points in the box.
  std::size_t count_box(const coord& lo, const coord& hi) const {
    if (n_ == 0) return 0;
    std::size_t n = 0;
    box_ranges(levels_[0], lo, hi, [&](std::uint32_t b, std::uint32_t e) {
      n += e - b;
      return true;
    });
    return n;
  }
  /// Levels of grids (1: uniform, no cell crowded).
  std::size_t levels() const { return levels_.size(); }

  /// Mean edge length of a cell of the top grid over the non-flat axes.
  double mean_step() const {
    double s = 0;
    int k = 0;
    for (std::size_t a = 0; a < G; ++a)
      if (levels_[0].step[a] > 0) s += levels_[0].step[a], ++k;
    return k ? s / k : 1.0;
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
  const coord& lower() const { return levels_[0].lo; }
  const coord& upper() const { return levels_[0].hi; }
  /// Edge length of a cell of the top grid along axis a.
  double cell_size(std::size_t a) const { return levels_[0].step[a]; }

 private:
  static constexpr int max_depth = 12;
  /// One uniform grid: the top one over all points, or a crowded cell's over the cell's points.
  struct level {
    coord lo{}, hi{}, inv{}, step{};
    std::array<long, G> dims{};
    std::vector<std::uint32_t> start;  // per cell, its first position in ids_/xyz_ (absolute); one past
    std::vector<std::int32_t> child;   // per cell, the level of its own grid or -1 (empty: none)
  };

  static long axis_index(const level& L, std::size_t a, double x) {
    const double t = (x - L.lo[a]) * L.inv[a];
    if (!(t > 0)) return 0;  // also NaN (an infinite x on a flat axis)
    return t >= static_cast<double>(L.dims[a]) ? L.dims[a] - 1 : static_cast<long>(t);
  }
  static std::array<long, G> cell_index(const level& L, const coord& c) {
    std::array<long, G> k;
    for (std::size_t a = 0; a < G; ++a) k[a] = axis_index(L, a, c[a]);
    return k;
  }
  static std::size_t linear(const level& L, const std::array<long, G>& k) {
    std::size_t r = 0;
    for (std::size_t a = G; a-- > 0;) r = r * static_cast<std::size_t>(L.dims[a]) + static_cast<std::size_t>(k[a]);
    return r;
  }

  /// Level `li` becomes a grid over the points at positions [b, e), which it sorts into its cell
  /// order. False if it would have one cell.
  bool split(std::size_t li, std::uint32_t b, std::uint32_t e, double per_cell) {
    level& L = levels_[li];
    const std::size_t m = e - b;
    if (m == 0) {
      L.dims.fill(1);
      L.start.assign(2, b);
      return false;
    }
    L.lo = L.hi = xyz_[b];
    for (auto k = b; k < e; ++k)
      for (std::size_t a = 0; a < G; ++a) {
        L.lo[a] = std::min(L.lo[a], xyz_[k][a]);
        L.hi[a] = std::max(L.hi[a], xyz_[k][a]);
      }
    double volume = 1;
    int flat = 0;
    for (std::size_t a = 0; a < G; ++a) {
      const double ex = L.hi[a] - L.lo[a];
      if (ex > 0) volume *= ex; else ++flat;
    }
    const double cells = std::max(1.0, static_cast<double>(m) / per_cell);
    double h = flat == static_cast<int>(G) ? 1.0 : std::pow(volume / cells, 1.0 / static_cast<double>(G - static_cast<std::size_t>(flat)));
    if (!(h > 0) || !std::isfinite(h)) h = 1;
    std::size_t total = 1;
    for (std::size_t a = 0; a < G; ++a) {
      const double ex = L.hi[a] - L.lo[a];
      // cells half as long along axis 0 as a cube and correspondingly wider across: a search
      // visits rows of cells along axis 0, whose points are contiguous, so fewer and longer
      // rows clipped finely along the row beat cubes (front bench: +12-20%)
      const double ha = h * (a == 0 ? 0.5 : std::pow(0.5, -1.0 / static_cast<double>(G - 1)));
      L.dims[a] = static_cast<long>(std::clamp(ex / ha, 0.0, double(1 << 20))) + 1;  // clamped before the cast
      L.dims[a] = std::min<long>(L.dims[a], 1 << 20);
      total *= static_cast<std::size_t>(L.dims[a]);
    }
    while (total > 4 * m + 16) {  // guard against degenerate extents
      total = 1;
      for (std::size_t a = 0; a < G; ++a) {
        L.dims[a] = std::max<long>(1, L.dims[a] / 2);
        total *= static_cast<std::size_t>(L.dims[a]);
      }
    }
    for (std::size_t a = 0; a < G; ++a) {
      const double ex = L.hi[a] - L.lo[a];
      L.inv[a] = ex > 0 ? static_cast<double>(L.dims[a]) / ex : 0.0;
      L.step[a] = ex / static_cast<double>(L.dims[a]);
    }
    L.start.assign(total + 1, 0);
    if (li != 0 && total == 1) return false;
    std::vector<std::uint32_t> cell_of(m);
    for (std::size_t i = 0; i < m; ++i) {
      cell_of[i] = static_cast<std::uint32_t>(linear(L, cell_index(L, xyz_[b + i])));
      ++L.start[cell_of[i] + 1];
    }
    L.start[0] = b;
    for (std::size_t i = 1; i < L.start.size(); ++i) L.start[i] += L.start[i - 1];
    // a stable counting sort of the range into cell order
    std::vector<vertex_id> ids(ids_.begin() + b, ids_.begin() + e);
    std::vector<coord> xyz(xyz_.begin() + b, xyz_.begin() + e);
    std::vector<std::uint32_t> fill(L.start.begin(), L.start.end() - 1);
    for (std::size_t i = 0; i < m; ++i) {
      const auto k = fill[cell_of[i]]++;
      ids_[k] = ids[i];
      xyz_[k] = xyz[i];
    }
    return true;
  }

  template <bool Local, class F>
  bool visit_range(std::uint32_t b, std::uint32_t e, F& f) const {
    for (auto k = b; k < e; ++k)
      if (!f(Local ? static_cast<vertex_id>(k) : ids_[k], xyz_[k])) return false;
    return true;
  }

  /// Calls g(linear cell index) of level L for its cells overlapping [lo, hi].
  template <class F>
  static bool cells_of(const level& L, const coord& lo, const coord& hi, F&& g) {
    const auto a = cell_index(L, lo), b = cell_index(L, hi);
    if constexpr (G == 2) {
      for (long y = a[1]; y <= b[1]; ++y)
        for (long x = a[0]; x <= b[0]; ++x)
          if (!g(linear(L, {x, y}))) return false;
    } else {
      for (long z = a[2]; z <= b[2]; ++z)
        for (long y = a[1]; y <= b[1]; ++y)
          for (long x = a[0]; x <= b[0]; ++x)
            if (!g(linear(L, {x, y, z}))) return false;
    }
    return true;
  }

  /// Calls g(b, e) for position ranges covering the points of level L's finest cells overlapping
  /// [lo, hi] (descending into crowded cells).
  template <class F>
  bool box_ranges(const level& L, const coord& lo, const coord& hi, F&& g) const {
    if (L.child.empty()) {  // a row's cells are contiguous: one range a row
      const auto a = cell_index(L, lo), b = cell_index(L, hi);
      auto row = [&](std::array<long, G> k) {
        k[0] = a[0];
        const auto first = linear(L, k);
        const auto last = first + static_cast<std::size_t>(b[0] - a[0]);
        return L.start[first] == L.start[last + 1] || g(L.start[first], L.start[last + 1]);
      };
      if constexpr (G == 2) {
        for (long y = a[1]; y <= b[1]; ++y)
          if (!row({0, y})) return false;
      } else {
        for (long z = a[2]; z <= b[2]; ++z)
          for (long y = a[1]; y <= b[1]; ++y)
            if (!row({0, y, z})) return false;
      }
      return true;
    }
    auto one = [&](std::size_t cell) {
      if (!L.child.empty() && L.child[cell] >= 0) return box_ranges(levels_[static_cast<std::size_t>(L.child[cell])], lo, hi, g);
      return L.start[cell] == L.start[cell + 1] || g(L.start[cell], L.start[cell + 1]);
    };
    return cells_of(L, lo, hi, one);
  }

  /// Calls g(b, e) for position ranges covering the points of the runs rows(L, ...) lists,
  /// descending into crowded cells with the same ball and half-space.
  template <class F>
  bool ball_ranges(const level& L, const coord& c, double r, const coord& n, double d, F&& g) const {
    if (L.child.empty())
      return rows(L, c, r, n, d, [&](std::size_t first, std::size_t last) {
        return L.start[first] == L.start[last + 1] || g(L.start[first], L.start[last + 1]);
      });
    return rows(L, c, r, n, d, [&](std::size_t first, std::size_t last) {
      std::size_t run = first;  // the childless cells run..cell-1 not yet passed on
      for (std::size_t cell = first; cell <= last; ++cell) {
        const auto k = L.child[cell];
        if (k < 0) continue;
        if (run < cell && L.start[run] != L.start[cell] && !g(L.start[run], L.start[cell])) return false;
        if (!ball_ranges(levels_[static_cast<std::size_t>(k)], c, r, n, d, g)) return false;
        run = cell + 1;
      }
      return run > last || L.start[run] == L.start[last + 1] || g(L.start[run], L.start[last + 1]);
    });
  }

  /// visit_rows on level L (the pad is the top grid's, so every level is as conservative).
  template <class F>
  bool rows(const level& L, const coord& c, double r, const coord& n, double d, F&& g) const {
    coord lo, hi;
    for (std::size_t a = 0; a < G; ++a) lo[a] = c[a] - r, hi[a] = c[a] + r;
    const auto ka = cell_index(L, lo), kb = cell_index(L, hi);
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
        const double clo = L.lo[a] + static_cast<double>(k) * L.step[a] - pad, chi = clo + L.step[a] + 2 * pad;
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
      const long x0 = std::max(ka[0], axis_index(L, 0, xa)), x1 = std::min(kb[0], axis_index(L, 0, xb));
      return x0 > x1 || g(base + static_cast<std::size_t>(x0), base + static_cast<std::size_t>(x1));
    };
    if constexpr (G == 2) {
      for (long y = ka[1]; y <= kb[1]; ++y) {
        const auto j = static_cast<std::size_t>(y - ka[1]);
        const double rest = r2 - gap2[1][j];
        if (rest >= 0 && !row(rest, top[1][j] - d, static_cast<std::size_t>(y) * static_cast<std::size_t>(L.dims[0])))
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
          if (rest >= 0 && !row(rest, top[1][j] + top[2][i] - d, linear(L, {0, y, z}))) return false;
        }
      }
    }
    return true;
  }

  std::size_t n_ = 0;
  double extent_ = 0;
  std::vector<level> levels_;  // levels_[0]: the uniform grid over all points
  std::vector<vertex_id> ids_;
  std::vector<std::uint32_t> positions_;  // dense grids: position of point i
  std::vector<coord> xyz_;
};

}  // namespace gsse::geometry
