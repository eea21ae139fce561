#define BOOST_TEST_MODULE parallel
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "gsse/traversal/parallel_sort.hpp"
#include "support/fixtures.hpp"

using namespace gsse;

// many equal keys: a result that differs from std::stable_sort (order or stability) shows
BOOST_AUTO_TEST_CASE(parallel_stable_sort_equals_std_stable_sort) {
  std::mt19937 rng(7);
  std::vector<std::pair<int, int>> in(100003);
  for (std::size_t i = 0; i < in.size(); ++i) in[i] = {static_cast<int>(rng() % 97), static_cast<int>(i)};
  auto by_key = [](const auto& a, const auto& b) { return a.first < b.first; };
  auto expect = in;
  std::stable_sort(expect.begin(), expect.end(), by_key);
  for (unsigned t : {1u, 2u, 3u, 4u, 7u}) {
    auto got = in;
    gsse::stable_sort(execution::par(t), got.begin(), got.end(), by_key);
    BOOST_TEST((got == expect), "threads " << t);
  }
  std::vector<int> small{3, 1, 2};  // below the piece size: one thread's sort
  gsse::stable_sort(execution::par(4), small.begin(), small.end());
  BOOST_TEST((small == std::vector<int>{1, 2, 3}));
}

// finalize() shares the vertex index and the neighbour matching over threads; 48000 cells are
// counted in several pieces, and the index must not depend on how many
BOOST_AUTO_TEST_CASE(finalize_is_the_same_for_any_thread_count) {
  const auto g = test::make_kuhn_grid<3>({20, 20, 20});
  simplicial_complex<3> one, many;
  for (const auto& c : g.cells) one.add_cell(c), many.add_cell(c);
  one.finalize(1);
  many.finalize(4);
  BOOST_TEST(one.used_vertices() == many.used_vertices());
  BOOST_TEST(one.used_vertices().size() == g.points.size());
  std::vector<std::size_t> count(g.points.size(), 0);
  for (const auto& c : g.cells)
    for (auto v : c) ++count[v];
  for (vertex_id v = 0; v < g.points.size(); ++v) {
    const auto a = one.cells_of_vertex(v), b = many.cells_of_vertex(v);
    BOOST_TEST_REQUIRE(std::equal(a.begin(), a.end(), b.begin(), b.end()));
    BOOST_TEST_REQUIRE(b.size() == count[v]);
    BOOST_TEST_REQUIRE(std::is_sorted(b.begin(), b.end()));  // increasing cell ids
    for (auto c : b) BOOST_TEST_REQUIRE(std::ranges::count(g.cells[c], v) == 1);
  }
  std::size_t inner = 0;
  for (cell_id c = 0; c < g.cells.size(); ++c)
    for (int i = 0; i < 4; ++i) {
      BOOST_TEST_REQUIRE(one.neighbour(c, i) == many.neighbour(c, i));
      inner += many.neighbour(c, i) != no_cell;
    }
  BOOST_TEST(inner == 4 * g.cells.size() - 2 * 6 * 20 * 20);  // every facet but the 4800 on the cube's faces
}
