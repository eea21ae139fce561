#pragma once
// Default cell-complex model: simplices as vertex-id tuples plus the neighbour across each facet
// (neighbour i opposite vertex i, as in CGAL's TDS), and a vertex-to-cell index in CSR form.
// Both derived relations are built by finalize() and dropped by any mutation.
#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "gsse/topology/simplex.hpp"

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
  /// cells (not a manifold complex).
  void finalize() {
    build_neighbours();
    build_vertex_index();
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
  struct key_hash {
    std::size_t operator()(const std::array<vertex_id, D>& k) const {
      std::size_t h = 1469598103934665603ull;
      for (auto v : k) h = (h ^ v) * 1099511628211ull;
      return h;
    }
  };
  void build_neighbours() {
    nbrs_.assign(cells_.size(), {});
    for (auto& n : nbrs_) n.fill(no_cell);
    std::unordered_map<std::array<vertex_id, D>, std::pair<cell_id, int>, key_hash> open;
    open.reserve(cells_.size() * 2);
    for (cell_id c = 0; c < cells_.size(); ++c) {
      for (int i = 0; i <= static_cast<int>(D); ++i) {
        std::array<vertex_id, D> k;
        for (std::size_t j = 0; j < D; ++j)
          k[j] = cells_[c][static_cast<std::size_t>(reference_simplex<D>::facet_vertices[i][j])];
        std::sort(k.begin(), k.end());
        auto [it, fresh] = open.try_emplace(k, c, i);
        if (!fresh) {
          auto [o, oi] = it->second;
          if (o == no_cell) throw std::runtime_error("gsse: a facet is shared by more than two cells");
          nbrs_[c][static_cast<std::size_t>(i)] = o;
          nbrs_[o][static_cast<std::size_t>(oi)] = c;
          it->second = {no_cell, -1};
        }
      }
    }
  }
  void build_vertex_index() {
    vertex_id extent = 0;
    for (const auto& c : cells_)
      for (auto v : c) extent = std::max(extent, v + 1);
    vstart_.assign(static_cast<std::size_t>(extent) + 1, 0);
    for (const auto& c : cells_)
      for (auto v : c) ++vstart_[v + 1];
    for (std::size_t i = 1; i < vstart_.size(); ++i) vstart_[i] += vstart_[i - 1];
    vcells_.resize(vstart_.back());
    std::vector<std::size_t> fill(vstart_.begin(), vstart_.end() - 1);
    for (cell_id c = 0; c < cells_.size(); ++c)
      for (auto v : cells_[c]) vcells_[fill[v]++] = c;
    used_.clear();
    for (vertex_id v = 0; v < extent; ++v)
      if (vstart_[v + 1] > vstart_[v]) used_.push_back(v);
  }

  std::vector<cell_type> cells_;
  std::vector<neighbour_type> nbrs_;
  std::vector<std::size_t> vstart_;
  std::vector<cell_id> vcells_;
  std::vector<vertex_id> used_;
  bool finalized_ = false;
};

}  // namespace gsse
