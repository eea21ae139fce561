#pragma once
// Small multi-segment meshes built from a Kuhn subdivision of a grid of unit squares/cubes.
// Cells with centre x < split go to segment "left" (number 1), the others to "right" (number 2),
// so the two segments share an interface at x = split.
#include <array>
#include <cstddef>
#include <vector>

#include "gsse/gsse.hpp"

namespace gsse::test {

/// Grid of nx*ny(*nz) unit cells, each split into D! simplices along the main diagonal (Kuhn),
/// which matches across cell faces. Returns points and cells (positively oriented).
template <std::size_t D>
struct kuhn_grid {
  std::vector<point<D>> points;
  std::vector<std::array<vertex_id, D + 1>> cells;
  std::vector<double> centre_x;
};

template <std::size_t D>
kuhn_grid<D> make_kuhn_grid(std::array<int, D> n) {
  kuhn_grid<D> g;
  std::array<int, D> m;
  for (std::size_t a = 0; a < D; ++a) m[a] = n[a] + 1;
  auto id = [&](std::array<int, D> c) {
    vertex_id v = 0;
    for (std::size_t a = D; a-- > 0;) v = v * static_cast<vertex_id>(m[a]) + static_cast<vertex_id>(c[a]);
    return v;
  };
  std::size_t total = 1;
  for (auto k : m) total *= static_cast<std::size_t>(k);
  g.points.resize(total);
  for (std::size_t v = 0; v < total; ++v) {
    std::size_t r = v;
    for (std::size_t a = 0; a < D; ++a) {
      g.points[v][a] = static_cast<double>(r % static_cast<std::size_t>(m[a]));
      r /= static_cast<std::size_t>(m[a]);
    }
  }
  std::array<int, D> perm;
  std::size_t cellcount = 1;
  for (auto k : n) cellcount *= static_cast<std::size_t>(k);
  for (std::size_t c = 0; c < cellcount; ++c) {
    std::array<int, D> base;
    std::size_t r = c;
    for (std::size_t a = 0; a < D; ++a) {
      base[a] = static_cast<int>(r % static_cast<std::size_t>(n[a]));
      r /= static_cast<std::size_t>(n[a]);
    }
    for (std::size_t a = 0; a < D; ++a) perm[a] = static_cast<int>(a);
    do {
      std::array<vertex_id, D + 1> s;
      auto cur = base;
      s[0] = id(cur);
      for (std::size_t k = 0; k < D; ++k) {
        cur[static_cast<std::size_t>(perm[k])] += 1;
        s[k + 1] = id(cur);
      }
      // orientation of a Kuhn simplex is the sign of its permutation
      int inversions = 0;
      for (std::size_t i = 0; i < D; ++i)
        for (std::size_t j = i + 1; j < D; ++j) inversions += perm[i] > perm[j];
      if (inversions % 2 == 1) std::swap(s[0], s[1]);
      g.cells.push_back(s);
      g.centre_x.push_back(base[0] + 0.5);
    } while (std::next_permutation(perm.begin(), perm.end()));
  }
  return g;
}

/// Default-model domain with segments "left" (x < split) and "right".
template <std::size_t D>
domain<D> make_two_segment_domain(std::array<int, D> n, double split) {
  auto g = make_kuhn_grid<D>(n);
  domain<D> d;
  for (const auto& p : g.points) d.add_point(p);
  d.add_segment("left", 1);
  d.add_segment("right", 2);
  auto& l = d.segments()[0];
  auto& r = d.segments()[1];
  for (std::size_t c = 0; c < g.cells.size(); ++c) (g.centre_x[c] < split ? l : r).add_cell(g.cells[c]);
  for (auto& s : d.segments()) s.finalize();
  return d;
}

}  // namespace gsse::test
