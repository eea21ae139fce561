// Lawson's flips in a round's cavity (modules/refinement/src/cavity_insertion.hpp,
// cavity::flip_to_delaunay): the 2-3 and 3-2 flips turn a cavity that is not locally Delaunay
// into the Delaunay one, its walls untouched; a face neither flip can mend is left and reported.
#define BOOST_TEST_MODULE cavity_flip
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <array>
#include <map>
#include <vector>

#include "cavity_insertion.hpp"
#include "gsse/geometry/predicates.hpp"

using namespace gsse;
namespace ins = gsse::refinement::insertion;

namespace {

// the cells made positive, with neighbours across shared faces and every other face a fixed wall
ins::cavity make(const std::vector<point3>& p, std::vector<ins::cell> cells) {
  for (auto& c : cells)
    if (geometry::orient3d(p[c[0]], p[c[1]], p[c[2]], p[c[3]]) < 0) std::swap(c[0], c[1]);
  std::vector<std::array<std::int32_t, 4>> nb(cells.size(), {ins::fixed, ins::fixed, ins::fixed, ins::fixed});
  std::map<std::array<vertex_id, 3>, std::pair<std::size_t, int>> seen;
  for (std::size_t a = 0; a < cells.size(); ++a)
    for (int i = 0; i < 4; ++i) {
      auto f = ins::face_of(cells[a], i);
      std::sort(f.begin(), f.end());
      if (auto it = seen.find(f); it != seen.end()) {
        nb[a][static_cast<std::size_t>(i)] = static_cast<std::int32_t>(it->second.first);
        nb[it->second.first][static_cast<std::size_t>(it->second.second)] = static_cast<std::int32_t>(a);
      } else {
        seen[f] = {a, i};
      }
    }
  return ins::cavity(std::span<const point3>(p), std::move(cells), std::move(nb));
}

// the faces met once (the walls), sorted
std::vector<std::array<vertex_id, 3>> walls(const std::vector<ins::cell>& cells) {
  std::map<std::array<vertex_id, 3>, int> count;
  for (const auto& c : cells)
    for (int i = 0; i < 4; ++i) {
      auto f = ins::face_of(c, i);
      std::sort(f.begin(), f.end());
      ++count[f];
    }
  std::vector<std::array<vertex_id, 3>> out;
  for (const auto& [f, n] : count)
    if (n == 1) out.push_back(f);
  return out;
}

// every cell positive and every pair across a face locally Delaunay (the cavity's own test)
void check_delaunay(const std::vector<point3>& p, const std::vector<ins::cell>& cells) {
  for (const auto& c : cells) BOOST_TEST(geometry::orient3d(p[c[0]], p[c[1]], p[c[2]], p[c[3]]) > 0);
  for (const auto& c : cells)
    for (const auto& d : cells)
      for (auto v : d)
        if (std::find(c.begin(), c.end(), v) == c.end()) {
          // a vertex of a cell sharing a face with c lies outside c's ball
          std::size_t shared = 0;
          for (auto w : d) shared += std::find(c.begin(), c.end(), w) != c.end();
          if (shared == 3) BOOST_TEST(geometry::in_sphere_perturbed(p[c[0]], p[c[1]], p[c[2]], p[c[3]], p[v]) < 0);
        }
}

// a triangle f = 0 1 2 in z = 0, and u = 3, v = 4 above and below its inside
std::vector<point3> points(double h) { return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, h}, {0.3, 0.3, -h}}; }

}  // namespace

// two cells on the face f, flat enough that each holds the other's apex: a 2-3 flip to three
// cells about the edge uv
BOOST_AUTO_TEST_CASE(two_cells_not_delaunay_become_three) {
  const auto p = points(0.2);
  const std::vector<ins::cell> before{{0, 1, 2, 3}, {0, 1, 2, 4}};
  auto cav = make(p, before);
  BOOST_TEST(!cav.locally_delaunay());
  BOOST_TEST(cav.flip_to_delaunay());
  const auto after = cav.cells();
  BOOST_TEST(after.size() == 3u);
  for (const auto& c : after) BOOST_TEST((std::find(c.begin(), c.end(), 3u) != c.end() && std::find(c.begin(), c.end(), 4u) != c.end()));
  BOOST_TEST((walls(after) == walls(before)));
  check_delaunay(p, after);
}

// three cells about the edge uv, which is long: a 3-2 flip to the two cells on f
BOOST_AUTO_TEST_CASE(three_cells_about_a_long_edge_become_two) {
  const auto p = points(1.0);
  const std::vector<ins::cell> before{{0, 1, 3, 4}, {1, 2, 3, 4}, {2, 0, 3, 4}};
  auto cav = make(p, before);
  BOOST_TEST(!cav.locally_delaunay());
  BOOST_TEST(cav.flip_to_delaunay());
  const auto after = cav.cells();
  BOOST_TEST(after.size() == 2u);
  BOOST_TEST((walls(after) == walls(before)));
  check_delaunay(p, after);
}

// already Delaunay: nothing changes
BOOST_AUTO_TEST_CASE(a_delaunay_cavity_is_left_as_it_is) {
  const auto p = points(1.0);
  const std::vector<ins::cell> before{{0, 1, 2, 3}, {0, 1, 2, 4}};
  auto cav = make(p, before);
  BOOST_TEST(cav.locally_delaunay());
  BOOST_TEST(cav.flip_to_delaunay());
  BOOST_TEST(cav.cells().size() == 2u);
}

// the face between the two flat cells is a wall (each cell's face there is fixed): no flip
// crosses a wall, and with no face between two cells the cavity counts as locally Delaunay
BOOST_AUTO_TEST_CASE(a_wall_is_never_flipped) {
  const auto p = points(0.2);
  std::vector<ins::cell> cells{{0, 1, 2, 3}, {0, 1, 2, 4}};
  for (auto& c : cells)
    if (geometry::orient3d(p[c[0]], p[c[1]], p[c[2]], p[c[3]]) < 0) std::swap(c[0], c[1]);
  std::vector<std::array<std::int32_t, 4>> nb(2, {ins::fixed, ins::fixed, ins::fixed, ins::fixed});
  ins::cavity cav(std::span<const point3>(p), cells, nb);
  BOOST_TEST(cav.flip_to_delaunay());  // locally Delaunay: no two cells meet at a face
  BOOST_TEST(cav.cells().size() == 2u);
}

// two flat cells whose apexes lie beyond the edge 0-1 of their face: the union is not convex
// there, and no third cell about that edge makes a 3-2 flip. Neither flip applies: the cavity is
// reported not Delaunay and left as it was (the caller's fallback takes it)
BOOST_AUTO_TEST_CASE(a_face_neither_flip_mends_is_reported) {
  const std::vector<point3> p{{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -0.2, 0.05}, {0.5, -0.2, -0.05}};
  const std::vector<ins::cell> before{{0, 1, 2, 3}, {0, 1, 2, 4}};
  auto cav = make(p, before);
  BOOST_TEST_REQUIRE(!cav.locally_delaunay());
  BOOST_TEST(!cav.flip_to_delaunay());
  auto after = cav.cells();
  BOOST_TEST(after.size() == 2u);
  BOOST_TEST((walls(after) == walls(before)));
}
