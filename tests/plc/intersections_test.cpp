#define BOOST_TEST_MODULE plc_intersections
#include <boost/test/unit_test.hpp>

#include <iostream>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <numbers>
#include <variant>

#include "gsse/io/poly.hpp"
#include "gsse/plc/intersections.hpp"
#include "support/plc_builder.hpp"
#include "support/shared.hpp"

using namespace gsse;
namespace pc = gsse::plc_check;

namespace {

using builder3 = gsse::test::plc_builder;

std::vector<pc::intersection> check(const plc<3>& p) { return pc::self_intersections(p); }

void expect_one(const std::vector<pc::intersection>& r, std::uint32_t a, std::uint32_t b, const std::string& what) {
  BOOST_TEST_REQUIRE(r.size() == 1u);
  BOOST_TEST(r[0].a == a);
  BOOST_TEST(r[0].b == b);
  BOOST_TEST(r[0].what == what);
}

void expect_sorted(const std::vector<pc::intersection>& r) {
  for (std::size_t k = 0; k < r.size(); ++k) {
    BOOST_TEST(r[k].a <= r[k].b);
    if (k) BOOST_TEST((std::tie(r[k - 1].a, r[k - 1].b) < std::tie(r[k].a, r[k].b)));
  }
}

/// The quadrilateral facets of a PLC split into two triangle facets each (as an STL export).
plc<3> as_triangles(const plc<3>& p) {
  plc<3> q = p;
  q.facets.clear();
  for (const auto& f : p.facets) {
    const auto& l = f.polygons[0];
    if (f.polygons.size() == 1 && l.size() == 4) {
      q.facets.push_back({{{l[0], l[1], l[2]}}, {}, 0, f.line});
      q.facets.push_back({{{l[0], l[2], l[3]}}, {}, 0, f.line});
    } else {
      q.facets.push_back(f);
    }
  }
  return q;
}

/// Turns a PLC by a generic rotation: its facets are then planar only up to rounding.
template <class P>
P rotated(P p) {
  const double a = 0.3, b = 0.7, c = 1.1;
  auto rot = [&](point3 x) {
    x = {x[0], std::cos(c) * x[1] - std::sin(c) * x[2], std::sin(c) * x[1] + std::cos(c) * x[2]};
    x = {std::cos(b) * x[0] + std::sin(b) * x[2], x[1], -std::sin(b) * x[0] + std::cos(b) * x[2]};
    return point3{std::cos(a) * x[0] - std::sin(a) * x[1], std::sin(a) * x[0] + std::cos(a) * x[1], x[2]};
  };
  for (auto& x : p.points) x = rot(x);
  for (auto& f : p.facets)
    for (auto& h : f.holes) h = rot(h);
  return p;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(solids)

BOOST_AUTO_TEST_CASE(cube_is_clean) {
  builder3 b;
  b.box({0, 0, 0}, {1, 1, 1});
  BOOST_TEST(check(b.p).empty());
  BOOST_TEST(check(as_triangles(b.p)).empty());
  BOOST_TEST(check(rotated(b.p)).empty());
  BOOST_CHECK_NO_THROW(pc::require_no_self_intersections(b.p));
}

BOOST_AUTO_TEST_CASE(facet_piercing_the_top) {
  builder3 b;
  b.box({0, 0, 0}, {1, 1, 1});
  b.facet({{0.5, 0.25, 0.5}, {0.5, 0.75, 0.5}, {0.5, 0.75, 1.5}, {0.5, 0.25, 1.5}});
  expect_one(check(b.p), 1, 6, "they cross");
  BOOST_TEST(pc::message(b.p, check(b.p)[0]) == "cube.poly:22: facet 7 (line 22) intersects facet 2 (line 12): they cross");
  BOOST_CHECK_EXCEPTION(pc::require_no_self_intersections(b.p), pc::input_error, [](const pc::input_error& e) {
    return std::string(e.what()) == "cube.poly:22: facet 7 (line 22) intersects facet 2 (line 12): they cross";
  });
  expect_one(check(rotated(b.p)), 1, 6, "they cross");
  // each triangle of the piercing facet meets each of the top (two of them only at the point
  // (0.5, 0.5, 1) on both diagonals)
  BOOST_TEST(check(as_triangles(b.p)).size() == 4u);
}

BOOST_AUTO_TEST_CASE(overlapping_cubes) {
  builder3 b;
  b.box({0, 0, 0}, {1, 1, 1});
  b.box({0.5, 0.5, 0.5}, {1.5, 1.5, 1.5});
  const auto r = check(b.p);
  expect_sorted(r);
  // the top of the first cube (facet 2) crosses the walls y = 0.5 and x = 0.5 of the second
  // (9 and 12), its side walls x = 1 and y = 1 (4, 5) cross the second cube's bottom (7) and walls
  std::string pairs;
  for (const auto& x : r) {
    pairs += std::to_string(x.a) + "-" + std::to_string(x.b) + " ";
    BOOST_TEST(x.what == "they cross");
  }
  BOOST_TEST(pairs == "1-8 1-11 3-6 3-8 4-6 4-11 ");
  const auto first = pc::self_intersections(b.p, 2);  // the same first two, the search cut short
  BOOST_TEST_REQUIRE(first.size() == 2u);
  BOOST_TEST(first[0].b == 8u);
  BOOST_TEST(first[1].b == 11u);
  BOOST_CHECK_EXCEPTION(pc::require_no_self_intersections(b.p), pc::input_error, [](const pc::input_error& e) {
    return std::string(e.what()) == "cube.poly:26: facet 9 (line 26) intersects facet 2 (line 12): they cross (and 5 more)";
  });
  // a problem of the last facet alone (found while triangulating; the facet is then left out of
  // the pairs) sorts after them
  b.p.facets[11].polygons.push_back({b.id({0.5, 1, 1.5})});
  const auto all = pc::self_intersections(b.p);
  BOOST_TEST_REQUIRE(all.size() == 5u);
  BOOST_TEST(all[4].a == 11u);
  BOOST_TEST(all[4].what == "vertex " + b.num({0.5, 1, 1.5}) + " lies on its polygon edge " + b.num({0.5, 0.5, 1.5}) +
                                "-" + b.num({0.5, 1.5, 1.5}));
  BOOST_TEST(pc::self_intersections(b.p, 2).size() == 2u);
}

BOOST_AUTO_TEST_CASE(cubes_sharing_a_face) {
  builder3 b;
  b.box({0, 0, 0}, {1, 1, 1});
  b.box({1, 0, 0}, {2, 1, 1});
  const auto shared = b.p.facets[3];  // x = 1
  b.p.facets.erase(b.p.facets.begin() + 11);  // the second cube's x = 1 repeats it
  BOOST_TEST(check(b.p).empty());
  BOOST_TEST(check(as_triangles(b.p)).empty());
  BOOST_TEST(check(rotated(b.p)).empty());
  BOOST_TEST(check(rotated(as_triangles(b.p))).empty());
  // the shared face given twice is a coplanar overlap
  b.p.facets.push_back(shared);
  expect_one(check(b.p), 3, 11, "they overlap in their plane");
}

BOOST_AUTO_TEST_CASE(stacked_cubes_of_different_sizes) {
  // a small cube standing on the top of a large one, on an inner polygon of the top: legal; the
  // same cube standing on the top without that polygon is a T-junction of its bottom's corners
  builder3 b;
  b.box({0, 0, 0}, {2, 2, 1});
  auto top = b.p.facets[1];
  b.box({0.5, 0.5, 1}, {1.5, 1.5, 2});
  b.p.facets.erase(b.p.facets.begin() + 6);  // its bottom: an inner polygon of the top
  b.p.facets[1].polygons.push_back(b.loop({{0.5, 0.5, 1}, {1.5, 0.5, 1}, {1.5, 1.5, 1}, {0.5, 1.5, 1}}));
  BOOST_TEST(check(b.p).empty());
  BOOST_TEST(check(rotated(b.p)).empty());
  b.p.facets[1] = top;
  const auto r = check(b.p);
  BOOST_TEST_REQUIRE(!r.empty());
  BOOST_TEST(r[0].a == 1u);
  BOOST_TEST(r[0].what.starts_with("vertex "));
  BOOST_TEST(r[0].what.ends_with(" lies inside facet 2"));
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(facet_pairs)

const std::vector<point3> floor_square{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};

BOOST_AUTO_TEST_CASE(crossing_interiors) {
  builder3 b;
  b.facet(floor_square);
  b.facet({{1, 0.5, -1}, {1, 1.5, -1}, {1, 1.5, 1}, {1, 0.5, 1}});
  expect_one(check(b.p), 0, 1, "they cross");
}

BOOST_AUTO_TEST_CASE(crossing_at_an_edge) {
  // only the edges meet: (1,0,-1)-(1,0,1) of the second crosses (0,0,0)-(2,0,0) of the first
  builder3 b;
  b.facet(floor_square);
  b.facet({{1, 0, -1}, {1, 0, 1}, {1, -1, 1}});
  expect_one(check(b.p), 0, 1, "they cross");
  // the second's edge lying in the first's interior
  builder3 c;
  c.facet(floor_square);
  c.facet({{1, 0.5, 0}, {1, 1.5, 0}, {1, 1.5, 1}, {1, 0.5, 1}});
  expect_one(check(c.p), 0, 1, "vertex " + c.num({1, 0.5, 0}) + " lies inside facet 1");
}

BOOST_AUTO_TEST_CASE(vertex_inside_another_facet) {
  builder3 b;
  b.facet(floor_square);
  b.facet({{0.5, 0.5, 0}, {0.2, 0.5, 1}, {0.8, 0.5, 1}});
  expect_one(check(b.p), 0, 1, "vertex 5 lies inside facet 1");
  // just above: legal
  b.p.points[4][2] = 1e-300;
  BOOST_TEST(check(b.p).empty());
}

BOOST_AUTO_TEST_CASE(t_junction) {
  // two squares along the edge (0,0,0)-(2,0,0) of a third: their common corner (1,0,0) lies on it
  builder3 b;
  b.facet({{0, -1, 0}, {2, -1, 0}, {2, 0, 0}, {0, 0, 0}});
  b.facet({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  b.facet({{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}});
  const auto r = check(b.p);
  BOOST_TEST_REQUIRE(r.size() == 2u);
  const std::string on = "vertex " + b.num({1, 0, 0}) + " lies on the edge " + b.num({2, 0, 0}) + "-" +
                         b.num({0, 0, 0}) + " of facet 1";
  BOOST_TEST(r[0].a == 0u);
  BOOST_TEST(r[0].b == 1u);
  BOOST_TEST(r[0].what == on);
  BOOST_TEST(r[1].a == 0u);
  BOOST_TEST(r[1].b == 2u);
  BOOST_TEST(r[1].what == on);
  // the same with a wall standing on the edge
  builder3 c;
  c.facet(floor_square);
  c.facet({{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}});
  const auto s = check(c.p);
  BOOST_TEST_REQUIRE(s.size() == 1u);
  BOOST_TEST(s[0].what.find("vertex " + c.num({1, 0, 0}) + " lies on the edge") == 0u);
  // the edge split at (1,0,0) in the floor too: legal
  c.p.facets[0].polygons[0].insert(c.p.facets[0].polygons[0].begin() + 1, c.id({1, 0, 0}));
  BOOST_TEST(check(c.p).empty());
  BOOST_TEST(check(rotated(c.p)).empty());
}

BOOST_AUTO_TEST_CASE(coplanar_overlap) {
  builder3 b;
  b.facet(floor_square);
  b.facet({{1, 1, 0}, {3, 1, 0}, {1, 3, 0}});
  const auto r = check(b.p);
  BOOST_TEST_REQUIRE(r.size() == 1u);
  BOOST_TEST(r[0].what == "vertex " + b.num({1, 1, 0}) + " lies inside facet 1");
  // overlapping without a vertex of one inside the other: a cross of two bars
  builder3 c;
  c.facet({{0, 1, 0}, {3, 1, 0}, {3, 2, 0}, {0, 2, 0}});
  c.facet({{1, 0, 0}, {2, 0, 0}, {2, 3, 0}, {1, 3, 0}});
  expect_one(check(c.p), 0, 1, "they overlap in their plane");
  // sharing an edge, on the same side of it
  builder3 d;
  d.facet(floor_square);
  d.facet({{0, 0, 0}, {2, 0, 0}, {1, 3, 0}});
  expect_one(check(d.p), 0, 1, "they overlap in their plane");
  // one triangle in another over their shared edge; lifted off the plane by a hair it is legal
  builder3 f;
  f.facet({{0, 0, 0}, {2, 0, 0}, {1, 2, 0}});
  f.facet({{0, 0, 0}, {2, 0, 0}, {1, 1, 0}});
  expect_one(check(f.p), 0, 1, "vertex 4 lies inside facet 1");
  f.p.points[3][2] = 1e-300;
  BOOST_TEST(check(f.p).empty());
  // sharing an edge, on opposite sides: legal
  builder3 e;
  e.facet(floor_square);
  e.facet({{0, 0, 0}, {2, 0, 0}, {1, -1, 0}});
  BOOST_TEST(check(e.p).empty());
}

BOOST_AUTO_TEST_CASE(shared_vertex) {
  // two triangles sharing a vertex, coplanar, one folded over the other beyond it
  builder3 b;
  b.facet({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}});
  b.facet({{0, 0, 0}, {1, 1, 0}, {-1, 1, 0}});
  BOOST_TEST(check(b.p).size() == 1u);
  // apart beyond the vertex, coplanar and not
  builder3 c;
  c.facet({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}});
  c.facet({{0, 0, 0}, {-1, 0, 0}, {-1, -1, 0}});
  c.facet({{0, 0, 0}, {-1, 0, 1}, {0, -1, 1}});
  BOOST_TEST(check(c.p).empty());
  // a triangle standing on the vertex, cutting through the first
  c.facet({{0, 0, 0}, {1, 1, 1}, {1, 1, -1}});
  expect_one(check(c.p), 0, 3, "they cross");
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(single_facets)

BOOST_AUTO_TEST_CASE(nested_polygon) {
  // a floor with an inner square, and a box standing on the inner square: legal, with the
  // inner area part of the floor or (hole point) not
  for (bool hole : {false, true}) {
    builder3 b;
    const std::vector<point3> inner{{0.5, 0.5, 0}, {1.5, 0.5, 0}, {1.5, 1.5, 0}, {0.5, 1.5, 0}};
    b.facet({{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, inner},
            hole ? std::vector<point3>{{1, 1, 0}} : std::vector<point3>{});
    b.box({0.5, 0.5, 0}, {1.5, 1.5, 1});
    b.p.facets.erase(b.p.facets.begin() + 1);  // the box's bottom is the inner square
    BOOST_TEST(check(b.p).empty(), "hole " << hole);
    BOOST_TEST(check(rotated(b.p)).empty(), "hole " << hole);
    BOOST_TEST(check(as_triangles(b.p)).empty(), "hole " << hole);
    // a facet filling the inner square overlaps the floor unless the hole point removed it
    b.facet(inner);
    const auto r = check(b.p);
    BOOST_TEST(r.size() == (hole ? 0u : 1u), "hole " << hole);
    if (!hole && !r.empty()) BOOST_TEST(r[0].what == "they overlap in their plane");
    // (turned, the two facets over the inner square need not be coplanar any more: with different
    // diagonals they are the faces of a thin tetrahedron, which is legal)
    if (hole) BOOST_TEST(check(rotated(b.p)).empty());
  }
}

BOOST_AUTO_TEST_CASE(hole_point_between_nested_polygons) {
  // a hole point in the ring between the outer and inner square leaves the inner area: a facet
  // over the ring overlaps nothing, one over the inner square does
  builder3 b;
  const std::vector<point3> outer{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  const std::vector<point3> inner{{0.5, 0.5, 0}, {1.5, 0.5, 0}, {1.5, 1.5, 0}, {0.5, 1.5, 0}};
  b.facet({outer, inner}, {{0.25, 1, 0}});
  b.facet({outer, inner});
  b.p.facets[1].holes = {{1, 1, 0}};
  BOOST_TEST(check(b.p).empty());
  b.p.facets[1].holes.clear();
  BOOST_TEST(check(b.p).size() == 1u);
}

BOOST_AUTO_TEST_CASE(many_nested_polygons) {
  // a disc of 400 corners holding 7 x 7 squares, every other one with a hole point; each square
  // is also a facet of its own: legal where the hole point removed the square from the disc
  builder3 b;
  std::vector<std::vector<point3>> polygons(1);
  for (int i = 0; i < 400; ++i) {
    const double t = 2 * std::numbers::pi * i / 400;
    polygons[0].push_back({10 * std::cos(t), 10 * std::sin(t), 0});
  }
  std::vector<point3> holes;
  std::vector<std::vector<point3>> squares;
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j) {
      const double x = 2.0 * i - 6.5, y = 2.0 * j - 6.5;
      squares.push_back({{x, y, 0}, {x + 1, y, 0}, {x + 1, y + 1, 0}, {x, y + 1, 0}});
      if ((i + j) % 2) holes.push_back({x + 0.5, y + 0.5, 0});
    }
  polygons.insert(polygons.end(), squares.begin(), squares.end());
  b.facet(polygons, holes);
  BOOST_TEST(check(b.p).empty());
  for (const auto& q : squares) b.facet(q);
  auto expect_plugs = [](const std::vector<pc::intersection>& r) {
    BOOST_TEST_REQUIRE(r.size() == 16u);  // the first 16 of 25 squares without a hole point
    for (std::size_t k = 0; k < r.size(); ++k) {
      BOOST_TEST(r[k].a == 0u);
      BOOST_TEST(r[k].b == 1 + 2 * k);
    }
  };
  expect_plugs(check(b.p));
  BOOST_TEST(pc::self_intersections(b.p, 100).size() == 25u);
  // turned, a plug without a hole point may overlap the disc or not (with other diagonals, it and
  // the disc bound a thin tetrahedron); one with a hole point never
  for (const auto& x : pc::self_intersections(rotated(b.p), 100)) BOOST_TEST((x.a == 0u && x.b % 2 == 1), x.b);
}

BOOST_AUTO_TEST_CASE(non_convex_polygons) {
  // a prism over a star with collinear corners: its bottom and top need more than ears of a
  // convex polygon; the walls share their edges
  builder3 b;
  std::vector<point3> bottom, top;
  const int n = 24;
  for (int i = 0; i < n; ++i) {
    const double r = i % 2 ? 1.0 : 0.4, t = 2 * std::numbers::pi * i / n;
    bottom.push_back({r * std::cos(t), r * std::sin(t), 0});
  }
  // collinear corners: the midpoint of every other edge
  std::vector<point3> with_mid;
  for (int i = 0; i < n; ++i) {
    with_mid.push_back(bottom[static_cast<std::size_t>(i)]);
    if (i % 3 == 0) {
      const auto& x = bottom[static_cast<std::size_t>(i)];
      const auto& y = bottom[static_cast<std::size_t>((i + 1) % n)];
      with_mid.push_back({(x[0] + y[0]) / 2, (x[1] + y[1]) / 2, 0});
    }
  }
  for (auto x : with_mid) top.push_back({x[0], x[1], 1});
  b.facet(with_mid);
  b.facet(top);
  for (std::size_t i = 0; i < with_mid.size(); ++i) {
    const std::size_t j = (i + 1) % with_mid.size();
    b.facet({with_mid[i], with_mid[j], top[j], top[i]});
  }
  BOOST_TEST(check(b.p).empty());
  BOOST_TEST(check(rotated(b.p)).empty());
  BOOST_TEST(check(as_triangles(b.p)).empty());
  // a vertical facet through the star's arms, standing on the bottom's corners 0 and 12
  b.facet({bottom[0], bottom[12], {bottom[12][0], bottom[12][1], 0.5}, {bottom[0][0], bottom[0][1], 0.5}});
  const auto r = check(b.p);
  BOOST_TEST(!r.empty());
  for (const auto& x : r) BOOST_TEST(x.b == b.p.facets.size() - 1);
}

BOOST_AUTO_TEST_CASE(own_polygon_edges_cross) {
  builder3 b;
  b.facet({{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}});  // a bow tie
  const auto r = check(b.p);
  BOOST_TEST_REQUIRE(r.size() == 1u);
  BOOST_TEST(r[0].a == 0u);
  BOOST_TEST(r[0].b == 0u);
  BOOST_TEST(r[0].what.find("its polygon edges") == 0u);
  BOOST_TEST(pc::message(b.p, r[0]).find("cube.poly:10: facet 1 (line 10): its polygon edges") == 0u);
  // an embedded point on its own edge, and an inner polygon crossing the outer one
  builder3 c;
  c.facet({{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, {{1, 0, 0}}});
  expect_one(check(c.p), 0, 0, "vertex 5 lies on its polygon edge 1-2");
  builder3 d;
  d.facet({{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, {{1, 1, 0}, {3, 1, 0}, {3, 1.5, 0}}});
  BOOST_TEST(check(d.p).size() == 1u);
}

BOOST_AUTO_TEST_CASE(free_point_on_a_facet) {
  builder3 b;
  b.box({0, 0, 0}, {1, 1, 1});
  b.id({0.5, 0.3, 1});
  expect_one(check(b.p), 1, 1, "vertex 9, on no facet, lies inside it");
  b.p.points[8] = {0.5, 0, 1};
  const auto r = check(b.p);  // on the top and on the wall y = 0
  BOOST_TEST_REQUIRE(r.size() == 2u);
  BOOST_TEST(r[0].a == 1u);
  BOOST_TEST(r[0].what == "vertex 9, on no facet, lies on the edge 5-6 of it");
  BOOST_TEST(r[1].a == 2u);
  b.p.points[8] = {0.5, 0.3, 0.7};  // inside the cube: a volume point
  BOOST_TEST(check(b.p).empty());
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(segments)

plc<2> segments(const std::vector<point2>& pts, const std::vector<std::array<vertex_id, 2>>& edges) {
  plc<2> p;
  p.source = "box.poly";
  p.points = pts;
  p.edges = edges;
  return p;
}

BOOST_AUTO_TEST_CASE(crossing) {
  const auto p = segments({{0, 0}, {2, 2}, {0, 2}, {2, 0}}, {{0, 1}, {2, 3}});
  const auto r = pc::self_intersections(p);
  expect_one(r, 0, 1, "they cross");
  BOOST_TEST(pc::message(p, r[0]) == "box.poly: segment 2 (vertices 3-4) intersects segment 1 (vertices 1-2): they cross");
  BOOST_CHECK_THROW(pc::require_no_self_intersections(p), pc::input_error);
}

BOOST_AUTO_TEST_CASE(vertex_on_a_segment) {
  expect_one(pc::self_intersections(segments({{0, 0}, {2, 0}, {1, 0}, {1, 1}}, {{0, 1}, {2, 3}})), 0, 1,
             "vertex 3 lies on segment 1");
  expect_one(pc::self_intersections(segments({{1, 0}, {1, 1}, {0, 0}, {2, 0}}, {{0, 1}, {2, 3}})), 0, 1,
             "vertex 1 lies on segment 2");
  // a point on no segment
  expect_one(pc::self_intersections(segments({{0, 0}, {2, 0}, {1, 0}}, {{0, 1}})), 0, 0,
             "vertex 3, on no segment, lies on it");
}

BOOST_AUTO_TEST_CASE(collinear_overlap) {
  expect_one(pc::self_intersections(segments({{0, 0}, {2, 0}, {1, 0}, {3, 0}}, {{0, 1}, {2, 3}})), 0, 1,
             "they overlap (collinear)");
  expect_one(pc::self_intersections(segments({{0, 0}, {2, 0}, {1, 0}}, {{0, 1}, {0, 2}})), 0, 1,
             "they overlap (collinear)");
  expect_one(pc::self_intersections(segments({{0, 0}, {2, 0}}, {{0, 1}, {1, 0}})), 0, 1, "they join the same vertices");
}

BOOST_AUTO_TEST_CASE(legal_touching) {
  // a square with a diagonal, a segment continuing an edge, one touching a corner from outside
  const auto p = segments({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {2, 0}, {2, 2}},
                          {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}, {1, 4}, {2, 5}});
  BOOST_TEST(pc::self_intersections(p).empty());
  // close but apart
  BOOST_TEST(pc::self_intersections(segments({{0, 0}, {1, 0}, {0.5, 1e-300}, {0.5, 1}}, {{0, 1}, {2, 3}})).empty());
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(structures)

BOOST_AUTO_TEST_CASE(examples_are_clean) {
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(GSSE_SOURCE_DIR) / "examples"))
    if (e.path().extension() == ".poly") {
      const auto any = io::read_plc(e.path().string());
      std::visit([&](const auto& p) { BOOST_TEST(pc::self_intersections(p).empty(), e.path()); }, any);
    }
}

BOOST_AUTO_TEST_CASE(benchmark_structures_are_clean) {
  const auto shared = test::shared_dir();
  if (!shared) {
    std::cout << "SKIPPED: ../shared absent (benchmark structures)" << std::endl;  // ctest: skipped
    return;
  }
  const auto dir = std::filesystem::temp_directory_path() / "gsse_plc_structures";
  for (const std::string name : {"mosfet", "diffusion", "trench", "finfet"})
    for (const std::string opt : {"--rotate", "--rotate --triangles", "--triangles", "--dim 2", "--dim 2 --rotate"}) {
      std::filesystem::remove_all(dir);
      std::filesystem::create_directories(dir);
      const std::string cmd = "python3 " + (*shared / "bench" / "structures.py").string() + " " + name + " " + opt +
                              " --out " + dir.string() + " > /dev/null";
      BOOST_TEST_REQUIRE(std::system(cmd.c_str()) == 0, cmd);
      const auto any = io::read_plc((dir / (name + ".poly")).string());
      std::visit([&](const auto& p) { BOOST_TEST(pc::self_intersections(p).empty(), name << " " << opt); }, any);
    }
  std::filesystem::remove_all(dir);
}

BOOST_AUTO_TEST_SUITE_END()
