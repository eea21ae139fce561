#define BOOST_TEST_MODULE predicates
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdint>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "gsse/geometry/predicates.hpp"

using namespace gsse;
using namespace gsse::geometry;

namespace {

using tet = std::array<int, 4>;
using tri = std::array<int, 3>;

/// All tetrahedra of `p` that pass the perturbed empty-sphere test against every other point.
std::vector<tet> perturbed_delaunay(const std::vector<point3>& p) {
  const int n = static_cast<int>(p.size());
  std::vector<tet> r;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c)
        for (int d = c + 1; d < n; ++d) {
          tet t{a, b, c, d};
          const int o = orient3d(p[a], p[b], p[c], p[d]);
          if (o == 0) continue;
          if (o < 0) std::swap(t[0], t[1]);
          bool empty = true;
          for (int e = 0; e < n && empty; ++e) {
            if (e == a || e == b || e == c || e == d) continue;
            const int s = in_sphere_perturbed(p[t[0]], p[t[1]], p[t[2]], p[t[3]], p[e]);
            BOOST_REQUIRE(s != 0);
            empty = s < 0;
          }
          if (empty) r.push_back(t);
        }
  return r;
}

/// Checks that `tets` is one valid tetrahedralization of conv(p) using every point: positively
/// oriented, every interior face shared by exactly two tets lying on opposite sides, every face
/// used once lying on the hull. (A pseudo-manifold of degree one whose boundary lies on the hull
/// boundary is a triangulation of the hull.)
void check_tetrahedralization(const std::vector<point3>& p, const std::vector<tet>& tets) {
  BOOST_TEST_REQUIRE(!tets.empty());
  std::map<tri, std::vector<std::pair<int, int>>> faces;  // sorted face -> (tet, apex)
  std::set<int> used;
  for (int k = 0; k < static_cast<int>(tets.size()); ++k) {
    const auto& t = tets[static_cast<std::size_t>(k)];
    BOOST_TEST(orient3d(p[t[0]], p[t[1]], p[t[2]], p[t[3]]) == 1);
    for (int i = 0; i < 4; ++i) {
      used.insert(t[i]);
      tri f;
      int m = 0;
      for (int j = 0; j < 4; ++j)
        if (j != i) f[m++] = t[j];
      std::sort(f.begin(), f.end());
      faces[f].push_back({k, t[i]});
    }
  }
  BOOST_TEST(used.size() == p.size());
  for (const auto& [f, users] : faces) {
    BOOST_TEST_REQUIRE(users.size() <= 2u);
    if (users.size() == 2) {
      const int s0 = orient3d(p[f[0]], p[f[1]], p[f[2]], p[users[0].second]);
      const int s1 = orient3d(p[f[0]], p[f[1]], p[f[2]], p[users[1].second]);
      BOOST_TEST(s0 * s1 == -1);
    } else {
      int pos = 0, neg = 0;
      for (const auto& q : p) {
        const int s = orient3d(p[f[0]], p[f[1]], p[f[2]], q);
        pos += s > 0;
        neg += s < 0;
      }
      BOOST_TEST((pos == 0 || neg == 0));  // a face used once lies on the hull
    }
  }
}

bool coplanar(const std::vector<point3>& p) {
  for (std::size_t a = 0; a < p.size(); ++a)
    for (std::size_t b = a + 1; b < p.size(); ++b)
      for (std::size_t c = b + 1; c < p.size(); ++c) {
        if (collinear(p[a], p[b], p[c])) continue;
        for (const auto& q : p)
          if (orient3d(p[a], p[b], p[c], q) != 0) return false;
        return true;
      }
  return true;
}

}  // namespace

BOOST_AUTO_TEST_CASE(exact_signs) {
  const point3 o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  BOOST_TEST(orient3d(o, x, y, z) == 1);
  BOOST_TEST(orient3d(o, y, x, z) == -1);
  BOOST_TEST(orient3d(o, x, y, point3{0.3, 0.3, 0}) == 0);
  BOOST_TEST(orient2d(point2{0, 0}, point2{1, 0}, point2{0, 1}) == 1);
  BOOST_TEST(in_sphere(o, x, y, z, point3{0.1, 0.1, 0.1}) == 1);
  BOOST_TEST(in_sphere(o, x, y, z, point3{2, 2, 2}) == -1);
  BOOST_TEST(in_sphere(o, x, y, z, point3{1, 1, 1}) == 0);  // cube corner: cospherical
  BOOST_TEST(in_diametral(o, x, point3{0.5, 0.4, 0}) == 1);
  BOOST_TEST(in_diametral(o, x, point3{0.5, 0.5, 0}) == 0);
  BOOST_TEST(in_equatorial(o, x, y, point3{0.5, 0.5, 0.70}) == 1);
  BOOST_TEST(in_equatorial(o, x, y, point3{0.5, 0, 0.5}) == 0);
  BOOST_TEST(in_equatorial(o, x, y, point3{0.5, 0.5, 0.71}) == -1);
  // nearly degenerate input (24 + 24e-17 rounds to 24, so this one is exactly collinear as
  // stored; orient2d_where_doubles_fail below has cases that plain doubles do get wrong)
  const double e = 1e-17;
  BOOST_TEST(orient2d(point2{0.5, 0.5}, point2{12, 12}, point2{24, 24 + 24 * e}) == 0);
  BOOST_TEST(orient2d(point2{0.5, 0.5}, point2{12, 12}, point2{24, std::nextafter(24.0, 25.0)}) == 1);
}

// Kettner et al., "Classroom examples of robustness problems in geometric computations": points
// p = (0.5 + i u, 0.5 + j u), u = 2^-53, against the line through (12, 12) and (24, 24). Scaled by
// 2^53 every coordinate is an integer below 2^58, so the sign is computed exactly in 128-bit
// integers here (an oracle sharing nothing with CGAL). The naive double formula gets hundreds of
// the 256 x 256 signs wrong; the predicate gets none.
BOOST_AUTO_TEST_CASE(orient2d_where_doubles_fail) {
  const double u = std::ldexp(1.0, -53);
  const point2 q{12, 12}, r{24, 24};
  auto scaled = [](double x) { return static_cast<__int128>(std::ldexp(x, 53)); };
  int naive_wrong = 0, wrong = 0;
  for (int i = 0; i < 256; ++i)
    for (int j = 0; j < 256; ++j) {
      const point2 p{0.5 + i * u, 0.5 + j * u};
      const __int128 det = (scaled(q[0]) - scaled(p[0])) * (scaled(r[1]) - scaled(p[1])) -
                           (scaled(q[1]) - scaled(p[1])) * (scaled(r[0]) - scaled(p[0]));
      const int exact = det > 0 ? 1 : det < 0 ? -1 : 0;
      // the orientation of (p, q, r) is that of (q - p) x (r - p)
      const double nd = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
      naive_wrong += (nd > 0 ? 1 : nd < 0 ? -1 : 0) != exact;
      wrong += orient2d(p, q, r) != exact;
    }
  BOOST_TEST_MESSAGE("naive doubles: " << naive_wrong << " wrong signs of 65536");
  BOOST_TEST(naive_wrong > 100);  // the case is hard: plain doubles fail on it
  BOOST_TEST(wrong == 0);
}

BOOST_AUTO_TEST_CASE(cube_corners) {
  std::vector<point3> p;
  for (int i = 0; i < 8; ++i) p.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  // every raw in-sphere test among the corners is a tie; the perturbed one never is
  int ties = 0;
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b)
      for (int c = 0; c < 8; ++c)
        for (int d = 0; d < 8; ++d) {
          if (orient3d(p[a], p[b], p[c], p[d]) != 1) continue;
          for (int e = 0; e < 8; ++e) {
            if (e == a || e == b || e == c || e == d) continue;
            ties += in_sphere(p[a], p[b], p[c], p[d], p[e]) == 0;
            BOOST_TEST(in_sphere_perturbed(p[a], p[b], p[c], p[d], p[e]) != 0);
          }
        }
  BOOST_TEST(ties > 0);
  const auto t = perturbed_delaunay(p);
  check_tetrahedralization(p, t);
  BOOST_TEST((t.size() == 5u || t.size() == 6u));
}

BOOST_AUTO_TEST_CASE(lattice_cospherical_sets) {
  // 5x5x5 lattice. Every group of >= 5 lattice points on a common sphere centred at a
  // half-integer point of the central region is checked: the tetrahedra passing the perturbed
  // empty-sphere test form exactly one tetrahedralization of the group's hull.
  std::vector<point3> lattice;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 5; ++k) lattice.push_back({double(i), double(j), double(k)});
  int groups = 0;
  std::size_t largest = 0;
  for (int ci = 2; ci <= 6; ++ci)
    for (int cj = 2; cj <= 6; ++cj)
      for (int ck = 2; ck <= 6; ++ck) {
        const point3 c{ci * 0.5, cj * 0.5, ck * 0.5};
        std::map<double, std::vector<point3>> shells;
        for (const auto& q : lattice) shells[squared_distance(q, c)].push_back(q);
        for (auto& [r2, pts] : shells) {
          if (r2 == 0 || pts.size() < 5 || pts.size() > 26 || coplanar(pts)) continue;
          ++groups;
          largest = std::max(largest, pts.size());
          BOOST_TEST_CONTEXT("centre " << c[0] << "," << c[1] << "," << c[2] << " r2 " << r2) {
            check_tetrahedralization(pts, perturbed_delaunay(pts));
          }
        }
      }
  BOOST_TEST(groups > 100);
  BOOST_TEST(largest >= 24u);
}

BOOST_AUTO_TEST_CASE(cocircular_points_2d) {
  // 4 cocircular points: exactly one of the two triangulations of the quad passes the test
  const std::vector<std::vector<point2>> quads = {
      {{0, 0}, {1, 0}, {1, 1}, {0, 1}},
      {{1, 0}, {0, 1}, {-1, 0}, {0, -1}},
      {{3, 4}, {-4, 3}, {-3, -4}, {5, 0}}};  // on the circle of radius 5
  for (const auto& q : quads) {
    BOOST_TEST(in_circle(q[0], q[1], q[2], q[3]) == 0);
    // triangles (0,1,2)+(0,2,3) use diagonal 02; (0,1,3)+(1,2,3) use diagonal 13
    auto empty = [&](int a, int b, int c, int d) {
      std::array<int, 3> t{a, b, c};
      if (orient2d(q[t[0]], q[t[1]], q[t[2]]) < 0) std::swap(t[0], t[1]);
      const int s = in_circle_perturbed(q[t[0]], q[t[1]], q[t[2]], q[d]);
      BOOST_TEST(s != 0);
      return s < 0;
    };
    const bool d02 = empty(0, 1, 2, 3) && empty(0, 2, 3, 1);
    const bool d13 = empty(0, 1, 3, 2) && empty(1, 2, 3, 0);
    BOOST_TEST(d02 != d13);
    // the perturbed decision is consistent: each triangle's verdict matches its diagonal's
    BOOST_TEST(empty(0, 1, 2, 3) == empty(0, 2, 3, 1));
    BOOST_TEST(empty(0, 1, 3, 2) == empty(1, 2, 3, 0));
  }
}

BOOST_AUTO_TEST_CASE(planar_perturbation_matches_2d) {
  // In-plane decisions on 3D points in z = 0 agree with the 2D perturbed predicate, for every
  // quadruple of a 4x4 lattice (full of cocircular ties).
  std::vector<point2> p2;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) p2.push_back({double(i), double(j)});
  int ties = 0;
  for (std::size_t a = 0; a < p2.size(); ++a)
    for (std::size_t b = 0; b < p2.size(); ++b)
      for (std::size_t c = 0; c < p2.size(); ++c) {
        if (orient2d(p2[a], p2[b], p2[c]) != 1) continue;
        for (std::size_t d = 0; d < p2.size(); ++d) {
          if (d == a || d == b || d == c) continue;
          auto l = [](const point2& q) { return point3{q[0], q[1], 0}; };
          ties += in_circle(p2[a], p2[b], p2[c], p2[d]) == 0;
          BOOST_TEST(in_circle_perturbed(p2[a], p2[b], p2[c], p2[d]) ==
                     in_coplanar_circle_perturbed(l(p2[a]), l(p2[b]), l(p2[c]), l(p2[d]), 2));
        }
      }
  BOOST_TEST(ties > 0);
}

// gsse/geometry/fixed_predicates.hpp decides orient3d, in_sphere and in_equatorial before CGAL is
// asked (its own double filter, then 64-bit-limb integers where the coordinate differences allow).
// Every sign it gives must be CGAL's: checked on lattices of several spacings and offsets (exact
// ties by the ten thousand), the same with one coordinate moved by an ulp (ties just broken),
// a cube's corners with a zero moved next to it (a near tie no integer width holds: CGAL's
// path), and generic points.
BOOST_AUTO_TEST_CASE(fixed_predicates_agree_with_cgal) {
  namespace fx = gsse::geometry::fixed;
  const kernel k;
  auto cg = [](const point3& p) { return kernel::Point_3(p[0], p[1], p[2]); };
  std::mt19937_64 g(20261127);
  std::uniform_real_distribution<double> spacing(1e-3, 1.0), offset(-3.0, 3.0), unit(0.0, 1.0);
  int decided[3] = {0, 0, 0}, ties[3] = {0, 0, 0}, wrong = 0, to_cgal = 0;
  for (int it = 0; it < 200000; ++it) {
    std::array<point3, 5> q;
    const int mode = it % 5;
    const double h = spacing(g), o = offset(g);
    std::uniform_int_distribution<int> cell(0, mode == 0 ? 1 : mode == 1 ? 3 : 40);
    for (auto& p : q)
      for (auto& x : p) x = mode == 4 ? 1 + unit(g) : o + cell(g) * h;
    if (mode == 2) q[4][it % 3] = std::nextafter(q[4][it % 3], 1e9);
    if (mode == 3) {  // a cube's corners, one at the origin, the query's zero coordinate moved
                      // next to it: a near tie no integer width holds (CGAL's path)
      for (std::size_t i = 0; i < 5; ++i)
        for (std::size_t a = 0; a < 3; ++a) q[i][a] = ((i + 1) >> a) & 1 ? h : 0.0;
      q[4][1] = 1e-20 * (1 + unit(g));  // the query (h, 0, h)
    }
    const int ori = static_cast<int>(k.orientation_3_object()(cg(q[0]), cg(q[1]), cg(q[2]), cg(q[3])));
    if (const int s = fx::orient3d(q[0], q[1], q[2], q[3]); s != fx::undecided) {
      ++decided[0], ties[0] += ori == 0, wrong += s != ori;
    }
    const int sph = static_cast<int>(
        k.side_of_oriented_sphere_3_object()(cg(q[0]), cg(q[1]), cg(q[2]), cg(q[3]), cg(q[4])));
    if (const int s = fx::in_sphere(q[0], q[1], q[2], q[3], q[4]); s != fx::undecided) {
      ++decided[1], ties[1] += sph == 0, wrong += s != sph;
    } else {
      ++to_cgal;
    }
    wrong += in_sphere(q[0], q[1], q[2], q[3], q[4]) != sph;
    wrong += orient3d(q[0], q[1], q[2], q[3]) != ori;
    if (k.collinear_3_object()(cg(q[0]), cg(q[1]), cg(q[2]))) continue;
    const int eq = static_cast<int>(k.side_of_bounded_sphere_3_object()(cg(q[0]), cg(q[1]), cg(q[2]), cg(q[4])));
    if (const int s = fx::in_equatorial(q[0], q[1], q[2], q[4]); s != fx::undecided) {
      ++decided[2], ties[2] += eq == 0, wrong += s != eq;
    }
    // the public predicates agree whichever path answers
    wrong += in_equatorial(q[0], q[1], q[2], q[4]) != eq;
  }
  BOOST_TEST(wrong == 0);
  BOOST_TEST(to_cgal > 200);  // and CGAL's path was taken too (the filter decides most of that fifth)
  for (int i = 0; i < 3; ++i) {
    BOOST_TEST(decided[i] > 120000);  // the fifth with a point next to zero may go to CGAL
    BOOST_TEST(ties[i] > 5000);      // exact zeros were exercised
  }
  // Mixed magnitudes (entries from 2^-560 to 2^500 in one call): the double filters must not be
  // fooled by a product that underflows and is then multiplied by a huge entry (a review found
  // 314, 2591 and 276 wrong signs in 20 s of this before filter_safe).
  const int exps[] = {-560, -540, -530, -400, -300, -200, 0, 200, 250, 300, 400, 500};
  std::uniform_int_distribution<int> pick(0, 11), small(-3, 3), zero(0, 2);
  int mixed_wrong = 0;
  for (int it = 0; it < 100000; ++it) {
    std::array<point3, 5> q;
    for (auto& p : q)
      for (auto& x : p) x = zero(g) == 0 ? 0.0 : std::ldexp(static_cast<double>(small(g)), exps[pick(g)]);
    const auto cq = [&](int i) { return cg(q[static_cast<std::size_t>(i)]); };
    mixed_wrong += orient3d(q[0], q[1], q[2], q[3]) != static_cast<int>(k.orientation_3_object()(cq(0), cq(1), cq(2), cq(3)));
    mixed_wrong += in_sphere(q[0], q[1], q[2], q[3], q[4]) !=
                   static_cast<int>(k.side_of_oriented_sphere_3_object()(cq(0), cq(1), cq(2), cq(3), cq(4)));
    if (k.collinear_3_object()(cq(0), cq(1), cq(2))) continue;
    mixed_wrong += in_equatorial(q[0], q[1], q[2], q[4]) !=
                   static_cast<int>(k.side_of_bounded_sphere_3_object()(cq(0), cq(1), cq(2), cq(4)));
  }
  BOOST_TEST(mixed_wrong == 0);
  // Wide rows, near ties: a cube of side 2^s units (s from 48 to 52) at an offset, its corners
  // cospherical and its faces coplanar, with the query corner moved by one unit (2^-60) along
  // an axis: the determinant is about 2^-s of the permanent, so the filters mostly cannot decide
  // and the integer path answers, with rows of up to 53 bits. (Rows of up to 61 bits need
  // coordinates the doubles cannot move by one unit at that width; a review checked them with
  // the filters switched off: 8.1 million configurations, no wrong sign.)
  std::uniform_int_distribution<int> side(48, 52), axis(0, 2), updown(0, 1);
  std::uniform_int_distribution<std::int64_t> off(0, std::int64_t{1} << 20);
  int wide_wrong = 0, wide_integer = 0;
  for (int it = 0; it < 20000; ++it) {
    const double u = 0x1p-60, H = std::ldexp(1.0, side(g)) * u;
    const point3 o{static_cast<double>(off(g)) * u, static_cast<double>(off(g)) * u, static_cast<double>(off(g)) * u};
    std::array<point3, 5> q = {o, o + point3{H, 0, 0}, o + point3{0, H, 0}, o + point3{0, 0, H}, o + point3{H, H, H}};
    q[4][static_cast<std::size_t>(axis(g))] += updown(g) ? u : -u;
    q[3][static_cast<std::size_t>(axis(g))] += updown(g) ? u : -u;  // and d off the face plane
    const auto cq = [&](int i) { return cg(q[static_cast<std::size_t>(i)]); };
    const int cs = static_cast<int>(k.side_of_oriented_sphere_3_object()(cq(0), cq(1), cq(2), cq(3), cq(4)));
    const int fs = fx::in_sphere(q[0], q[1], q[2], q[3], q[4]);
    wide_integer += fs != fx::undecided && cs != 0;
    wide_wrong += fs != fx::undecided && fs != cs;
    const point3 m{q[4][0], q[4][1], o[2]};  // near the plane z = o's and the equator of (0, 1, 2)
    const int ce = static_cast<int>(k.side_of_bounded_sphere_3_object()(cq(0), cq(1), cq(2), cg(m)));
    const int fe = fx::in_equatorial(q[0], q[1], q[2], m);
    wide_wrong += fe != fx::undecided && fe != ce;
    const int co = static_cast<int>(k.orientation_3_object()(cq(0), cq(1), cq(2), cg(m)));
    const int fo = fx::orient3d(q[0], q[1], q[2], m);
    wide_wrong += fo != fx::undecided && fo != co;
  }
  BOOST_TEST(wide_wrong == 0);
  BOOST_TEST(wide_integer > 10000);  // non-zero answers, not only ties
  // Near ties whose differences are not doubles: a box's corners (side h) whose low corner lies
  // between h/16 and h/4 from the origin on each axis (either side of it), so that the coordinates
  // of one call differ in magnitude by more than a factor 2 and their differences are rarely
  // exact doubles: the direct integer path cannot take them. Half the boxes sit on the third axis
  // instead 1000-2000 h from the origin: their integers then fit only once that axis is moved by a
  // multiple of s (integer_rows' t != 0). The corners are exact ties; one coordinate of the
  // query corner, or of the fourth corner, is moved 1-3 ulps, which no filter decides. The moved
  // integers (integer_rows' second path) must decide them all, with CGAL's signs: the in-sphere
  // of five corners, the orientation of a face's four, the equatorial ball of three of a face's
  // corners against the fourth.
  int moved_wrong = 0, moved_decided = 0, moved_nonzero = 0, far_decided = 0;
  std::uniform_int_distribution<int> side_sign(0, 1), ulps(1, 3), which_axis(0, 2);
  for (int it = 0; it < 20000; ++it) {
    const double h = spacing(g);
    const bool far = it % 2 == 1;
    point3 base;
    for (auto& x : base) x = (side_sign(g) ? 1.0 : -1.0) * h * (1.0 / 16 + unit(g) * 3 / 16);
    if (far) base[2] = (side_sign(g) ? 1.0 : -1.0) * h * (1000 + 1000 * unit(g));
    auto corner = [&](unsigned bits) {
      point3 p = base;
      for (std::size_t a = 0; a < 3; ++a)
        if ((bits >> a) & 1) p[a] = base[a] + h;
      return p;
    };
    auto nudge = [&](point3 p) {
      double& x = p[static_cast<std::size_t>(which_axis(g))];
      const double to = side_sign(g) ? 1e300 : -1e300;
      for (int n = ulps(g); n > 0; --n) x = std::nextafter(x, to);
      return p;
    };
    const std::array<point3, 5> q = {corner(1), corner(2), corner(3), corner(4), nudge(corner(5))};
    const auto cq = [&](int i) { return cg(q[static_cast<std::size_t>(i)]); };
    const int cs = static_cast<int>(k.side_of_oriented_sphere_3_object()(cq(0), cq(1), cq(2), cq(3), cq(4)));
    const int fs = fx::in_sphere(q[0], q[1], q[2], q[3], q[4]);
    moved_decided += fs != fx::undecided, far_decided += far && fs != fx::undecided, moved_nonzero += cs != 0;
    moved_wrong += (fs != fx::undecided && fs != cs) + (in_sphere(q[0], q[1], q[2], q[3], q[4]) != cs);
    const std::array<point3, 4> f = {corner(0), corner(1), corner(2), nudge(corner(3))};
    const auto cf = [&](int i) { return cg(f[static_cast<std::size_t>(i)]); };
    const int co = static_cast<int>(k.orientation_3_object()(cf(0), cf(1), cf(2), cf(3)));
    const int fo = fx::orient3d(f[0], f[1], f[2], f[3]);
    moved_decided += fo != fx::undecided, far_decided += far && fo != fx::undecided, moved_nonzero += co != 0;
    moved_wrong += fo != fx::undecided && fo != co;
    const int ce = static_cast<int>(k.side_of_bounded_sphere_3_object()(cf(0), cf(1), cf(2), cf(3)));
    const int fe = fx::in_equatorial(f[0], f[1], f[2], f[3]);
    moved_decided += fe != fx::undecided, far_decided += far && fe != fx::undecided, moved_nonzero += ce != 0;
    moved_wrong += fe != fx::undecided && fe != ce;
  }
  BOOST_TEST(moved_wrong == 0);
  BOOST_TEST(moved_decided > 59000);  // all but a few, whose low corner's last bit lies too far down
  BOOST_TEST(far_decided > 29500);    // the far boxes too: the moved axis
  BOOST_TEST(moved_nonzero > 40000);  // the nudges broke the ties (a nudge along a face leaves some)
  BOOST_TEST_MESSAGE("fixed predicates decided " << decided[0] << ", " << decided[1] << ", " << decided[2]
                                                 << "; exact zeros " << ties[0] << ", " << ties[1] << ", " << ties[2]
                                                 << "; in-sphere tests left to CGAL " << to_cgal
                                                 << "; wide near-ties answered " << wide_integer
                                                 << "; near ties at generic coordinates decided " << moved_decided
                                                 << " of 60000 (far from the origin " << far_decided << " of 30000; non-zero "
                                                 << moved_nonzero << ")");
}
