#pragma once
// Reference simplex: local numbering of facets and edges, derived at compile time.
// Facet i is opposite vertex i. Its vertices are ordered so that (facet..., vertex i) has the
// orientation of the cell: a facet "faces into" its cell (the cell lies on its positive side).
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace gsse {

using vertex_id = std::uint32_t;
using cell_id = std::uint32_t;
inline constexpr cell_id no_cell = std::numeric_limits<cell_id>::max();
inline constexpr vertex_id no_vertex = std::numeric_limits<vertex_id>::max();

/// x == y, vertex by vertex (std::array's == called memcmp for each face: 2-3% of a run where the
/// refinement compares its boundary faces between rounds).
template <std::size_t N>
bool same_vertices(const std::array<vertex_id, N>& x, const std::array<vertex_id, N>& y) {
  bool eq = true;
  for (std::size_t k = 0; k < N; ++k) eq &= x[k] == y[k];
  return eq;
}

template <std::size_t D>
struct simplex_tag {
  static constexpr std::size_t dimension = D;
  static constexpr std::size_t num_vertices = D + 1;
  static constexpr std::size_t num_facets = D + 1;
  static constexpr std::size_t num_edges = (D + 1) * D / 2;
};

template <std::size_t D>
struct reference_simplex {
  /// facet_vertices[i]: local vertex numbers of facet i, oriented towards the cell.
  static constexpr std::array<std::array<int, D>, D + 1> facet_vertices = [] {
    std::array<std::array<int, D>, D + 1> f{};
    for (std::size_t i = 0; i <= D; ++i) {
      std::size_t k = 0;
      for (std::size_t j = 0; j <= D; ++j)
        if (j != i) f[i][k++] = static_cast<int>(j);
      // moving vertex i to the end is a permutation of sign (-1)^(D-i)
      if ((D - i) % 2 == 1) std::swap(f[i][0], f[i][1]);
    }
    return f;
  }();
  /// edge_vertices[e]: the two local vertices of edge e, lexicographic (0,1),(0,2),...
  static constexpr std::array<std::array<int, 2>, (D + 1) * D / 2> edge_vertices = [] {
    std::array<std::array<int, 2>, (D + 1) * D / 2> e{};
    std::size_t k = 0;
    for (int i = 0; i <= static_cast<int>(D); ++i)
      for (int j = i + 1; j <= static_cast<int>(D); ++j) e[k++] = {i, j};
    return e;
  }();
};

}  // namespace gsse
