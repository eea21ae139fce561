#define BOOST_TEST_MODULE hash_grid
#include <boost/test/unit_test.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>

#include "gsse/geometry/hash_grid.hpp"

// hash_grid::insert_simplex files a slanted segment or triangle in the cells it meets, not in every
// cell of its bounding box. What the lattice placement needs (pipeline, keep-off from the boundary):
// any point within one cell size of the simplex finds it in the ring of cells about its own.

using namespace gsse;

namespace {

template <std::size_t D>
point<D> random_point(std::mt19937_64& g, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  point<D> p;
  for (auto& x : p) x = u(g);
  return p;
}

/// A point of the simplex v (random barycentric weights) moved by less than `reach` (doubles).
template <std::size_t D>
point<D> near_point(std::mt19937_64& g, const std::array<point<D>, D>& v, double reach) {
  std::uniform_real_distribution<double> u(0, 1);
  std::array<double, D> w;
  double sum = 0;
  for (auto& x : w) sum += (x = u(g));
  point<D> p{};
  for (std::size_t i = 0; i < D; ++i) p = p + (w[i] / sum) * v[i];
  point<D> d = random_point<D>(g, -1, 1);
  double n = 0;
  for (auto x : d) n += x * x;
  return p + (0.999 * reach * u(g) / std::sqrt(n)) * d;
}

template <std::size_t D>
void every_near_point_finds_its_simplex(unsigned seed) {
  std::mt19937_64 g(seed);
  for (int trial = 0; trial < 200; ++trial) {
    const double cell = std::uniform_real_distribution<double>(0.003, 0.2)(g);
    hash_grid<D> grid(random_point<D>(g, -1, 0), cell);
    std::array<point<D>, D> v;
    for (auto& q : v) q = random_point<D>(g, -1, 1);
    grid.insert_simplex(7, v);
    for (int k = 0; k < 200; ++k) {
      const point<D> q = near_point<D>(g, v, cell);
      bool found = false;
      grid.visit_ring(q, 1, [&](std::uint32_t id) { found = found || id == 7; });
      BOOST_TEST_REQUIRE(found, "trial " << trial << ": a point within one cell of the simplex missed it");
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(near_points_find_the_triangle) { every_near_point_finds_its_simplex<3>(11); }
BOOST_AUTO_TEST_CASE(near_points_find_the_segment) { every_near_point_finds_its_simplex<2>(12); }

// A slanted triangle across a box of 100^3 cells is filed in about (its area / cell^2) cells
// times a few, not in the million of its box; an axis-aligned one in its own layer of cells.
BOOST_AUTO_TEST_CASE(cells_follow_the_triangle_not_its_box) {
  const double cell = 0.01;
  {
    hash_grid<3> grid(point3{0, 0, 0}, cell);
    grid.insert_simplex(1, {point3{0.001, 0.002, 0.003}, point3{0.999, 0.3, 0.7}, point3{0.2, 0.998, 0.997}});
    BOOST_TEST(grid.occupied() > 5000u);   // the triangle's area / cell^2 is about 5,700
    BOOST_TEST(grid.occupied() < 60000u);  // its box holds about 1e6 cells
  }
  {
    hash_grid<3> grid(point3{0, 0, 0}, cell);
    grid.insert_simplex(1, {point3{0.001, 0.002, 0.5}, point3{0.999, 0.002, 0.5}, point3{0.001, 0.998, 0.5}});
    BOOST_TEST(grid.occupied() <= 100u * 100u);  // one layer of cells
  }
  {
    // degenerate (collinear): filed by its box, still found
    hash_grid<3> grid(point3{0, 0, 0}, cell);
    grid.insert_simplex(3, {point3{0.1, 0.1, 0.1}, point3{0.2, 0.2, 0.2}, point3{0.3, 0.3, 0.3}});
    bool found = false;
    grid.visit_ring(point3{0.25, 0.25, 0.25}, 1, [&](std::uint32_t id) { found = found || id == 3; });
    BOOST_TEST(found);
  }
}
