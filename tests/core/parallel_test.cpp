#define BOOST_TEST_MODULE parallel
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <atomic>
#include <functional>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <thread>
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
      const cell_id n = many.neighbour(c, i);
      inner += n != no_cell;
      if (n == no_cell) continue;
      // neighbour i is across the facet opposite vertex i: it holds that facet's vertices and not
      // vertex i, and names c back across the same facet
      const auto& a = g.cells[c];
      const auto& b = g.cells[n];
      for (int j = 0; j < 4; ++j) BOOST_TEST_REQUIRE(std::ranges::count(b, a[static_cast<std::size_t>(j)]) == (j == i ? 0 : 1));
      int back = 0;
      for (int j = 0; j < 4; ++j)
        if (many.neighbour(n, j) == c) {
          ++back;
          BOOST_TEST_REQUIRE(std::ranges::count(a, b[static_cast<std::size_t>(j)]) == 0);
        }
      BOOST_TEST_REQUIRE(back == 1);
    }
  BOOST_TEST(inner == 4 * g.cells.size() - 2 * 6 * 20 * 20);  // every facet but the 4800 on the cube's faces
}

// the parallel for_each runs on kept threads: loops of any width, loops inside loops, and a loop
// after one that threw must all still visit every element exactly once
BOOST_AUTO_TEST_CASE(for_each_threads_are_reused_safely) {
  for (unsigned t : {2u, 5u, 3u, 8u, 2u}) {
    std::vector<std::atomic<int>> hits(1000);
    std::vector<int> ids(hits.size());
    std::iota(ids.begin(), ids.end(), 0);
    for_each(execution::par(t), ids, [&](int i) { ++hits[static_cast<std::size_t>(i)]; });
    for (auto& h : hits) BOOST_TEST_REQUIRE(h.load() == 1);
  }
  std::vector<int> outer(8), inner(50);
  std::iota(outer.begin(), outer.end(), 0);
  std::iota(inner.begin(), inner.end(), 0);
  std::vector<std::atomic<int>> cells(outer.size() * inner.size());
  for_each(execution::par(2), outer, [&](int o) {
    for_each(execution::par(2), inner, [&](int i) { ++cells[static_cast<std::size_t>(o) * inner.size() + static_cast<std::size_t>(i)]; });
  });
  for (auto& c : cells) BOOST_TEST_REQUIRE(c.load() == 1);
  BOOST_CHECK_THROW(for_each(execution::par(2), inner, [](int i) {
                      if (i == 17) throw std::runtime_error("boom");
                    }),
                    std::runtime_error);
  std::atomic<int> after{0};
  for_each(execution::par(2), inner, [&](int) { ++after; });
  BOOST_TEST(after.load() == 50);
}

// beyond 64 elements per thread the cheap ones are handed out in runs: whatever the cost estimates
// (zero, a few huge, not a number), every element is still visited exactly once, and a throw
// inside a run still reaches the caller
BOOST_AUTO_TEST_CASE(for_each_runs_visit_every_element_once_whatever_the_costs) {
  std::vector<int> ids(5000);
  std::iota(ids.begin(), ids.end(), 0);
  const std::vector<std::function<double(int)>> estimates{
      [](int) { return 0.0; },
      [](int i) { return i % 997 == 0 ? 1e9 : 1.0; },
      [](int i) { return static_cast<double>(i % 7); },
      [](int i) { return i == 3 ? std::numeric_limits<double>::quiet_NaN() : 2.0; }};
  for (unsigned t : {2u, 3u})
    for (const auto& cost : estimates) {
      std::vector<std::atomic<int>> hits(ids.size());
      for_each(execution::par(t), ids, [&](int i) { ++hits[static_cast<std::size_t>(i)]; }, cost);
      for (auto& h : hits) BOOST_TEST_REQUIRE(h.load() == 1);
    }
  BOOST_CHECK_THROW(for_each(execution::par(2), ids, [](int i) {
                      if (i == 4321) throw std::runtime_error("boom");
                    }, [](int) { return 0.0; }),
                    std::runtime_error);
}

BOOST_AUTO_TEST_CASE(zero_threads_means_every_hardware_thread_everywhere) {
  // one meaning of a thread count: for_each, the parallel sort and the writers all resolve 0 here
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  BOOST_TEST(gsse::execution::thread_count(0) == hw);
  BOOST_TEST(gsse::execution::thread_count(3) == 3u);
  std::vector<int> v(1000, 0);
  std::atomic<int> seen{0};
  gsse::for_each(gsse::execution::par(0), v, [&](int& x) { x = 1, ++seen; });
  BOOST_TEST(seen.load() == 1000);
}
