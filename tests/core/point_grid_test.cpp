#define BOOST_TEST_MODULE point_grid
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "../support/crowded_points.hpp"
#include "gsse/geometry/point_grid.hpp"

using namespace gsse;

// A grid over points crowded into one cell of the uniform grid (the CAD hammer: 15,929 of 21,000
// points in one cell, every search near them read them all) gives such cells grids of their own:
// every search still sees every point of its ball or box exactly once, and reads few beyond.
// Returns the balls (of 400) that read over 4 times what they hold, plus 256.
template <std::size_t D>
std::size_t check_crowded(std::uint64_t seed, std::size_t count) {
  std::mt19937_64 rng(seed);
  const auto p = testing::crowded_points<D>(count, rng);
  const geometry::point_grid<D> grid(p);
  BOOST_TEST(grid.levels() > 2u);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> scale(0, 18);
  std::size_t wasteful = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // a ball near the crowded corner, of radius 2^-k, cut by a random half-space through it
    const double r = std::ldexp(1.0, -scale(rng));
    point<D> c, n;
    for (auto& x : c) x = r * u(rng);
    for (auto& x : n) x = u(rng) - 0.5;
    const double d = dot(n, c) - 0.3 * r * std::sqrt(dot(n, n));
    std::vector<int> seen(p.size(), 0);
    grid.visit_ball(c, r, n, d, [&](vertex_id y, const point<D>& q) {
      BOOST_TEST_REQUIRE(q == p[y]);
      ++seen[y];
      return true;
    });
    std::size_t in = 0, read = 0;
    for (vertex_id y = 0; y < p.size(); ++y) {
      BOOST_TEST_REQUIRE(seen[y] <= 1);
      read += static_cast<std::size_t>(seen[y]);
      const point<D> e = p[y] - c;
      if (dot(e, e) <= r * r && dot(n, p[y]) >= d) {
        BOOST_TEST_REQUIRE(seen[y] == 1);
        ++in;
      }
    }
    wasteful += read > 4 * in + 256;
    // the box of the ball: every point in it once; count_box at least the points in it
    std::vector<int> boxed(p.size(), 0);
    point<D> lo, hi;
    for (std::size_t a = 0; a < D; ++a) lo[a] = c[a] - r, hi[a] = c[a] + r;
    std::size_t in_box = 0;
    grid.visit_box(lo, hi, [&](vertex_id y, const point<D>&) {
      ++boxed[y];
      return true;
    });
    for (vertex_id y = 0; y < p.size(); ++y) {
      BOOST_TEST_REQUIRE(boxed[y] <= 1);
      bool inside = true;
      for (std::size_t a = 0; a < D; ++a) inside = inside && lo[a] <= p[y][a] && p[y][a] <= hi[a];
      if (inside) BOOST_TEST_REQUIRE(boxed[y] == 1);
      in_box += inside;
    }
    BOOST_TEST_REQUIRE(grid.count_box(lo, hi) >= in_box);
  }
  BOOST_TEST_MESSAGE(wasteful << " wasteful balls in " << D << "D");
  return wasteful;
}

// A uniform grid reads the crowded corner's cells whole for the small balls (3D: 207 of these 400
// read over 4 times what they hold, plus 256; 2D: 123); the nested grids read little beyond the balls.
BOOST_AUTO_TEST_CASE(crowded_grid_visits_each_point_once_and_little_more) {
  BOOST_TEST(check_crowded<3>(7, 20000) == 0u);
}

BOOST_AUTO_TEST_CASE(crowded_grid_2d) {
  BOOST_TEST(check_crowded<2>(9, 20000) == 0u);
}
