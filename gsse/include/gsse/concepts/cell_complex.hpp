#pragma once
// Concept CellComplex: a simplicial complex of dimension 2 or 3 reached through free functions,
// so that foreign mesh types can be adapted without touching them. See docs/concepts/cell_complex.md.
#include <concepts>
#include <cstddef>
#include <ranges>

#include "gsse/topology/simplex.hpp"

namespace gsse {

/// Associated dimension. Models either expose `static constexpr std::size_t dimension` or
/// specialise complex_traits.
template <class X>
struct complex_traits {
  static constexpr std::size_t dimension = X::dimension;
};
template <class X>
inline constexpr std::size_t dimension_v = complex_traits<std::remove_cvref_t<X>>::dimension;

template <class X>
concept cell_complex = requires(const X& x, cell_id c, int i, vertex_id v) {
  requires dimension_v<X> == 2 || dimension_v<X> == 3;
  { num_cells(x) } -> std::convertible_to<std::size_t>;
  { vertices(x, c) } -> std::ranges::random_access_range;
  requires std::convertible_to<std::ranges::range_value_t<decltype(vertices(x, c))>, vertex_id>;
  { neighbour(x, c, i) } -> std::convertible_to<cell_id>;
  { cells(x, v) } -> std::ranges::forward_range;  // cells around vertex v
};

namespace archetypes {
/// Minimal model of CellComplex: the valid expressions and nothing else.
template <std::size_t D>
struct cell_complex {
  static constexpr std::size_t dimension = D;
  friend std::size_t num_cells(const cell_complex&) { return 0; }
  friend std::array<vertex_id, D + 1> vertices(const cell_complex&, cell_id) { return {}; }
  friend cell_id neighbour(const cell_complex&, cell_id, int) { return no_cell; }
  friend std::ranges::empty_view<cell_id> cells(const cell_complex&, vertex_id) { return {}; }
};
}  // namespace archetypes

static_assert(cell_complex<archetypes::cell_complex<2>>);
static_assert(cell_complex<archetypes::cell_complex<3>>);
static_assert(!cell_complex<archetypes::cell_complex<4>>);

}  // namespace gsse
