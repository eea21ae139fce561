#pragma once
// Dynamic uniform grid of hashed cells holding ids: of points (by their cell) or of objects (by
// every cell their bounding box meets). For sets that grow while they are searched (the
// conformer's points) or whose extent would make a dense grid too large (faces kept off by half a
// mesh size). Cells live in an open-addressing table (packed cell key -> bucket), probed once per
// cell a scan meets; scans meet cells in a fixed order, so results never depend on hashing.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "gsse/geometry/point.hpp"

namespace gsse {

template <std::size_t D>
class hash_grid {
 public:
  using cell = std::array<long, D>;

  hash_grid(const point<D>& origin, double cell_size) : o_(origin), inv_(1.0 / cell_size) { rehash(64); }

  cell cell_of(const point<D>& p) const {
    cell c;
    for (std::size_t k = 0; k < D; ++k) c[k] = static_cast<long>(std::clamp(std::floor((p[k] - o_[k]) * inv_), -1e9, 1e9));
    return c;
  }
  /// Files id in the cell of p.
  void insert(std::uint32_t id, const point<D>& p) { bucket(key(cell_of(p))).push_back(id); }
  /// Files id in every cell the box [lo, hi] meets.
  void insert_box(std::uint32_t id, const point<D>& lo, const point<D>& hi) {
    for_cells(cell_of(lo), cell_of(hi), [&](const cell& c) {
      bucket(key(c)).push_back(id);
      return true;
    });
  }
  /// Files id in the cells a segment (2D) or triangle (3D) `v` meets, and a few more (not in every
  /// cell of its bounding box: a slanted facet's box holds (L/s)^3 cells, the facet about (L/s)^2).
  /// Columns along the axis its normal is largest in: in each column (one cell wide across the
  /// other axes, within the box) the cells from the lowest to the highest height the simplex's
  /// line or plane reaches over the column, padded by a cell each way for rounding, clipped to
  /// the box.
  /// Every cell holding a point of the simplex is among them. A degenerate simplex: its box.
  void insert_simplex(std::uint32_t id, const std::array<point<D>, D>& v) {
    simplex_cells(v, [&](const cell& c) { bucket(key(c)).push_back(id); });
  }
  /// Files id in cell c.
  void insert_cell(std::uint32_t id, const cell& c) { bucket(key(c)).push_back(id); }
  /// Calls f(cell) for every cell insert_simplex(id, v) files id in, in the same order (read only:
  /// callers may list many simplices' cells in parallel, then file them).
  template <class F>
  void simplex_cells(const std::array<point<D>, D>& v, F&& f) const {
    point<D> lo = v[0], hi = v[0];
    for (const auto& q : v)
      for (std::size_t k = 0; k < D; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
    point<D> n{};
    if constexpr (D == 2) {
      n = {v[0][1] - v[1][1], v[1][0] - v[0][0]};
    } else {
      const point<D> a = v[1] - v[0], b = v[2] - v[0];
      n = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    }
    std::size_t k = 0;
    for (std::size_t i = 1; i < D; ++i)
      if (std::abs(n[i]) > std::abs(n[k])) k = i;
    if (!(std::abs(n[k]) > 0)) {
      for_cells(cell_of(lo), cell_of(hi), [&](const cell& c) {
        f(c);
        return true;
      });
      return;
    }
    const cell a = cell_of(lo), b = cell_of(hi);
    const double s = 1.0 / inv_;
    // the simplex's height along k over the column: x_k = v0_k - sum_{i != k} n_i (x_i - v0_i) / n_k
    auto height = [&](const point<D>& x) {
      double h = v[0][k];
      for (std::size_t i = 0; i < D; ++i)
        if (i != k) h -= n[i] * (x[i] - v[0][i]) / n[k];
      return h;
    };
    cell lo_col = a, hi_col = b;
    lo_col[k] = hi_col[k] = 0;
    for_cells(lo_col, hi_col, [&](const cell& c) {
      double zlo = 1e300, zhi = -1e300;
      for (unsigned corner = 0; corner < (1u << D); ++corner) {
        if (corner & (1u << k)) continue;
        point<D> x{};
        for (std::size_t i = 0; i < D; ++i)
          if (i != k) x[i] = o_[i] + s * static_cast<double>(c[i] + ((corner >> i) & 1u));
        const double z = height(x);
        zlo = std::min(zlo, z), zhi = std::max(zhi, z);
      }
      point<D> p0{}, p1{};
      p0[k] = std::max(zlo - s, lo[k]), p1[k] = std::min(zhi + s, hi[k]);
      if (p0[k] > p1[k]) return true;
      cell from = c, to = c;
      from[k] = std::max(a[k], cell_of(p0)[k]), to[k] = std::min(b[k], cell_of(p1)[k]);
      for (long z = from[k]; z <= to[k]; ++z) {
        cell at = c;
        at[k] = z;
        f(at);
      }
      return true;
    });
  }
  /// Calls f(id) for the ids in the cells the box [lo, hi] meets (an id filed in several of them
  /// comes several times; a box of more cells than are occupied scans all occupied cells). If f
  /// returns bool, false stops the scan and visit returns false.
  template <class F>
  bool visit(const point<D>& lo, const point<D>& hi, F&& f) const {
    return visit_cells(cell_of(lo), cell_of(hi), f);
  }
  /// The cells the box [lo, hi] meets, by rings about q's cell (ring k: the cells k cells away
  /// from it in the maximum norm), nearest first; `ring_done()` is called after each ring with
  /// ids and true from it stops the scan (a search that takes the nearest find reads a few cells
  /// of a large ball, not all of them). If f returns bool, false stops the scan at once. Returns
  /// false if stopped. Once the rings so far span more cells than are occupied, the rest of the
  /// box comes as one last ring: every occupied cell in it, in the table's order.
  template <class F, class Done>
  bool visit_rings(const point<D>& q, const point<D>& lo, const point<D>& hi, F&& f, Done&& ring_done) const {
    const cell a = cell_of(lo), b = cell_of(hi), c0 = cell_of(q);
    long rings = 0;
    for (std::size_t k = 0; k < D; ++k) rings = std::max({rings, c0[k] - a[k], b[k] - c0[k]});
    double count = 1;
    for (std::size_t k = 0; k < D; ++k) count *= static_cast<double>(b[k] - a[k] + 1);
    const double occupied = 4.0 * static_cast<double>(buckets_.size()) + 64;
    bool stopped = false;
    auto probe = [&](const cell& c) {
      if (stopped) return;
      const std::uint64_t key_c = key(c);
      const std::size_t i = slot(key_c);
      if (keys_[i] == key_c)
        for (auto id : buckets_[vals_[i]])
          if (!call(f, id)) {
            stopped = true;
            return;
          }
    };
    for (long r = 0; r <= rings; ++r) {
      if (count > occupied && r > 0 && std::pow(2.0 * static_cast<double>(r) + 1, static_cast<double>(D)) > occupied) {
        // the rest of a box of more cells than are occupied: every occupied cell beyond ring r-1,
        // in the table's order (fixed by the insertions made; the callers' results do not depend
        // on it, only how soon they stop)
        for (std::size_t i = 0; i < keys_.size(); ++i) {
          if (keys_[i] == empty) continue;
          const std::uint32_t v = vals_[i];
          const cell c = unkey(keys_[i]);
          long d = 0;
          bool in = true;
          for (std::size_t j = 0; j < D; ++j) in = in && a[j] <= c[j] && c[j] <= b[j], d = std::max(d, std::abs(c[j] - c0[j]));
          if (in && d >= r)
            for (auto id : buckets_[v])
              if (!call(f, id)) return false;
        }
        ring_done();
        return true;
      }
      // the shell of ring r, clipped to the box: the cells at distance exactly r
      cell lo_c, hi_c;
      bool none = false;
      for (std::size_t k = 0; k < D; ++k) {
        lo_c[k] = std::max(a[k], c0[k] - r), hi_c[k] = std::min(b[k], c0[k] + r);
        none = none || lo_c[k] > hi_c[k];
      }
      if (!none) {
        // in the plane of the first two axes: the rows at +-r whole, the columns at +-r between
        auto rim = [&](cell c, bool whole) {
          for (c[1] = lo_c[1]; c[1] <= hi_c[1]; ++c[1]) {
            if (whole || std::abs(c[1] - c0[1]) == r) {
              for (c[0] = lo_c[0]; c[0] <= hi_c[0]; ++c[0]) probe(c);
            } else {
              for (long x : {c0[0] - r, c0[0] + r})
                if (lo_c[0] <= x && x <= hi_c[0] && (r > 0 || x == c0[0] - r)) c[0] = x, probe(c);
            }
          }
        };
        cell c = c0;
        if constexpr (D == 2) {
          rim(c, false);
        } else {
          for (c[2] = lo_c[2]; c[2] <= hi_c[2]; ++c[2]) rim(c, std::abs(c[2] - c0[2]) == r);
        }
      }
      if (stopped) return false;
      if (ring_done()) return r == rings;
    }
    return true;
  }

  /// Occupied cells.
  std::size_t occupied() const { return buckets_.size(); }
  /// Calls f(cell) for every occupied cell, in the table's order (callers must not depend on it).
  template <class F>
  void for_each_occupied(F&& f) const {
    for (std::size_t i = 0; i < keys_.size(); ++i)
      if (keys_[i] != empty) f(unkey(keys_[i]));
  }

  /// The same for the cells within `ring` cells of q's cell.
  template <class F>
  bool visit_ring(const point<D>& q, long ring, F&& f) const {
    cell a = cell_of(q), b = a;
    for (std::size_t k = 0; k < D; ++k) a[k] -= ring, b[k] += ring;
    return visit_cells(a, b, f);
  }

 private:
  static constexpr std::uint64_t empty = ~std::uint64_t{0};

  template <class F>
  static bool call(F& f, std::uint32_t id) {
    if constexpr (std::is_same_v<std::invoke_result_t<F&, std::uint32_t>, bool>)
      return f(id);
    else
      return f(id), true;
  }
  template <class F>
  bool visit_cells(const cell& a, const cell& b, F& f) const {
    double count = 1;
    for (std::size_t k = 0; k < D; ++k) count *= static_cast<double>(b[k] - a[k] + 1);
    if (count > 4.0 * static_cast<double>(buckets_.size()) + 64) {
      // a box of more cells than are occupied: scan every occupied cell, by key (a superset)
      std::vector<std::pair<std::uint64_t, std::uint32_t>> order;
      for (std::size_t i = 0; i < keys_.size(); ++i)
        if (keys_[i] != empty) order.push_back({keys_[i], vals_[i]});
      std::sort(order.begin(), order.end());
      for (auto [k, v] : order)
        for (auto id : buckets_[v])
          if (!call(f, id)) return false;
      return true;
    }
    return for_cells(a, b, [&](const cell& c) {
      const std::uint64_t k = key(c);
      const std::size_t i = slot(k);
      if (keys_[i] == k)
        for (auto id : buckets_[vals_[i]])
          if (!call(f, id)) return false;
      return true;
    });
  }
  template <class F>
  static bool for_cells(const cell& a, const cell& b, F&& f) {
    cell c = a;
    for (;;) {
      if (!f(c)) return false;
      std::size_t k = 0;
      while (k < D && ++c[k] > b[k]) c[k] = a[k], ++k;
      if (k == D) return true;
    }
  }
  static cell unkey(std::uint64_t h) {
    cell c;
    for (std::size_t k = D; k-- > 0;) {
      c[k] = static_cast<long>(h & 0x1FFFFF) - (1l << 20);
      h >>= 21;
    }
    return c;
  }
  /// Cell coordinates packed in 21 bits each: distinct for |coordinate| < 2^20 (beyond, cells may
  /// share a bucket, which only adds candidates), never equal to `empty`.
  static std::uint64_t key(const cell& c) {
    std::uint64_t h = 0;
    for (std::size_t k = 0; k < D; ++k) h = (h << 21) | (static_cast<std::uint64_t>(c[k] + (1l << 20)) & 0x1FFFFF);
    return h;
  }
  std::size_t slot(std::uint64_t k) const {
    const std::uint64_t h = k * 0x9E3779B97F4A7C15ull;
    for (std::size_t i = (h ^ (h >> 31)) & mask_;; i = (i + 1) & mask_)
      if (keys_[i] == k || keys_[i] == empty) return i;
  }
  std::vector<std::uint32_t>& bucket(std::uint64_t k) {
    std::size_t i = slot(k);
    if (keys_[i] == empty) {
      if (2 * (buckets_.size() + 1) > keys_.size()) {
        rehash(2 * keys_.size());
        i = slot(k);
      }
      keys_[i] = k;
      vals_[i] = static_cast<std::uint32_t>(buckets_.size());
      buckets_.emplace_back();
    }
    return buckets_[vals_[i]];
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
  std::vector<std::vector<std::uint32_t>> buckets_;
};

/// Points in hash grids of cells h, 4h, 16h, ... up to `top`: a search takes the finest on which
/// its box spans a few cells, so a large ball over a set whose spacing varies much (a refined
/// surface in a coarse model) reads a few cells of a coarse level instead of many of a fine one.
/// Ids come as from that level's hash_grid (visit, visit_rings, visit_ring).
template <std::size_t D>
class grid_levels {
 public:
  grid_levels(const point<D>& origin, double h, double top) {
    levels_.emplace_back(origin, h);
    for (double c = 4 * h; c < 4 * top && levels_.size() < 12; c *= 4) levels_.emplace_back(origin, c);
  }
  void insert(std::uint32_t id, const point<D>& p) {
    for (auto& g : levels_) g.insert(id, p);
  }
  const hash_grid<D>& finest() const { return levels_.front(); }
  /// The finest level on which [lo, hi] spans at most `span` cells along every axis (the
  /// coarsest if none).
  const hash_grid<D>& for_box(const point<D>& lo, const point<D>& hi, long span = 8) const {
    for (const auto& g : levels_) {
      const auto a = g.cell_of(lo), b = g.cell_of(hi);
      bool fits = true;
      for (std::size_t k = 0; k < D; ++k) fits = fits && b[k] - a[k] < span;
      if (fits) return g;
    }
    return levels_.back();
  }

 private:
  std::vector<hash_grid<D>> levels_;
};

}  // namespace gsse
