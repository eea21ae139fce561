// The self-intersection check against CGAL's Polygon_mesh_processing::self_intersections (GPL,
// tests only) on crumpled closed triangle surfaces: random displacements fold the surface, and
// snapping the coordinates to a coarse grid makes many coplanar and collinear configurations.
// Both use exact predicates, so the intersecting face pairs must be the same.
#define BOOST_TEST_MODULE plc_cgal_oracle
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include "gsse/plc/intersections.hpp"

using namespace gsse;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using mesh = CGAL::Surface_mesh<K::Point_3>;

namespace {

/// Icosahedron subdivided `levels` times, on the unit sphere; one triangle facet per face.
plc<3> icosphere(int levels) {
  plc<3> p;
  p.source = "icosphere";
  const double g = (1 + std::sqrt(5.0)) / 2;
  p.points = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
              {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::array<vertex_id, 3>> f{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                          {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                          {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                          {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<vertex_id, vertex_id>, vertex_id> mid;
    auto m = [&](vertex_id a, vertex_id b) {
      auto [it, fresh] = mid.try_emplace({std::min(a, b), std::max(a, b)}, static_cast<vertex_id>(p.points.size()));
      if (fresh) {
        const auto &x = p.points[a], &y = p.points[b];
        p.points.push_back({(x[0] + y[0]) / 2, (x[1] + y[1]) / 2, (x[2] + y[2]) / 2});
      }
      return it->second;
    };
    std::vector<std::array<vertex_id, 3>> next;
    for (auto [a, b, c] : f) {
      const auto ab = m(a, b), bc = m(b, c), ca = m(c, a);
      next.insert(next.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    f = std::move(next);
  }
  for (auto& x : p.points) {
    const double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (auto& c : x) c /= r;
  }
  for (auto [a, b, c] : f) p.facets.push_back({{{a, b, c}}, {}, 0, p.facets.size() + 1});
  return p;
}

std::set<std::pair<std::uint32_t, std::uint32_t>> cgal_pairs(const plc<3>& p) {
  std::vector<K::Point_3> pts;
  for (const auto& x : p.points) pts.push_back({x[0], x[1], x[2]});
  std::vector<std::vector<std::size_t>> polys;
  for (const auto& f : p.facets) polys.push_back({f.polygons[0].begin(), f.polygons[0].end()});
  mesh m;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(pts, polys, m);
  std::vector<std::pair<mesh::Face_index, mesh::Face_index>> out;
  CGAL::Polygon_mesh_processing::self_intersections(m, std::back_inserter(out));
  std::set<std::pair<std::uint32_t, std::uint32_t>> s;
  for (auto [f, g] : out) {
    const auto a = static_cast<std::uint32_t>(f), b = static_cast<std::uint32_t>(g);
    s.insert({std::min(a, b), std::max(a, b)});
  }
  return s;
}

/// Crumples the sphere `trials` times (displacements up to `amplitude`, coordinates snapped to
/// multiples of `snap` if > 0; trials with coinciding points or degenerate faces are redrawn)
/// and compares; returns the number of intersecting pairs seen.
std::size_t compare(int levels, double amplitude, double snap, int trials, unsigned seed) {
  const auto sphere = icosphere(levels);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  std::size_t pairs = 0;
  for (int t = 0; t < trials;) {
    auto p = sphere;
    for (auto& x : p.points)
      for (auto& c : x) {
        c += u(rng);
        if (snap > 0) c = std::round(c / snap) * snap;
      }
    auto sorted = p.points;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) continue;
    bool degenerate = false;
    for (const auto& f : p.facets) {
      const auto& l = f.polygons[0];
      auto P = [&](std::size_t k) { return K::Point_3(p.points[l[k]][0], p.points[l[k]][1], p.points[l[k]][2]); };
      degenerate = degenerate || CGAL::collinear(P(0), P(1), P(2));
    }
    if (degenerate) continue;
    ++t;
    const auto want = cgal_pairs(p);
    std::set<std::pair<std::uint32_t, std::uint32_t>> got;
    for (const auto& x : plc_check::self_intersections(p, 1u << 30)) got.insert({x.a, x.b});
    BOOST_TEST((got == want), "trial " << t << ": CGAL " << want.size() << " pairs, ours " << got.size());
    pairs += want.size();
  }
  return pairs;
}

}  // namespace

BOOST_AUTO_TEST_CASE(crumpled_spheres) {
  const auto n = compare(2, 0.15, 0, 200, 1);
  BOOST_TEST_MESSAGE(n << " intersecting pairs");
  BOOST_TEST(n > 100u);
}

BOOST_AUTO_TEST_CASE(crumpled_spheres_on_a_grid) {
  // on multiples of 1/8 and 1/4: coplanar faces, vertices on edges and faces of others
  const auto n = compare(1, 0.2, 0.125, 300, 2) + compare(1, 0.3, 0.25, 300, 3);
  BOOST_TEST_MESSAGE(n << " intersecting pairs");
  BOOST_TEST(n > 100u);
}
