#pragma once
// An oracle for the conformer's output that shares nothing with the conformer: CGAL's predicates
// called directly (side_of_bounded_circle / side_of_bounded_sphere of CGAL's own kernel, not
// gsse::geometry), brute force over every point (sorted by x, a window from CGAL's circumcentre
// padded generously, never the conformer's ball bounds or tie rules), the subsegments found
// from the faces themselves, and, in 3D, CGAL's Delaunay_triangulation_3 (GPL: tests only) as
// the judge of whether each subfacet is Delaunay.
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <vector>

#include "gsse/conformer/conformer.hpp"

namespace gsse::test {

struct oracle_report {
  std::set<std::size_t> strictly_encroached;  // faces with a point strictly inside their ball
  std::size_t subsegments = 0;                // 3D: facet boundary edges found from the faces
  std::size_t encroached_subsegments = 0;     // 3D: of those, with a point strictly inside
  std::size_t ties = 0;                       // (face, point) pairs with the point on the sphere
  std::size_t not_delaunay = 0;               // 3D: subfacets that are no facet of CGAL's DT
};

namespace oracle_detail {
using EK = CGAL::Exact_predicates_inexact_constructions_kernel;

template <std::size_t D>
typename std::conditional_t<D == 2, EK::Point_2, EK::Point_3> cg(const point<D>& p) {
  if constexpr (D == 2)
    return {p[0], p[1]};
  else
    return {p[0], p[1], p[2]};
}

/// Half-width of the x window around a ball's centre x: its radius with a margin far above any
/// rounding of the double construction (1%, and 1e-9 of the coordinates); unbounded when not finite.
inline double padded(double x, double radius) {
  const double r = radius * 1.01 + 1e-9 * (std::abs(x) + radius) + 1e-300;
  return std::isfinite(r) && std::isfinite(x) ? r : std::numeric_limits<double>::infinity();
}

template <std::size_t D>
std::vector<vertex_id> sorted_by_x(const std::vector<point<D>>& p) {
  std::vector<vertex_id> by_x(p.size());
  std::iota(by_x.begin(), by_x.end(), vertex_id{0});
  std::sort(by_x.begin(), by_x.end(), [&](vertex_id a, vertex_id c) { return p[a][0] < p[c][0]; });
  return by_x;
}

/// Calls f(y) for every point y whose x lies within [x - reach, x + reach] (ids sorted by x).
template <std::size_t D, class F>
void window(const std::vector<point<D>>& p, const std::vector<vertex_id>& by_x, double x, double reach, F&& f) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double lo = std::isfinite(reach) ? x - reach : -inf, hi = std::isfinite(reach) ? x + reach : inf;
  auto first = std::lower_bound(by_x.begin(), by_x.end(), lo, [&](vertex_id v, double l) { return p[v][0] < l; });
  for (; first != by_x.end() && p[*first][0] <= hi; ++first) f(*first);
}
}  // namespace oracle_detail

/// Brute-force check of a conformed 2D boundary: each subsegment against every point.
inline oracle_report encroachment_oracle(const conformer::boundary<2>& b) {
  using namespace oracle_detail;
  oracle_report r;
  const auto& p = b.points;
  const auto by_x = sorted_by_x(p);
  for (std::size_t f = 0; f < b.faces.size(); ++f) {
    const auto [a, c] = b.faces[f];
    const double mid = 0.5 * (p[a][0] + p[c][0]);
    const double reach = padded(mid, 0.5 * std::sqrt(CGAL::to_double(CGAL::squared_distance(cg(p[a]), cg(p[c])))));
    window(p, by_x, mid, reach, [&](vertex_id y) {
      if (y == a || y == c) return;
      const auto s = CGAL::side_of_bounded_circle(cg(p[a]), cg(p[c]), cg(p[y]));
      if (s == CGAL::ON_BOUNDED_SIDE) r.strictly_encroached.insert(f);
      if (s == CGAL::ON_BOUNDARY) ++r.ties;
    });
  }
  return r;
}

/// Brute-force check of a conformed 3D boundary: each subfacet's equatorial ball and each
/// subsegment's diametral ball against every point, and each subfacet against CGAL's Delaunay
/// triangulation of all the points.
inline oracle_report encroachment_oracle(const conformer::boundary<3>& b) {
  using namespace oracle_detail;
  oracle_report r;
  const auto& p = b.points;
  const auto by_x = sorted_by_x(p);
  for (std::size_t f = 0; f < b.faces.size(); ++f) {
    const auto [a, c, d] = b.faces[f];
    const auto o = CGAL::circumcenter(cg(p[a]), cg(p[c]), cg(p[d]));
    const double rad = std::sqrt(CGAL::to_double(CGAL::squared_distance(o, cg(p[a]))));
    const double reach = padded(o.x(), rad);
    window(p, by_x, o.x(), reach, [&](vertex_id y) {
      if (y == a || y == c || y == d) return;
      const auto s = CGAL::side_of_bounded_sphere(cg(p[a]), cg(p[c]), cg(p[d]), cg(p[y]));
      if (s == CGAL::ON_BOUNDED_SIDE) r.strictly_encroached.insert(f);
      if (s == CGAL::ON_BOUNDARY) ++r.ties;
    });
  }
  // subsegments: edges that bound the faces of one input facet (used an odd number of times
  // among that facet's faces)
  std::map<std::pair<std::uint32_t, std::pair<vertex_id, vertex_id>>, int> uses;
  for (std::size_t f = 0; f < b.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      vertex_id u = b.faces[f][k], v = b.faces[f][(k + 1) % 3];
      if (u > v) std::swap(u, v);
      ++uses[{b.face_source[f], {u, v}}];
    }
  std::set<std::pair<vertex_id, vertex_id>> subsegments;
  for (const auto& [key, n] : uses)
    if (n % 2 == 1) subsegments.insert(key.second);
  r.subsegments = subsegments.size();
  for (const auto& [a, c] : subsegments) {
    const double mid = 0.5 * (p[a][0] + p[c][0]);
    const double reach = padded(mid, 0.5 * std::sqrt(CGAL::to_double(CGAL::squared_distance(cg(p[a]), cg(p[c])))));
    bool hit = false;
    window(p, by_x, mid, reach, [&](vertex_id y) {
      if (y != a && y != c && CGAL::side_of_bounded_sphere(cg(p[a]), cg(p[c]), cg(p[y])) == CGAL::ON_BOUNDED_SIDE) hit = true;
    });
    r.encroached_subsegments += hit;
  }
  // every subfacet a facet of CGAL's Delaunay triangulation (symbolically perturbed, so unique)
  using Vb = CGAL::Triangulation_vertex_base_with_info_3<vertex_id, EK>;
  using DT = CGAL::Delaunay_triangulation_3<EK, CGAL::Triangulation_data_structure_3<Vb>>;
  std::vector<std::pair<EK::Point_3, vertex_id>> in;
  for (vertex_id i = 0; i < p.size(); ++i) in.push_back({cg(p[i]), i});
  const DT dt(in.begin(), in.end());
  std::vector<DT::Vertex_handle> handle(p.size());
  std::vector<char> present(p.size(), 0);  // a point at the position of another is not a vertex
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) handle[v->info()] = v, present[v->info()] = 1;
  for (const auto& F : b.faces) {
    DT::Cell_handle cell;
    int i, j, k;
    if (!present[F[0]] || !present[F[1]] || !present[F[2]] || !dt.is_facet(handle[F[0]], handle[F[1]], handle[F[2]], cell, i, j, k))
      ++r.not_delaunay;
  }
  return r;
}

}  // namespace gsse::test
