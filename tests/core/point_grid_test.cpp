#define BOOST_TEST_MODULE point_grid
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "../support/crowded_points.hpp"
#include "gsse/geometry/point_grid.hpp"

using namespace gsse;

// A grid over points crowded into one cell of the uniform grid (the CAD hammer: 15,929 of 21,000
// points in one cell, every search near them read them all) gives such cells grids of their own:
// every search still sees every point of its ball or box exactly once, and reads few beyond.
BOOST_AUTO_TEST_CASE(crowded_grid_visits_each_point_once_and_little_more) {
  std::mt19937_64 rng(7);
  const auto p = testing::crowded_cube_points(20000, rng);
  const geometry::point_grid<3> grid(p);
  BOOST_TEST(grid.levels() > 2u);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> scale(0, 18);
  std::size_t wasteful = 0;  // balls that read over 4 times what they hold, plus 256
  for (int trial = 0; trial < 400; ++trial) {
    // a ball near the crowded corner, of radius 2^-k, cut by a random half-space through it
    const double r = std::ldexp(1.0, -scale(rng));
    const point3 c{r * u(rng), r * u(rng), r * u(rng)};
    point3 n{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5};
    const double d = dot(n, c) - 0.3 * r * std::sqrt(dot(n, n));
    std::vector<int> seen(p.size(), 0);
    grid.visit_ball(c, r, n, d, [&](vertex_id y, const point3& q) {
      BOOST_TEST_REQUIRE(q == p[y]);
      ++seen[y];
      return true;
    });
    std::size_t in = 0, read = 0;
    for (vertex_id y = 0; y < p.size(); ++y) {
      BOOST_TEST_REQUIRE(seen[y] <= 1);
      read += seen[y];
      const point3 e = p[y] - c;
      if (dot(e, e) <= r * r && dot(n, p[y]) >= d) {
        BOOST_TEST_REQUIRE(seen[y] == 1);
        ++in;
      }
    }
    wasteful += read > 4 * in + 256;
    // the box of the ball: every point in it once; count_box at least the points in it
    std::vector<int> boxed(p.size(), 0);
    const point3 lo{c[0] - r, c[1] - r, c[2] - r}, hi{c[0] + r, c[1] + r, c[2] + r};
    std::size_t in_box = 0;
    grid.visit_box(lo, hi, [&](vertex_id y, const point3&) {
      ++boxed[y];
      return true;
    });
    for (vertex_id y = 0; y < p.size(); ++y) {
      BOOST_TEST_REQUIRE(boxed[y] <= 1);
      bool inside = true;
      for (int a = 0; a < 3; ++a) inside = inside && lo[a] <= p[y][a] && p[y][a] <= hi[a];
      if (inside) BOOST_TEST_REQUIRE(boxed[y] == 1);
      in_box += inside;
    }
    BOOST_TEST_REQUIRE(grid.count_box(lo, hi) >= in_box);
  }
  // a uniform grid reads the crowded corner's cells whole for the small balls (207 of these 400
  // read over 4 times what they hold); the nested grids read little beyond the balls
  BOOST_TEST_MESSAGE(wasteful << " wasteful balls");
  BOOST_TEST(wasteful == 0u);
}

