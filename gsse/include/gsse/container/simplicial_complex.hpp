#pragma once
// Default cell-complex model: simplices as vertex-id tuples plus the neighbour across each facet
// (neighbour i opposite vertex i, as in CGAL's TDS), and a vertex-to-cell index in CSR form.
// Both derived relations are built by finalize() and dropped by any mutation.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <utility>
#include <span>
#include <stdexcept>
#include <vector>

#include "gsse/topology/simplex.hpp"
#include "gsse/traversal/for_each.hpp"

namespace gsse {

template <std::size_t D>
class simplicial_complex {
 public:
  static constexpr std::size_t dimension = D;
  using cell_type = std::array<vertex_id, D + 1>;
  using neighbour_type = std::array<cell_id, D + 1>;

  cell_id add_cell(const cell_type& c) {
    cells_.push_back(c);
    finalized_ = false;
    return static_cast<cell_id>(cells_.size() - 1);
  }
  void reserve(std::size_t n) { cells_.reserve(n); }
  void clear() {
    cells_.clear();
    finalized_ = false;
  }
  std::size_t num_cells() const { return cells_.size(); }
  const cell_type& cell(cell_id c) const { return cells_[c]; }
  std::span<const cell_type> cell_data() const { return cells_; }
  std::vector<cell_type>& mutable_cells() {
    finalized_ = false;
    return cells_;
  }

  bool finalized() const { return finalized_; }
  /// Builds neighbours and the vertex-to-cell index. Throws if a facet is shared by more than two
  /// cells (not a manifold complex). `threads` share the vertex index (by cell ranges) and the
  /// neighbour matching (by vertex ranges); the result is the same for any number.
  void finalize(unsigned threads = 1) {
    build_vertex_index(std::max(1u, threads));
    build_neighbours(std::max(1u, threads));
    finalized_ = true;
  }

  cell_id neighbour(cell_id c, int i) const {
    require_finalized();
    return nbrs_[c][static_cast<std::size_t>(i)];
  }
  std::span<const cell_id> cells_of_vertex(vertex_id v) const {
    require_finalized();
    if (v + 1 >= vstart_.size()) return {};
    return std::span<const cell_id>(vcells_).subspan(vstart_[v], vstart_[v + 1] - vstart_[v]);
  }
  /// Sorted distinct vertex ids used by the cells.
  const std::vector<vertex_id>& used_vertices() const {
    require_finalized();
    return used_;
  }
  vertex_id vertex_extent() const { return static_cast<vertex_id>(vstart_.empty() ? 0 : vstart_.size() - 1); }

 private:
  void require_finalized() const {
    if (!finalized_) throw std::logic_error("gsse: incidence queried before finalize()");
  }
  /// Each facet is matched at its smallest vertex v, among the cells around v (vertex index):
  /// sorting those few (other vertices, cell, facet) entries pairs the two cells of each facet.
  /// Local and allocation-free, unlike a global facet hash.
  void build_neighbours(unsigned threads) {
    nbrs_.assign(cells_.size(), {});
    for (auto& n : nbrs_) n.fill(no_cell);
    const std::size_t nv = vstart_.empty() ? 0 : vstart_.size() - 1;
    if (threads <= 1 || nv < 4096) return match_facets(0, nv);
    // each facet is matched at its smallest vertex, so vertex ranges write disjoint entries; the
    // ranges are small and handed out as threads come free (low ids own more facets)
    constexpr std::size_t range = 2048;
    std::vector<std::size_t> starts;
    for (std::size_t a = 0; a < nv; a += range) starts.push_back(a);
    for_each(execution::par(threads), starts, [&](std::size_t a) { match_facets(a, std::min(nv, a + range)); });
  }
  void match_facets(std::size_t v0, std::size_t v1) {
    // the facet's other vertices, sorted, as one integer (D <= 3: at most two 32-bit ids): one
    // word to hash and compare; the order of a facet's two cells does not matter
    static_assert(D >= 1 && D <= 3 && sizeof(vertex_id) <= 4);
    struct entry {
      std::uint64_t rest;
      cell_id c;
      int i;
    };
    std::vector<entry> around;
    std::vector<std::int64_t> table;  // entry per slot, -1: empty
    for (std::size_t v = v0; v < v1; ++v) {
      around.clear();
      for (std::size_t k = vstart_[v]; k < vstart_[v + 1]; ++k) {
        const cell_id c = vcells_[k];
        const auto& cell = cells_[c];
        // a facet is matched at its smallest vertex: v is the smallest of every facet on it when
        // it is the cell's smallest, of the one facet without the only smaller vertex when it is
        // the second smallest, else of none (half the cells of a star are skipped here, and the
        // others give their facets without testing each)
        std::size_t below = 0, smaller = 0;
        for (std::size_t j = 0; j <= D; ++j)
          if (cell[j] < v) ++below, smaller = j;
        if (below > 1) continue;
        for (std::size_t i = 0; i <= D; ++i) {
          if (cell[i] == v || (below == 1 && i != smaller)) continue;  // facet i lacks v, or is matched lower
          std::array<vertex_id, D - 1> rest{};
          std::size_t m = 0;
          for (std::size_t j = 0; j <= D; ++j)
            if (j != i && cell[j] != v) rest[m++] = cell[j];
          std::uint64_t key = 0;
          if constexpr (D == 3) {
            key = rest[0] < rest[1] ? (std::uint64_t{rest[0]} << 32 | rest[1]) : (std::uint64_t{rest[1]} << 32 | rest[0]);
          } else if constexpr (D == 2) {
            key = rest[0];
          }
          around.push_back({key, c, static_cast<int>(i)});
        }
      }
      // the two entries of each facet paired through a small open-addressing table keyed by the
      // other vertices (sorting them was half of finalize(): a star's 20-40 entries by insertion)
      std::size_t cap = 16;
      int bits = 4;
      while (cap < 2 * around.size()) cap *= 2, ++bits;
      if (table.size() < cap) table.resize(cap);
      std::fill_n(table.begin(), cap, -1);
      for (std::size_t k = 0; k < around.size(); ++k) {
        const std::uint64_t key = around[k].rest;
        std::size_t at = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> (64 - bits));
        for (;; at = (at + 1) & (cap - 1)) {
          const std::int64_t j = table[at];
          if (j < 0) {
            table[at] = static_cast<std::int64_t>(k);
            break;
          }
          const auto& e = around[static_cast<std::size_t>(j)];
          if (e.rest != key) continue;
          if (nbrs_[e.c][static_cast<std::size_t>(e.i)] != no_cell)  // paired already: a third cell
            throw std::runtime_error("gsse: a facet is shared by more than two cells");
          nbrs_[around[k].c][static_cast<std::size_t>(around[k].i)] = e.c;
          nbrs_[e.c][static_cast<std::size_t>(e.i)] = around[k].c;
          break;
        }
      }
    }
  }
  /// CSR index: the cells of each vertex in increasing order. Cell ranges are counted and filled by
  /// `threads` concurrently; a vertex's entries from lower ranges come first, so the index is the
  /// same for any number of threads.
  void build_vertex_index(unsigned threads) {
    const std::size_t pieces = std::clamp<std::size_t>(cells_.size() / 16384, 1, threads);
    std::vector<std::size_t> cut(pieces + 1), ids(pieces);
    for (std::size_t t = 0; t <= pieces; ++t) cut[t] = cells_.size() * t / pieces;
    std::iota(ids.begin(), ids.end(), std::size_t{0});
    auto run = [&](auto&& body) {
      if (pieces == 1) return body(std::size_t{0});
      for_each(execution::par(static_cast<unsigned>(pieces)), ids, body);
    };
    std::vector<vertex_id> extents(pieces, 0);
    run([&](std::size_t t) {
      vertex_id e = 0;
      for (std::size_t c = cut[t]; c < cut[t + 1]; ++c)
        for (auto v : cells_[c]) e = std::max(e, v + 1);
      extents[t] = e;
    });
    const std::size_t extent = *std::max_element(extents.begin(), extents.end());
    // count[t][v]: cells of piece t at v; turned into piece t's first slot at v
    std::vector<std::vector<std::size_t>> count(pieces);
    run([&](std::size_t t) {
      std::vector<std::size_t> n(extent, 0);
      for (std::size_t c = cut[t]; c < cut[t + 1]; ++c)
        for (auto v : cells_[c]) ++n[v];
      count[t] = std::move(n);
    });
    vstart_.assign(extent + 1, 0);
    used_.clear();
    for (std::size_t v = 0; v < extent; ++v) {
      std::size_t at = vstart_[v];
      for (auto& n : count) at += std::exchange(n[v], at);
      vstart_[v + 1] = at;
      if (at > vstart_[v]) used_.push_back(static_cast<vertex_id>(v));
    }
    vcells_.resize(vstart_.back());
    run([&](std::size_t t) {
      auto& fill = count[t];
      for (std::size_t c = cut[t]; c < cut[t + 1]; ++c)
        for (auto v : cells_[c]) vcells_[fill[v]++] = static_cast<cell_id>(c);
    });
  }

  std::vector<cell_type> cells_;
  std::vector<neighbour_type> nbrs_;
  std::vector<std::size_t> vstart_;
  std::vector<cell_id> vcells_;
  std::vector<vertex_id> used_;
  bool finalized_ = false;
};

}  // namespace gsse
