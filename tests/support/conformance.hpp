#pragma once
// Generic conformance suite: checks that the incidences of any Domain model agree with each other
// and with the geometry. Every container model (gsse::domain, adapted foreign meshes) runs it.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <map>
#include <set>
#include <vector>

#include "gsse/gsse.hpp"

namespace gsse::test {

template <std::size_t D>
int orientation_of(const std::array<point<D>, D + 1>& p) {
  if constexpr (D == 2)
    return geometry::orient2d(p[0], p[1], p[2]);
  else
    return geometry::orient3d(p[0], p[1], p[2], p[3]);
}

/// True if facet vertex sequences a and b list the same vertices in opposite orientation.
template <std::size_t N>
bool opposite_orientation(std::array<vertex_id, N> a, std::array<vertex_id, N> b) {
  // parity of the permutation taking a to b, plus equality of sets
  std::array<vertex_id, N> sa = a, sb = b;
  std::sort(sa.begin(), sa.end());
  std::sort(sb.begin(), sb.end());
  if (sa != sb) return false;
  int swaps = 0;
  for (std::size_t i = 0; i < N; ++i) {
    if (a[i] == b[i]) continue;
    auto j = static_cast<std::size_t>(std::find(a.begin() + static_cast<long>(i) + 1, a.end(), b[i]) - a.begin());
    std::swap(a[i], a[j]);
    ++swaps;
  }
  return swaps % 2 == 1;
}

template <domain_model Dm>
void check_domain(const Dm& d) {
  constexpr std::size_t D = dimension_v<Dm>;
  const auto& segs = segments(d);
  BOOST_TEST_REQUIRE(std::ranges::size(segs) >= 1u);
  std::size_t total_cells = 0;
  for (const auto& s : segs) {
    BOOST_TEST_CONTEXT("segment " << name(s)) {
      total_cells += num_cells(s);
      for (cell_id c : cells(s)) {
        const auto vs = vertices(s, c);
        std::array<point<D>, D + 1> p;
        for (std::size_t k = 0; k <= D; ++k) p[k] = position(d, vs[k]);
        BOOST_TEST(orientation_of<D>(p) == 1);  // cells are positively oriented
        for (const facet f : facets(s, c)) {
          // the facet faces into its cell: the opposite vertex is on its positive side
          const auto fv = vertices(s, f);
          std::array<point<D>, D + 1> q;
          for (std::size_t k = 0; k < D; ++k) q[k] = position(d, fv[k]);
          q[D] = position(d, vs[static_cast<std::size_t>(f.index)]);
          BOOST_TEST(orientation_of<D>(q) == 1);
          const cell_id n = neighbour(s, f);
          if (n == no_cell) continue;
          // the neighbour points back, across the same facet, seen in opposite orientation
          int back = -1;
          for (int j = 0; j <= static_cast<int>(D); ++j)
            if (neighbour(s, n, j) == c) back = j;
          BOOST_TEST_REQUIRE(back >= 0);
          BOOST_TEST(opposite_orientation(fv, vertices(s, facet{n, back})));
        }
        // every vertex of the cell sees the cell among its cells
        for (vertex_id v : vs) {
          bool found = false;
          for (cell_id a : cells(s, v)) found |= (a == c);
          BOOST_TEST(found);
        }
        for (const auto& e : edges(s, c)) {
          BOOST_TEST((std::ranges::find(vs, e[0]) != vs.end() && std::ranges::find(vs, e[1]) != vs.end()));
          BOOST_TEST(e[0] != e[1]);
        }
      }
      // cells around a vertex contain it
      std::set<vertex_id> used;
      for (cell_id c : cells(s))
        for (vertex_id v : vertices(s, c)) used.insert(v);
      for (vertex_id v : used)
        for (cell_id a : cells(s, v)) {
          const auto vs = vertices(s, a);
          BOOST_TEST((std::ranges::find(vs, v) != vs.end()));
        }
      // boundary facets are exactly the facets without neighbour
      for (const facet f : boundary_facets(s)) BOOST_TEST(neighbour(s, f) == no_cell);
    }
  }
  BOOST_TEST(total_cells > 0u);
  // interface facets appear in both segments, with opposite orientation
  for (std::size_t a = 0; a < std::ranges::size(segs); ++a)
    for (std::size_t b = a + 1; b < std::ranges::size(segs); ++b) {
      const auto ab = interface_facets(d, a, b);
      const auto ba = interface_facets(d, b, a);
      BOOST_TEST(ab.size() == ba.size());
      for (const auto& i : ab) {
        BOOST_TEST(neighbour(segs[a], i.first) == no_cell);
        BOOST_TEST(neighbour(segs[b], i.second) == no_cell);
        BOOST_TEST(opposite_orientation(vertices(segs[a], i.first), vertices(segs[b], i.second)));
      }
    }
}

}  // namespace gsse::test
