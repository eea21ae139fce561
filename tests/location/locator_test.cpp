#define BOOST_TEST_MODULE location
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <array>
#include <vector>

#include "gsse/geometry/predicates.hpp"
#include "gsse/location/locator.hpp"

// location::locator against answers known without its predicates: the Kuhn triangulation of the
// unit cube (square), whose simplex for the axis order (a, b, c) holds q exactly when
// 1 >= q[a] >= q[b] >= q[c] >= 0, asked at every point of a dyadic grid (exact in doubles)
// reaching past the cube, ties (points on shared faces, edges, vertices) included; and cells of
// zero volume, which a look-up must never answer with.

using namespace gsse;

namespace {

template <std::size_t D>
using cells_t = std::vector<std::vector<location::cell_t<D>>>;

/// The axis orders of the Kuhn simplices, each simplex's vertices: 0, then one unit step along
/// each axis in the order's turn.
template <std::size_t D>
std::vector<std::array<int, D>> axis_orders() {
  std::array<int, D> a;
  for (std::size_t k = 0; k < D; ++k) a[k] = static_cast<int>(k);
  std::vector<std::array<int, D>> out;
  do out.push_back(a);
  while (std::next_permutation(a.begin(), a.end()));
  return out;
}

/// The cube's corners (index = bit mask of the unit coordinates) and the Kuhn simplex of order a,
/// positively oriented (by the predicate: the orientation is the test's input, not its answer).
template <std::size_t D>
std::vector<point<D>> corners() {
  std::vector<point<D>> p(std::size_t{1} << D);
  for (std::size_t m = 0; m < p.size(); ++m)
    for (std::size_t k = 0; k < D; ++k) p[m][k] = (m >> k) & 1u ? 1.0 : 0.0;
  return p;
}
template <std::size_t D>
location::cell_t<D> kuhn(const std::vector<point<D>>& p, const std::array<int, D>& a) {
  location::cell_t<D> c{};
  vertex_id m = 0;
  c[0] = 0;
  for (std::size_t k = 0; k < D; ++k) c[k + 1] = m |= vertex_id{1} << a[k];
  int o;
  if constexpr (D == 2)
    o = geometry::orient2d(p[c[0]], p[c[1]], p[c[2]]);
  else
    o = geometry::orient3d(p[c[0]], p[c[1]], p[c[2]], p[c[3]]);
  BOOST_REQUIRE(o != 0);
  if (o < 0) std::swap(c[0], c[1]);
  return c;
}
template <std::size_t D>
bool kuhn_holds(const std::array<int, D>& a, const point<D>& q) {
  if (q[static_cast<std::size_t>(a[0])] > 1 || q[static_cast<std::size_t>(a[D - 1])] < 0) return false;
  for (std::size_t k = 0; k + 1 < D; ++k)
    if (q[static_cast<std::size_t>(a[k])] < q[static_cast<std::size_t>(a[k + 1])]) return false;
  return true;
}

/// The grid points k/4, k = -1..5, along every axis.
template <std::size_t D>
std::vector<point<D>> grid_points() {
  std::vector<point<D>> out;
  std::array<int, D> i;
  i.fill(-1);
  for (;;) {
    point<D> q;
    for (std::size_t k = 0; k < D; ++k) q[k] = i[k] / 4.0;
    out.push_back(q);
    std::size_t k = 0;
    while (k < D && ++i[k] > 5) i[k++] = -1;
    if (k == D) return out;
  }
}

/// Checks m (over `cells`, whose Kuhn simplices are `kuhn_of[index]`, -1 for a cell to ignore)
/// at every grid point and in the plane of the flat cells at `extra` points: the least index of
/// a simplex holding q, its region, and the hinted look-ups from every hint.
template <std::size_t D>
void check(const location::locator<D>& m, const cells_t<D>& cells, const std::vector<int>& kuhn_of,
           const std::vector<std::array<int, D>>& orders, const std::vector<point<D>>& extra) {
  std::vector<int> region;
  for (std::size_t r = 0; r < cells.size(); ++r) region.insert(region.end(), cells[r].size(), static_cast<int>(r));
  auto points = grid_points<D>();
  points.insert(points.end(), extra.begin(), extra.end());
  std::size_t inside = 0, ties = 0;
  for (const auto& q : points) {
    std::uint32_t expect = location::locator<D>::no_cell;
    int holders = 0;
    for (std::size_t c = 0; c < kuhn_of.size(); ++c)
      if (kuhn_of[c] >= 0 && kuhn_holds<D>(orders[static_cast<std::size_t>(kuhn_of[c])], q)) {
        if (expect == location::locator<D>::no_cell) expect = static_cast<std::uint32_t>(c);
        ++holders;
      }
    inside += holders > 0, ties += holders > 1;
    BOOST_TEST(m.cell_holding(q) == expect);
    const int r = expect == location::locator<D>::no_cell ? -1 : region[expect];
    BOOST_TEST(m.region_of(q) == r);
    BOOST_TEST(m.in_segment(q) == (r >= 0));
    for (std::uint32_t h0 = 0; h0 <= kuhn_of.size(); ++h0) {
      const std::uint32_t start = h0 == kuhn_of.size() ? location::locator<D>::no_cell : h0;
      std::uint32_t hint = start;
      BOOST_TEST(m.region_of(q, hint) == r);
      // after an answer the hint is a cell that holds q (a simplex, not a flat cell)
      if (r >= 0) BOOST_TEST((hint < kuhn_of.size() && kuhn_of[hint] >= 0 && kuhn_holds<D>(orders[static_cast<std::size_t>(kuhn_of[hint])], q)));
      hint = start;
      BOOST_TEST(m.in_segment(q, hint) == (r >= 0));
    }
  }
  BOOST_TEST(inside > 0u);  // the grid meets the inside, the outside and the shared faces
  BOOST_TEST(inside < points.size());
  BOOST_TEST(ties > 0u);
}

}  // namespace

BOOST_AUTO_TEST_CASE(kuhn_cube_located_exactly_3d) {
  const auto p = corners<3>();
  const auto orders = axis_orders<3>();
  cells_t<3> cells(3);  // region = the order's first axis: a shared face between regions
  std::vector<int> kuhn_of;
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t o = 0; o < orders.size(); ++o)
      if (orders[o][0] == static_cast<int>(r)) cells[r].push_back(kuhn<3>(p, orders[o])), kuhn_of.push_back(static_cast<int>(o));
  const location::locator<3> m(p, cells);
  BOOST_TEST(m.cells() == 6u);
  BOOST_TEST(m.flat_cells() == 0u);
  BOOST_TEST((m.lo() == point3{0, 0, 0}));
  BOOST_TEST((m.hi() == point3{1, 1, 1}));
  check<3>(m, cells, kuhn_of, orders, {});
}

BOOST_AUTO_TEST_CASE(kuhn_square_located_exactly_2d) {
  const auto p = corners<2>();
  const auto orders = axis_orders<2>();
  cells_t<2> cells(2);
  std::vector<int> kuhn_of;
  for (std::size_t o = 0; o < orders.size(); ++o) cells[o].push_back(kuhn<2>(p, orders[o])), kuhn_of.push_back(static_cast<int>(o));
  const location::locator<2> m(p, cells);
  BOOST_TEST(m.flat_cells() == 0u);
  check<2>(m, cells, kuhn_of, orders, {});
}

// A cell of zero volume holds (closed) every point of its plane: all its facets' orientations
// about such a point are 0. Put first (the least index, what cell_holding prefers), one lies in
// the plane x = y through the cube, across the face two regions share, and one in the plane
// z = 2 above it, outside the mesh; the look-ups must answer as if neither were there, hinted
// at them too (the grid and the extra points include points of both planes).
BOOST_AUTO_TEST_CASE(cells_of_zero_volume_are_never_the_answer_3d) {
  auto p = corners<3>();
  const auto orders = axis_orders<3>();
  const vertex_id top = static_cast<vertex_id>(p.size());
  for (const point3& q : {point3{0, 0, 2}, point3{1, 0, 2}, point3{0, 1, 2}, point3{1, 1, 2}}) p.push_back(q);
  cells_t<3> cells(3);
  std::vector<int> kuhn_of;
  cells[0].push_back({0, 3, 4, 7});                      // (0,0,0) (1,1,0) (0,0,1) (1,1,1): plane x = y
  cells[0].push_back({top, top + 1, top + 2, top + 3});  // plane z = 2
  kuhn_of.push_back(-1), kuhn_of.push_back(-1);
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t o = 0; o < orders.size(); ++o)
      if (orders[o][0] == static_cast<int>(r)) cells[r].push_back(kuhn<3>(p, orders[o])), kuhn_of.push_back(static_cast<int>(o));
  const location::locator<3> m(p, cells);
  BOOST_TEST(m.cells() == 8u);
  BOOST_TEST(m.flat_cells() == 2u);
  check<3>(m, cells, kuhn_of, orders, {point3{0.5, 0.5, 2}, point3{0.25, 0.75, 2}, point3{0.3, 0.3, 0.7}, point3{0.6, 0.6, 0.1}});
}

BOOST_AUTO_TEST_CASE(cells_of_zero_volume_are_never_the_answer_2d) {
  auto p = corners<2>();
  const auto orders = axis_orders<2>();
  const vertex_id off = static_cast<vertex_id>(p.size());
  for (const point2& q : {point2{2, 0}, point2{2, 0.5}, point2{2, 1}}) p.push_back(q);
  cells_t<2> cells(2);
  std::vector<int> kuhn_of;
  cells[0].push_back({0, 3, 0});                // a triangle with a repeated corner on the diagonal x = y
  cells[0].push_back({off, off + 1, off + 2});  // on the line x = 2, beside the square
  kuhn_of.push_back(-1), kuhn_of.push_back(-1);
  for (std::size_t o = 0; o < orders.size(); ++o) cells[o].push_back(kuhn<2>(p, orders[o])), kuhn_of.push_back(static_cast<int>(o));
  const location::locator<2> m(p, cells);
  BOOST_TEST(m.flat_cells() == 2u);
  check<2>(m, cells, kuhn_of, orders, {point2{0.3, 0.3}, point2{2, 0.25}, point2{2, 0.75}});
}
