#pragma once
// Incidence as free functions. The primitives (num_cells, vertices(x,c), neighbour, cells(x,v))
// are what a model provides; everything else here is derived from them and works for any
// CellComplex, including adapted foreign types (found by argument-dependent lookup).
#include <algorithm>
#include <array>
#include <ranges>
#include <span>
#include <unordered_map>
#include <vector>

#include "gsse/concepts/domain.hpp"
#include "gsse/container/domain.hpp"
#include "gsse/topology/simplex.hpp"

namespace gsse {

// ---- primitives of the default model -------------------------------------------------------
template <std::size_t D>
std::size_t num_cells(const simplicial_complex<D>& x) { return x.num_cells(); }
template <std::size_t D>
const typename simplicial_complex<D>::cell_type& vertices(const simplicial_complex<D>& x, cell_id c) {
  return x.cell(c);
}
template <std::size_t D>
cell_id neighbour(const simplicial_complex<D>& x, cell_id c, int i) { return x.neighbour(c, i); }
/// Cells around vertex v (requires finalize()).
template <std::size_t D>
std::span<const cell_id> cells(const simplicial_complex<D>& x, vertex_id v) { return x.cells_of_vertex(v); }
template <std::size_t D>
const std::string& name(const segment<D>& s) { return s.name(); }
template <std::size_t D>
int number(const segment<D>& s) { return s.number(); }
template <std::size_t D>
std::size_t num_points(const domain<D>& d) { return d.points().size(); }
template <std::size_t D>
const point<D>& position(const domain<D>& d, vertex_id v) { return d.position(v); }
template <std::size_t D>
const std::deque<segment<D>>& segments(const domain<D>& d) { return d.segments(); }
template <std::size_t D>
std::deque<segment<D>>& segments(domain<D>& d) { return d.segments(); }

// ---- derived incidences (any CellComplex) ---------------------------------------------------
/// All cell handles of a complex.
template <cell_complex X>
auto cells(const X& x) {
  return std::views::iota(cell_id{0}, static_cast<cell_id>(num_cells(x)));
}

/// A facet is (cell, i): the facet of `cell` opposite its local vertex i.
struct facet {
  cell_id cell = no_cell;
  int index = 0;
  friend bool operator==(facet, facet) = default;
};

template <cell_complex X>
std::array<facet, dimension_v<X> + 1> facets(const X&, cell_id c) {
  std::array<facet, dimension_v<X> + 1> f;
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = {c, static_cast<int>(i)};
  return f;
}

/// Vertices of facet f, ordered so that the facet faces into its cell (the cell's opposite vertex
/// lies on the facet's positive side).
// (The facet parameter is constrained first so that these overloads are discarded for cell ids
// before CellComplex itself is checked, which would recurse.)
template <class X, std::same_as<facet> F>
  requires cell_complex<X>
std::array<vertex_id, dimension_v<X>> vertices(const X& x, F f) {
  constexpr std::size_t D = dimension_v<X>;
  const auto& cv = vertices(x, f.cell);
  std::array<vertex_id, D> r;
  for (std::size_t j = 0; j < D; ++j)
    r[j] = cv[static_cast<std::size_t>(reference_simplex<D>::facet_vertices[static_cast<std::size_t>(f.index)][j])];
  return r;
}

template <class X, std::same_as<facet> F>
  requires cell_complex<X>
cell_id neighbour(const X& x, F f) {
  return neighbour(x, f.cell, f.index);
}

/// Edges of a cell as vertex pairs, in the reference simplex's edge order.
template <cell_complex X>
std::array<std::array<vertex_id, 2>, simplex_tag<dimension_v<X>>::num_edges> edges(const X& x, cell_id c) {
  constexpr std::size_t D = dimension_v<X>;
  const auto& cv = vertices(x, c);
  std::array<std::array<vertex_id, 2>, simplex_tag<D>::num_edges> e;
  for (std::size_t k = 0; k < e.size(); ++k)
    e[k] = {cv[static_cast<std::size_t>(reference_simplex<D>::edge_vertices[k][0])],
            cv[static_cast<std::size_t>(reference_simplex<D>::edge_vertices[k][1])]};
  return e;
}

/// Facets of a complex with no neighbour, in cell order.
template <cell_complex X>
std::vector<facet> boundary_facets(const X& x) {
  std::vector<facet> r;
  for (cell_id c : cells(x))
    for (int i = 0; i <= static_cast<int>(dimension_v<X>); ++i)
      if (neighbour(x, c, i) == no_cell) r.push_back({c, i});
  return r;
}

/// A facet shared by two segments: `first` in s0 (its vertex order faces into s0, which is the
/// interface's orientation with respect to s0) and `second` in s1 (facing into s1: opposite).
struct interface_facet {
  facet first;
  facet second;
};

template <cell_complex S>
std::vector<interface_facet> interface_facets(const S& s0, const S& s1) {
  constexpr std::size_t D = dimension_v<S>;
  struct h {
    std::size_t operator()(const std::array<vertex_id, D>& k) const {
      std::size_t v = 1469598103934665603ull;
      for (auto a : k) v = (v ^ a) * 1099511628211ull;
      return v;
    }
  };
  std::unordered_map<std::array<vertex_id, D>, facet, h> b1;
  for (const facet& f : boundary_facets(s1)) {
    auto k = vertices(s1, f);
    std::sort(k.begin(), k.end());
    b1.emplace(k, f);
  }
  std::vector<interface_facet> r;
  for (const facet& f : boundary_facets(s0)) {
    auto k = vertices(s0, f);
    std::sort(k.begin(), k.end());
    if (auto it = b1.find(k); it != b1.end()) r.push_back({f, it->second});
  }
  return r;
}

/// Interface facets between segments k0 and k1 of a domain.
template <domain_model Dm>
auto interface_facets(const Dm& d, std::size_t k0, std::size_t k1) {
  const auto& segs = segments(d);
  return interface_facets(segs[k0], segs[k1]);
}

}  // namespace gsse
