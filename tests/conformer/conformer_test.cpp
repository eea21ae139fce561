#define BOOST_TEST_MODULE conformer
#include <boost/test/unit_test.hpp>

#include <iostream>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <set>

#include "gsse/conformer/conformer.hpp"
#include "gsse/geometry/circumcentre.hpp"
#include "gsse/geometry/predicates.hpp"
#include "gsse/conformer/regions.hpp"
#include "gsse/io/poly.hpp"
#include "gsse/pipeline/pipeline.hpp"
#include "conformer/encroachment_oracle.hpp"
#include "support/shared.hpp"

using namespace gsse;
namespace cf = gsse::conformer;

namespace {

/// Conforms, then requires the exact post-check to pass and labelling to succeed. Returns the
/// number of Steiner points (reported in the log for docs/benchmarks.md).
template <std::size_t D>
std::size_t conform_and_check(const plc<D>& p, const std::vector<point<D>>& volume, double size,
                              const std::string& what) {
  cf::options o;
  o.size = size;
  const auto b = cf::conform(p, volume, o);
  const auto bad = cf::encroached(b);
  BOOST_TEST(bad.empty(), what << ": " << bad.size() << " encroached elements");
  // the independent oracle (CGAL directly, brute force; tests/conformer/encroachment_oracle.hpp)
  const auto oracle = test::encroachment_oracle(b);
  BOOST_TEST(oracle.strictly_encroached.empty(), what << ": oracle finds " << oracle.strictly_encroached.size() << " encroached elements");
  BOOST_TEST(oracle.not_delaunay == 0u, what << ": " << oracle.not_delaunay << " subfacets are not faces of CGAL's Delaunay triangulation");
  BOOST_TEST(oracle.encroached_subsegments == 0u,
             what << ": " << oracle.encroached_subsegments << " of " << oracle.subsegments << " subsegments encroached");
  BOOST_TEST_MESSAGE("oracle " << what << ": " << oracle.ties << " ties, " << oracle.subsegments << " subsegments");
  BOOST_CHECK_NO_THROW(cf::label(b, p));
  BOOST_TEST_MESSAGE("steiner " << what << " size=" << size << " volume=" << volume.size() << ": " << b.steiner
                                << " Steiner points, " << b.faces.size() << " faces, " << b.rounds << " rounds");
  return b.steiner;
}

plc<2> wedge_2d(double degrees) {
  const double a = degrees * std::numbers::pi / 180;
  plc<2> p;
  p.source = "wedge";
  p.points = {{0, 0}, {1, 0}, {std::cos(a), std::sin(a)}};
  p.edges = {{0, 1}, {1, 2}, {2, 0}};
  p.edge_markers = {0, 0, 0};
  p.regions.push_back({{0.6, 0.3 * std::sin(a)}, 1, -1, "wedge"});
  return p;
}

plc<3> prism(const std::vector<point2>& section, double height, const std::string& name) {
  plc<3> p;
  p.source = name;
  const auto n = static_cast<vertex_id>(section.size());
  for (const auto& q : section) p.points.push_back({q[0], q[1], 0});
  for (const auto& q : section) p.points.push_back({q[0], q[1], height});
  plc_facet bottom, top;
  bottom.polygons = {{}};
  top.polygons = {{}};
  for (vertex_id i = 0; i < n; ++i) {
    bottom.polygons[0].push_back(i);
    top.polygons[0].push_back(n + i);
    p.facets.push_back({{{i, (i + 1) % n, n + (i + 1) % n, n + i}}, {}, 0, 0});
  }
  p.facets.push_back(bottom);
  p.facets.push_back(top);
  point3 c{0, 0, height / 2};
  for (const auto& q : section) c[0] += q[0] / static_cast<double>(n), c[1] += q[1] / static_cast<double>(n);
  p.regions.push_back({c, 1, -1, name});
  return p;
}

/// Two stacked boxes [0,1]^2 x [-1,0] and [0,1]^2 x [0,t], sharing the face z = 0.
plc<3> stacked(double t) {
  plc<3> p;
  p.source = "stacked";
  for (double z : {-1.0, 0.0, t})
    for (int k = 0; k < 4; ++k) p.points.push_back({double(k == 1 || k == 2), double(k >= 2), z});
  auto quad = [&](vertex_id a, vertex_id b, vertex_id c, vertex_id d) { p.facets.push_back({{{a, b, c, d}}, {}, 0, 0}); };
  for (vertex_id layer = 0; layer < 3; ++layer) quad(4 * layer, 4 * layer + 1, 4 * layer + 2, 4 * layer + 3);
  for (vertex_id layer = 0; layer < 2; ++layer)
    for (vertex_id k = 0; k < 4; ++k) {
      const vertex_id a = 4 * layer + k, b = 4 * layer + (k + 1) % 4;
      quad(a, b, b + 4, a + 4);
    }
  p.regions.push_back({{0.5, 0.5, -0.5}, 1, -1, "silicon"});
  p.regions.push_back({{0.5, 0.5, t / 2}, 2, -1, "oxide"});
  return p;
}

}  // namespace

BOOST_AUTO_TEST_CASE(bundled_examples) {
  for (const char* name : {"mosfet2d", "mosfet", "stack"}) {
    const auto path = std::string(GSSE_SOURCE_DIR) + "/examples/" + name + ".poly";
    std::visit([&](const auto& p) { conform_and_check(p, {}, 0.0, name); conform_and_check(p, {}, 0.1, name); },
               io::read_plc(path));
  }
}

BOOST_AUTO_TEST_CASE(bench_structures_with_and_without_cloud) {
  const auto shared = test::shared_dir();
  if (!shared) {
    std::cout << "SKIPPED: ../shared absent (benchmark structures)" << std::endl;  // ctest: skipped
    return;
  }
  for (const char* s : {"mosfet", "diffusion", "trench", "finfet"})
    for (int dim : {2, 3}) {
      const auto path = test::bench_structure(*shared, s, dim, dim == 3 ? 2000 : 500);
      const auto base = path.substr(0, path.size() - 5);
      std::visit(
          [&](const auto& p) {
            constexpr std::size_t D = std::remove_cvref_t<decltype(p)>::dimension;
            conform_and_check(p, {}, 0.0, std::string(s) + std::to_string(D) + "d");
            // the cloud, inside the silicon, as volume points
            const auto cloud = io::read_node<D>(base + ".cloud.node");
            conform_and_check(p, cloud, 0.0, std::string(s) + std::to_string(D) + "d+cloud");
          },
          io::read_plc(path));
    }
}

BOOST_AUTO_TEST_CASE(small_angles_2d) {
  for (double deg : {1.0, 5.0, 30.0}) {
    const auto p = wedge_2d(deg);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<point2> inside;
    const double a = deg * std::numbers::pi / 180;
    for (int i = 0; i < 200; ++i) {
      const double r = u(rng) * 0.95, t = u(rng) * a;
      inside.push_back({r * std::cos(t), r * std::sin(t)});
    }
    conform_and_check(p, {}, 0.0, "wedge " + std::to_string(deg));
    conform_and_check(p, inside, 0.0, "wedge+points " + std::to_string(deg));
    conform_and_check(p, {}, 0.05, "wedge sized " + std::to_string(deg));
  }
}

BOOST_AUTO_TEST_CASE(dihedral_5_degrees_3d) {
  const double a = 5 * std::numbers::pi / 180;
  const auto p = prism({{0, 0}, {1, 0}, {std::cos(a), std::sin(a)}}, 0.5, "wedge5");
  conform_and_check(p, {}, 0.0, "dihedral 5");
  // Known limitation: with a target size (facet lattices on both slanted facets) the triangulation
  // of a slanted facet fails with an error; see docs/benchmarks.md. Exercised without sizing.
  std::vector<point3> inside;
  for (int i = 1; i < 6; ++i) inside.push_back({0.15 * i, 0.15 * i * std::tan(a) * 0.5, 0.1 * i});
  conform_and_check(p, inside, 0.0, "dihedral 5 + points");
}

BOOST_AUTO_TEST_CASE(thin_layer) {
  const auto p = stacked(1e-3);  // 1e-3 of the domain size
  conform_and_check(p, {}, 0.0, "thin layer");
  conform_and_check(p, {}, 0.25, "thin layer sized");
}

BOOST_AUTO_TEST_CASE(cloud_points_near_a_facet) {
  const auto p = stacked(0.5);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  std::vector<point3> near;
  for (int i = 0; i < 100; ++i) near.push_back({u(rng), u(rng), -1e-6});       // 1e-6 below the interface
  for (int i = 0; i < 100; ++i) near.push_back({u(rng), u(rng), 0.5 - 1e-7});  // just under the top
  for (int i = 0; i < 20; ++i) near.push_back({u(rng), u(rng), 0.0});          // exactly on the interface
  conform_and_check(p, near, 0.0, "cloud near facet");
}

/// Conforms p with and without options::delaunay_faces. With it, every subfacet must still be a
/// facet of CGAL's Delaunay triangulation of all the points (the independent oracle), the boundary
/// must label, and it must take no more Steiner points. Returns the two Steiner counts and the
/// number of subfacets (with it) whose equatorial ball holds a point: kept all the same.
template <std::size_t D>
std::array<std::size_t, 3> conform_delaunay_faces(const plc<D>& p, const std::vector<point<D>>& volume, const std::string& what) {
  const auto g = cf::conform(p, volume, cf::options{});
  cf::options o;
  o.delaunay_faces = true;
  const auto b = cf::conform(p, volume, o);
  const auto oracle = test::encroachment_oracle(b);
  BOOST_TEST(oracle.not_delaunay == 0u, what << ": " << oracle.not_delaunay << " subfacets are not faces of CGAL's Delaunay triangulation");
  BOOST_CHECK_NO_THROW(cf::label(b, p));
  BOOST_TEST(b.steiner <= g.steiner, what << ": " << b.steiner << " Steiner points against " << g.steiner);
  BOOST_TEST_MESSAGE("delaunay faces " << what << ": " << b.steiner << " Steiner points (Gabriel: " << g.steiner << "), "
                                       << oracle.strictly_encroached.size() << " subfacets encroached and kept");
  return {g.steiner, b.steiner, oracle.strictly_encroached.size()};
}

BOOST_AUTO_TEST_CASE(delaunay_faces_keep_encroached_subfacets_that_are_delaunay) {
  // Points inside the upper box of two, 0.1 and more from its walls: they lie in the equatorial
  // balls of the top's and the interface's subfacets, all on one side, and the spheres through
  // those subfacets that bulge to the other side are empty. options::delaunay_faces keeps such
  // subfacets; an empty equatorial ball (Gabriel) needs many more points
  const auto p = stacked(0.5);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.1, 0.9), z(0.1, 0.4);
  std::vector<point3> inside;
  for (int i = 0; i < 200; ++i) inside.push_back({u(rng), u(rng), z(rng)});
  const auto [gabriel, delaunay, kept] = conform_delaunay_faces(p, inside, "stacked + points");
  BOOST_TEST(delaunay < gabriel);
  BOOST_TEST(kept > 0u, "some subfacet is encroached and kept");
  // encroached() is the Gabriel post-check still: it reports the kept subfacets
  cf::options o;
  o.delaunay_faces = true;
  const auto b = cf::conform(p, inside, o);
  BOOST_TEST(!cf::encroached(b).empty());
  // each kept face's apex (boundary::face_apex) and face_encroached: on the line through the
  // face's circumcentre, across from the apex, a point just inside the sphere through the face and
  // the apex (beyond the equatorial ball) breaks it, one just outside does not
  BOOST_TEST_REQUIRE(b.face_apex.size() == b.faces.size());
  std::size_t apexes = 0, beyond_ball = 0;
  for (std::size_t f = 0; f < b.faces.size(); ++f) {
    if (b.face_apex[f] == no_vertex) continue;
    ++apexes;
    const auto& F = b.faces[f];
    const point3 &a = b.points[F[0]], &c = b.points[F[1]], &d = b.points[F[2]], &x = b.points[b.face_apex[f]];
    const point3 u = c - a, v = d - a, n = cross(u, v);
    const point3 o0 = a + geometry::triangle_circumcentre_offset(u, v, n, dot(n, n));
    double det = 0;
    const point3 s0 = a + geometry::tetrahedron_circumcentre_offset(u, v, x - a, det);
    const double R = distance(s0, a), r = distance(o0, a);
    point3 away = (1 / std::sqrt(dot(n, n))) * n;
    if (dot(away, x - a) > 0) away = -1.0 * away;
    const double reach = dot(s0 - o0, away) + std::sqrt(R * R - dot(s0 - o0, s0 - o0) + dot(s0 - o0, away) * dot(s0 - o0, away));
    if (reach < 1.01 * r) continue;  // the sphere hardly reaches past the ball there
    ++beyond_ball;
    const point3 in = o0 + (0.999 * reach) * away, out = o0 + (1.001 * reach) * away;
    BOOST_TEST(geometry::in_equatorial(a, c, d, in) < 0);
    BOOST_TEST(cf::face_encroached(b, f, in), "face " << f << ": a point in the sphere across from its apex");
    BOOST_TEST(!cf::face_encroached(b, f, out), "face " << f << ": a point past the sphere");
  }
  BOOST_TEST(apexes >= kept, apexes << " faces with an apex");
  BOOST_TEST(beyond_ball > 0u);
  // the rest: no more points, every subfacet Delaunay
  for (const char* name : {"mosfet", "stack"})
    std::visit(
        [&](const auto& q) {
          if constexpr (std::remove_cvref_t<decltype(q)>::dimension == 3) conform_delaunay_faces(q, {}, name);
        },
        io::read_plc(std::string(GSSE_SOURCE_DIR) + "/examples/" + name + ".poly"));
  const double a = 5 * std::numbers::pi / 180;
  conform_delaunay_faces(prism({{0, 0}, {1, 0}, {std::cos(a), std::sin(a)}}, 0.5, "wedge5"), {}, "dihedral 5");
  conform_delaunay_faces(stacked(1e-3), {}, "thin layer");
}

BOOST_AUTO_TEST_CASE(post_check_reports_encroachment) {
  // a boundary that was never conformed: the square's side is encroached by a point near it
  cf::boundary<2> b;
  b.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.1}};
  b.faces = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  const auto bad = cf::encroached(b);
  BOOST_TEST_REQUIRE(bad.size() == 1u);
  BOOST_TEST(bad[0].first == 0u);
  BOOST_TEST(bad[0].second == 4u);
  // a point exactly on the diametral circle is a tie; the square's other corners do not make
  // the edge non-Delaunay, so it is not encroached
  b.points[4] = {0.5, 0.5};
  BOOST_TEST(cf::encroached(b).empty());
}

BOOST_AUTO_TEST_CASE(steiner_cap_is_a_clear_error) {
  const auto p = wedge_2d(1.0);
  cf::options o;
  o.size = 0.001;
  o.max_steiner = 50;
  BOOST_CHECK_EXCEPTION(cf::conform(p, {}, o), cf::conform_error,
                        [](const auto& e) { return std::string(e.what()).find("more than 50 boundary points") != std::string::npos; });
}

BOOST_AUTO_TEST_CASE(invalid_plcs_are_rejected) {
  auto open = stacked(0.5);
  open.facets.pop_back();  // one side wall missing: not closed
  cf::options o;
  const auto b = cf::conform(open, {}, o);
  BOOST_CHECK_EXCEPTION(cf::label(b, open), cf::conform_error,
                        [](const auto& e) { return std::string(e.what()).find("not closed") != std::string::npos; });
  auto outside = stacked(0.5);
  outside.regions[1].at = {5, 5, 5};
  const auto b2 = cf::conform(outside, {}, o);
  BOOST_CHECK_EXCEPTION(cf::label(b2, outside), cf::conform_error,
                        [](const auto& e) { return std::string(e.what()).find("outside the domain") != std::string::npos; });
  auto nonplanar = stacked(0.5);
  nonplanar.points[8][2] = 0.6;  // one corner of the top facet lifted
  BOOST_CHECK_EXCEPTION(cf::conform(nonplanar, {}, o), cf::conform_error,
                        [](const auto& e) { return std::string(e.what()).find("not in the facet's plane") != std::string::npos; });
}

BOOST_AUTO_TEST_CASE(post_check_agrees_with_the_oracle) {
  // a conformed boundary spoiled by random points: the library's post-check and the independent
  // oracle must name the same encroached faces (random points: no ties, almost surely)
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.05, 1.05);
  {
    auto b = cf::conform(stacked(0.5), {}, {});
    const std::size_t n = b.points.size();
    for (int i = 0; i < 40; ++i) b.points.push_back({u(rng), u(rng), u(rng) * 1.5 - 1});
    b.homes.resize(b.points.size());
    std::set<std::size_t> mine;
    for (const auto& [f, v] : cf::encroached(b)) {
      BOOST_TEST(v >= n);  // only the new points encroach
      mine.insert(f);
    }
    const auto o = test::encroachment_oracle(b);
    BOOST_TEST(!mine.empty());
    BOOST_TEST(mine == o.strictly_encroached, "3D: post-check " << mine.size() << " faces, oracle " << o.strictly_encroached.size());
  }
  {
    auto b = cf::conform(wedge_2d(30), {}, {});
    for (int i = 0; i < 40; ++i) b.points.push_back({u(rng), u(rng) * 0.6});
    b.homes.resize(b.points.size());
    std::set<std::size_t> mine;
    for (const auto& [f, v] : cf::encroached(b)) mine.insert(f);
    const auto o = test::encroachment_oracle(b);
    BOOST_TEST(!mine.empty());
    BOOST_TEST(mine == o.strictly_encroached, "2D: post-check " << mine.size() << " faces, oracle " << o.strictly_encroached.size());
  }
}

BOOST_AUTO_TEST_CASE(small_angles_at_both_ends_of_an_edge) {
  // a 31 x 0.1 strip cut by its diagonal: the diagonal meets the bottom side at 0.18 degrees at
  // one end and the top side at the other. With concentric shells about each small-angle vertex
  // every edge there is split at the same dyadic distances, so the sides need O(log(31 / 0.1))
  // points each; splits that do not match (midpoints of edges of different lengths) cascaded
  // along the whole strip: 2,198 Steiner points before the dyadic shells, 51 with them. The
  // bound is the theory's order with a generous constant: 4 points per halving per edge.
  plc<2> p;
  p.source = "strip";
  p.points = {{0, 0}, {31, 0}, {31, 0.1}, {0, 0.1}};
  p.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}};
  p.edge_markers = {0, 0, 0, 0, 0};
  p.regions.push_back({{20, 0.02}, 1, -1, "below"});
  p.regions.push_back({{10, 0.08}, 2, -1, "above"});
  const std::size_t steiner = conform_and_check(p, {}, 0.0, "strip with a diagonal");
  BOOST_TEST(steiner <= static_cast<std::size_t>(4 * 5 * std::log2(31 / 0.1)), steiner << " Steiner points");
}

BOOST_AUTO_TEST_CASE(small_angle_margin_in_3d) {
  // In 3D an angle below 62 degrees is small (docs/design-decisions.md, "A margin over 60 degrees
  // for small angles in 3D"): a prism over a kite with a 61-degree corner (every other angle at
  // least 90) gives that corner's two vertices protecting balls, one with a 63-degree corner
  // none. With the bound at 60 a CAD "60 degrees" rounded to 60.13 got no ball, and refinement
  // split the edges there down to 1e-9 of the vertex (scad_example001).
  auto kite = [](double corner_degrees) {
    const double a = corner_degrees * std::numbers::pi / 180;
    // the kite's far corner on the bisector, where the angle is 90 degrees
    const double t = std::sin(std::numbers::pi * 3 / 4 - a / 2) / std::sin(std::numbers::pi / 4);
    return std::vector<point2>{{0, 0}, {1, 0}, {t * std::cos(a / 2), t * std::sin(a / 2)}, {std::cos(a), std::sin(a)}};
  };
  for (const double deg : {61.0, 63.0}) {
    const auto p = prism(kite(deg), 0.7, "kite " + std::to_string(deg));
    const auto b = cf::conform(p, {}, cf::options{});
    BOOST_TEST_REQUIRE(b.protect.size() == p.points.size());
    for (vertex_id v = 0; v < p.points.size(); ++v) {
      const bool corner = v == 0 || v == 4;  // the small corner, bottom and top
      BOOST_TEST((b.protect[v] > 0) == (corner && deg < 62), "kite " << deg << " degrees, vertex " << v << ": ball "
                                                                        << b.protect[v]);
    }
    conform_and_check(p, {}, 0.0, "kite " + std::to_string(deg));
  }
}

namespace {
/// The unit sphere as an icosahedron subdivided `levels` times, its points pushed onto the sphere:
/// a closed surface of triangle facets, as a CAD tessellation or an STL gives one.
plc<3> icosphere(int levels) {
  plc<3> p;
  p.source = "icosphere";
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<point3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<vertex_id, 3>> tri = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                               {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                               {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<vertex_id, vertex_id>, vertex_id> mid;
    auto m = [&](vertex_id a, vertex_id b) {
      const auto key = std::minmax(a, b);
      if (auto it = mid.find(key); it != mid.end()) return it->second;
      v.push_back(0.5 * (v[a] + v[b]));
      return mid[key] = static_cast<vertex_id>(v.size() - 1);
    };
    std::vector<std::array<vertex_id, 3>> next;
    for (const auto& [a, b, c] : tri) {
      const vertex_id ab = m(a, b), bc = m(b, c), ca = m(c, a);
      next.insert(next.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    tri = std::move(next);
  }
  for (auto& q : v) q = (1 / std::sqrt(dot(q, q))) * q;
  p.points = v;
  for (const auto& [a, b, c] : tri) p.facets.push_back({{{a, b, c}}, {}, 1, 0});
  p.regions.push_back({{0, 0, 0}, 1, -1, "ball"});
  return p;
}
}  // namespace

BOOST_AUTO_TEST_CASE(vertices_inside_a_smooth_surface_get_no_protecting_ball) {
  // Every vertex of a triangulated sphere has a facet corner below 62 degrees, and facets of 9
  // degrees' fold about it: a small angle of the surface, not of the solid (docs/design-decisions.md,
  // "A vertex inside a smooth surface gets no protecting ball"). Its edges were split where they
  // left protecting balls, 4,017 Steiner points for 642 vertices. With
  // shells alone (a ball's radius still kept in `protect` for the refinement's guard) the surface
  // is conformed as it is: its triangles are Gabriel already.
  const auto p = icosphere(3);
  BOOST_TEST_REQUIRE(p.points.size() == 642u);
  const auto b = cf::conform(p, {}, cf::options{});
  std::size_t guarded = 0;
  for (vertex_id v = 0; v < p.points.size(); ++v) guarded += b.protect.at(v) > 0;
  BOOST_TEST(guarded > 0u, "the small corners keep a guard radius for the refinement");
  const std::size_t steiner = conform_and_check(p, {}, 0.0, "icosphere");
  BOOST_TEST(steiner == 0u, steiner << " Steiner points");
  // folds of 42 degrees are no smooth surface: the icosahedron itself (corners of 60 degrees)
  // keeps its balls, and each of its 30 edges is split where it leaves the balls of both ends
  const std::size_t sharp = conform_and_check(icosphere(0), {}, 0.0, "icosahedron");
  BOOST_TEST(sharp >= 60u, sharp << " Steiner points");
}

BOOST_AUTO_TEST_CASE(obtuse_corner_of_a_smooth_surface_splits_nothing) {
  // A triangle facet of a smooth surface with an obtuse corner: that corner lies in the diametral
  // ball of the opposite edge, but the facet is convex there and both triangles through the edge
  // have empty balls, so the edge is a Delaunay edge and nothing needs a split
  // (docs/design-decisions.md, "Subsegments of a smooth surface are not split for their own
  // facets' corners"). Splitting it, as every encroached subsegment was, started shells about its
  // ends: 49 Steiner points here, 45,145 on a Gmsh torus whose 38,974 triangles have 74 such
  // corners (bench/surface_torus.sh), 1,159 now.
  auto p = icosphere(3);
  const auto& T = p.facets[0].polygons[0];
  const vertex_id a = T[0], b = T[1], c = T[2];
  const point3 mid = 0.5 * (p.points[a] + p.points[b]);
  point3 q = p.points[c] + 0.5 * (mid - p.points[c]);
  p.points[c] = (1 / std::sqrt(dot(q, q))) * q;
  const point3 u = p.points[a] - p.points[c], v = p.points[b] - p.points[c];
  BOOST_TEST_REQUIRE(dot(u, v) < 0, "the corner at c is obtuse");
  const auto bo = cf::conform(p, {}, cf::options{});
  BOOST_TEST(bo.steiner == 0u, bo.steiner << " Steiner points");
  BOOST_TEST(cf::encroached(bo).empty());
  const auto oracle = test::encroachment_oracle(bo);
  BOOST_TEST(oracle.strictly_encroached.empty());
  BOOST_TEST(oracle.not_delaunay == 0u, oracle.not_delaunay << " subfacets are not faces of CGAL's Delaunay triangulation");
  // the case is the one above: the edge (a, b) is encroached, by c, and left as it is
  BOOST_TEST(oracle.encroached_subsegments >= 1u);
  BOOST_CHECK_NO_THROW(cf::label(bo, p));
}
