#include "gsse/plc/intersections.hpp"

#include <algorithm>
#include <limits>
#include <optional>
#include <tuple>

#include <CGAL/Intersections_3/Segment_3_Triangle_3.h>
#include <CGAL/Intersections_3/Triangle_3_Triangle_3.h>

#include "box_pairs.hpp"
#include "facet_triangulation.hpp"
#include "gsse/geometry/predicates.hpp"

namespace gsse::plc_check {
namespace {

using geometry::orient2d;
using geometry::orient3d;
using geometry::detail::cg;
using K = geometry::kernel;
constexpr std::uint32_t no_group = std::numeric_limits<std::uint32_t>::max();

std::string num(std::size_t i) { return std::to_string(i + 1); }

// ---------------------------------------------------------------------------------------------
// 3D: triangles of the facets' triangulations, and PLC points on no facet

struct element3 {
  std::array<vertex_id, 3> v;  // a point: three times the same id
  std::uint32_t facet;         // no_group for a point
  std::uint8_t polygon_edges;  // bit i: edge (v[i], v[i+1]) is a polygon edge of the facet
  std::uint8_t axis;           // the facet's projection, in which the triangle is counter-clockwise
};

bool has(const element3& T, vertex_id v) { return T.v[0] == v || T.v[1] == v || T.v[2] == v; }

/// Whether triangles T and U are disjoint in T's projection, or meet there only in their shared
/// vertices and edge: then they do so in 3D, since the projection is one-to-one on T's plane. A
/// sufficient test in 2D orientations, cheaper than the 3D tests, that decides most pairs of
/// neighbouring facets: a line through an edge of either triangle with the other's vertices
/// strictly beyond it, except shared ones that are the edge's ends.
bool apart_in_projection(const std::vector<point3>& p, const element3& T, const element3& U) {
  const int axis = T.axis;
  std::array<point2, 3> t, u;
  for (std::size_t i = 0; i < 3; ++i) t[i] = geometry::project(p[T.v[i]], axis), u[i] = geometry::project(p[U.v[i]], axis);
  auto separates = [&](const element3& E, const std::array<point2, 3>& e, std::size_t i, int side,
                       const element3& F, const std::array<point2, 3>& f) {
    const vertex_id x = E.v[i], y = E.v[(i + 1) % 3];
    for (std::size_t k = 0; k < 3; ++k)  // (E's third vertex is on the inner side: never beyond)
      if (F.v[k] != x && F.v[k] != y && orient2d(e[i], e[(i + 1) % 3], f[k]) != side) return false;
    return true;
  };
  for (std::size_t i = 0; i < 3; ++i)
    if (separates(T, t, i, -1, U, u)) return true;
  // U's orientation in this projection tells which side of its edges is outside
  const int o = orient2d(u[0], u[1], u[2]);
  if (o == 0) return false;
  for (std::size_t i = 0; i < 3; ++i)
    if (separates(U, u, i, -o, T, t)) return true;
  return false;
}

/// Where x lies in triangle T: -1 not in it (or not in its plane), 0..2 on edge (T[i], T[i+1]),
/// 3 in its interior.
int locate(const std::vector<point3>& p, const element3& T, const point3& x) {
  const auto& a = p[T.v[0]];
  const auto& b = p[T.v[1]];
  const auto& c = p[T.v[2]];
  if (orient3d(a, b, c, x) != 0) return -1;
  const auto side = geometry::detail::K().coplanar_orientation_3_object();
  int where = 3;
  for (std::size_t i = 0; i < 3; ++i) {
    const auto s = side(cg(p[T.v[i]]), cg(p[T.v[(i + 1) % 3]]), cg(p[T.v[(i + 2) % 3]]), cg(x));
    if (s == CGAL::NEGATIVE) return -1;
    if (s == CGAL::COLLINEAR) where = static_cast<int>(i);
  }
  return where;
}

std::string vertex_in(const element3& T, int where, vertex_id x, const std::string& facet) {
  if (where < 3 && (T.polygon_edges >> where & 1))
    return "vertex " + num(x) + " lies on the edge " + num(T.v[static_cast<std::size_t>(where)]) + "-" +
           num(T.v[static_cast<std::size_t>(where + 1) % 3]) + " of " + facet;
  return "vertex " + num(x) + " lies inside " + facet;
}

/// What the intersecting triangles T (of facet b) and U (of facet a) have in common besides
/// shared vertices: a vertex of one in the other, coplanar overlap, or a crossing.
std::string describe(const std::vector<point3>& p, const element3& T, const element3& U) {
  for (vertex_id x : T.v)
    if (!has(U, x))
      if (const int w = locate(p, U, p[x]); w >= 0) return vertex_in(U, w, x, "facet " + num(U.facet));
  for (vertex_id y : U.v)
    if (!has(T, y))
      if (const int w = locate(p, T, p[y]); w >= 0) return vertex_in(T, w, y, "facet " + num(T.facet));
  for (vertex_id y : U.v)
    if (orient3d(p[T.v[0]], p[T.v[1]], p[T.v[2]], p[y]) != 0) return "they cross";
  return "they overlap in their plane";
}

/// Whether triangles T and U (of different facets) intersect other than in shared vertices and a
/// shared edge.
bool improper(const std::vector<point3>& p, const element3& T, const element3& U) {
  std::array<vertex_id, 3> own{}, other{};
  std::size_t n_own = 0, n_other = 0, shared = 0;
  std::array<vertex_id, 3> common{};
  for (vertex_id x : T.v)
    if (has(U, x)) common[shared++] = x;
    else own[n_own++] = x;
  for (vertex_id y : U.v)
    if (!has(T, y)) other[n_other++] = y;
  if (shared < 3 && apart_in_projection(p, T, U)) return false;
  auto tri = [&](const element3& E) { return K::Triangle_3(cg(p[E.v[0]]), cg(p[E.v[1]]), cg(p[E.v[2]])); };
  switch (shared) {
    case 3:
      return true;
    case 2: {
      // a shared edge: only coplanar triangles on the same side of it overlap
      const auto &a = p[common[0]], &b = p[common[1]], &c = p[own[0]], &d = p[other[0]];
      if (orient3d(a, b, c, d) != 0) return false;
      return geometry::detail::K().coplanar_orientation_3_object()(cg(a), cg(b), cg(c), cg(d)) == CGAL::POSITIVE;
    }
    case 1: {
      // a shared vertex v: the triangles meet beyond v iff the edge of one opposite v meets the other
      const auto& v = p[common[0]];
      const auto &a = p[own[0]], &b = p[own[1]], &c = p[other[0]], &d = p[other[1]];
      if (orient3d(v, a, b, c) * orient3d(v, a, b, d) > 0) return false;
      if (orient3d(v, c, d, a) * orient3d(v, c, d, b) > 0) return false;
      return CGAL::do_intersect(K::Segment_3(cg(a), cg(b)), tri(U)) ||
             CGAL::do_intersect(K::Segment_3(cg(c), cg(d)), tri(T));
    }
    default:
      return CGAL::do_intersect(tri(T), tri(U));
  }
}

// ---------------------------------------------------------------------------------------------
// 2D: segments and PLC points on no segment

/// Whether x lies strictly between a and b on segment ab.
bool on_segment(const point2& a, const point2& b, const point2& x) {
  return orient2d(a, b, x) == 0 && lex_less(a, x) != lex_less(b, x);
}

/// What segments S (index b) and R (index a) have in common besides a shared endpoint, if anything.
std::optional<std::string> segments_meet(const std::vector<point2>& p, std::array<vertex_id, 2> S,
                                         std::array<vertex_id, 2> R, std::uint32_t a, std::uint32_t b) {
  const bool s0 = S[0] == R[0] || S[0] == R[1], s1 = S[1] == R[0] || S[1] == R[1];
  if (s0 && s1) return "they join the same vertices";
  if (s0 || s1) {
    const vertex_id v = s0 ? S[0] : S[1], x = s0 ? S[1] : S[0], y = R[0] == v ? R[1] : R[0];
    if (orient2d(p[v], p[x], p[y]) == 0 && lex_less(p[v], p[x]) == lex_less(p[v], p[y]))
      return std::string("they overlap (collinear)");
    return std::nullopt;
  }
  const int o1 = orient2d(p[R[0]], p[R[1]], p[S[0]]), o2 = orient2d(p[R[0]], p[R[1]], p[S[1]]);
  if (o1 * o2 > 0) return std::nullopt;
  const int o3 = orient2d(p[S[0]], p[S[1]], p[R[0]]), o4 = orient2d(p[S[0]], p[S[1]], p[R[1]]);
  if (o3 * o4 > 0) return std::nullopt;
  if (o1 == 0 && o2 == 0) {
    // collinear: the lexicographic order is the order along the line
    auto lo = [&](std::array<vertex_id, 2> e) { return lex_less(p[e[0]], p[e[1]]) ? p[e[0]] : p[e[1]]; };
    auto hi = [&](std::array<vertex_id, 2> e) { return lex_less(p[e[0]], p[e[1]]) ? p[e[1]] : p[e[0]]; };
    if (lex_less(hi(S), lo(R)) || lex_less(hi(R), lo(S))) return std::nullopt;
    return std::string("they overlap (collinear)");
  }
  if (o1 == 0) return "vertex " + num(S[0]) + " lies on segment " + num(a);
  if (o2 == 0) return "vertex " + num(S[1]) + " lies on segment " + num(a);
  if (o3 == 0) return "vertex " + num(R[0]) + " lies on segment " + num(b);
  if (o4 == 0) return "vertex " + num(R[1]) + " lies on segment " + num(b);
  return std::string("they cross");
}

// ---------------------------------------------------------------------------------------------

/// Points referenced by no facet or segment.
std::vector<vertex_id> free_points(std::size_t n, const std::vector<vertex_id>& used_ids) {
  std::vector<char> used(n, 0);
  for (vertex_id v : used_ids) used[v] = 1;
  std::vector<vertex_id> out;
  for (std::size_t v = 0; v < n; ++v)
    if (!used[v]) out.push_back(static_cast<vertex_id>(v));
  return out;
}

struct candidate {
  std::uint32_t a, b;  // report key
  std::uint32_t i, j;  // elements: i of b (or the point), j of a
};

/// Runs `test` over the candidates grouped by (a, b) in increasing order, stopping a group at its
/// first finding, and merges the findings with `found` (problems known already) into the first
/// max_reports by (a, b).
template <class Test>
std::vector<intersection> collect(std::vector<candidate> cands, std::vector<intersection> found,
                                  std::size_t max_reports, Test&& test) {
  // by a (counting), then by (b, i, j) within each a: small sorts instead of one large one
  {
    std::uint32_t groups = 0;
    for (const auto& c : cands) groups = std::max(groups, c.a + 1);
    std::vector<std::size_t> start(groups + 1, 0);
    for (const auto& c : cands) ++start[c.a + 1];
    for (std::size_t g = 0; g < groups; ++g) start[g + 1] += start[g];
    std::vector<candidate> by_a(cands.size());
    auto fill = start;
    for (const auto& c : cands) by_a[fill[c.a]++] = c;
    for (std::size_t g = 0; g < groups; ++g)
      std::sort(by_a.begin() + static_cast<std::ptrdiff_t>(start[g]), by_a.begin() + static_cast<std::ptrdiff_t>(start[g + 1]),
                [](const candidate& x, const candidate& y) { return std::tie(x.b, x.i, x.j) < std::tie(y.b, y.i, y.j); });
    cands = std::move(by_a);
  }
  std::sort(found.begin(), found.end(), [](const intersection& x, const intersection& y) {
    return std::tie(x.a, x.b) < std::tie(y.a, y.b);
  });
  const std::size_t known = found.size();
  std::size_t before = 0;  // known problems ordered before the current group
  for (std::size_t k = 0; k < cands.size();) {
    const auto key = std::tie(cands[k].a, cands[k].b);
    while (before < known && std::tie(found[before].a, found[before].b) < key) ++before;
    if (before + (found.size() - known) >= max_reports) break;
    std::size_t end = k;
    while (end < cands.size() && std::tie(cands[end].a, cands[end].b) == key) ++end;
    for (; k < end; ++k)
      if (auto what = test(cands[k])) {
        found.push_back({cands[k].a, cands[k].b, std::move(*what)});
        break;
      }
    k = end;
  }
  std::stable_sort(found.begin(), found.end(), [](const intersection& x, const intersection& y) {
    return std::tie(x.a, x.b) < std::tie(y.a, y.b);
  });
  if (found.size() > max_reports) found.resize(max_reports);
  return found;
}

template <std::size_t D>
std::string line_of(const plc<D>& p, std::size_t line) {
  return p.source + (line ? ":" + std::to_string(line) : std::string()) + ": ";
}

template <std::size_t D>
void require(const plc<D>& p) {
  constexpr std::size_t most = 16;
  const auto r = self_intersections(p, most);
  if (r.empty()) return;
  std::string m = message(p, r.front());
  if (r.size() > 1)
    m += " (and " + std::string(r.size() == most ? "at least " : "") + std::to_string(r.size() - 1) + " more)";
  throw input_error(m);
}

}  // namespace

std::vector<intersection> self_intersections(const plc<3>& p, std::size_t max_reports) {
  const auto& pts = p.points;
  std::vector<element3> elems;
  std::vector<intersection> found;
  std::vector<vertex_id> used;
  for (std::uint32_t f = 0; f < p.facets.size(); ++f) {
    for (const auto& poly : p.facets[f].polygons) used.insert(used.end(), poly.begin(), poly.end());
    auto ft = detail::triangulate_facet(pts, p.facets[f]);
    if (!ft.problem.empty()) found.push_back({f, f, std::move(ft.problem)});
    for (std::size_t t = 0; t < ft.triangles.size(); ++t) elems.push_back({ft.triangles[t], f, ft.polygon_edges[t], static_cast<std::uint8_t>(ft.axis)});
  }
  for (vertex_id v : free_points(pts.size(), used)) elems.push_back({{v, v, v}, no_group, 0, 0});
  std::vector<detail::box<3>> boxes;
  boxes.reserve(elems.size());
  for (const auto& e : elems) {
    detail::box<3> b{pts[e.v[0]], pts[e.v[0]], e.facet};
    for (vertex_id v : e.v)
      for (std::size_t k = 0; k < 3; ++k) b.lo[k] = std::min(b.lo[k], pts[v][k]), b.hi[k] = std::max(b.hi[k], pts[v][k]);
    boxes.push_back(b);
  }
  std::vector<candidate> cands;
  for (auto [i, j] : detail::box_pairs(boxes)) {
    const auto fi = elems[i].facet, fj = elems[j].facet;
    if (fi == no_group) cands.push_back({fj, fj, i, j});
    else if (fj == no_group) cands.push_back({fi, fi, j, i});
    else if (fi > fj) cands.push_back({fj, fi, i, j});
    else cands.push_back({fi, fj, j, i});
  }
  return collect(std::move(cands), std::move(found), max_reports, [&](const candidate& c) -> std::optional<std::string> {
    const auto &T = elems[c.i], &U = elems[c.j];
    if (T.facet == no_group) {
      const int w = locate(pts, U, pts[T.v[0]]);
      if (w < 0) return std::nullopt;
      const auto s = vertex_in(U, w, T.v[0], "it");
      return s.substr(0, s.find(" lies")) + ", on no facet," + s.substr(s.find(" lies"));
    }
    if (!improper(pts, T, U)) return std::nullopt;
    return describe(pts, T, U);
  });
}

std::vector<intersection> self_intersections(const plc<2>& p, std::size_t max_reports) {
  const auto& pts = p.points;
  std::vector<vertex_id> used;
  std::vector<detail::box<2>> boxes;
  for (std::uint32_t s = 0; s < p.edges.size(); ++s) {
    const auto [u, w] = p.edges[s];
    used.push_back(u), used.push_back(w);
    boxes.push_back({{std::min(pts[u][0], pts[w][0]), std::min(pts[u][1], pts[w][1])},
                     {std::max(pts[u][0], pts[w][0]), std::max(pts[u][1], pts[w][1])},
                     s});
  }
  const auto free = free_points(pts.size(), used);
  for (vertex_id v : free) boxes.push_back({pts[v], pts[v], no_group});
  const auto segments = static_cast<std::uint32_t>(p.edges.size());
  std::vector<candidate> cands;
  for (auto [i, j] : detail::box_pairs(boxes)) {
    // the segment indices are the box indices; points come after them
    if (j >= segments) cands.push_back({i, i, j, i});
    else cands.push_back({i, j, j, i});
  }
  std::vector<intersection> found;
  for (std::uint32_t s = 0; s < segments; ++s)
    if (p.edges[s][0] == p.edges[s][1]) found.push_back({s, s, "its two vertices are the same"});
  return collect(std::move(cands), std::move(found), max_reports, [&](const candidate& c) -> std::optional<std::string> {
    if (c.i >= segments) {
      const vertex_id x = free[c.i - segments];
      const auto& e = p.edges[c.j];
      if (!on_segment(pts[e[0]], pts[e[1]], pts[x])) return std::nullopt;
      return "vertex " + num(x) + ", on no segment, lies on it";
    }
    if (p.edges[c.i][0] == p.edges[c.i][1] || p.edges[c.j][0] == p.edges[c.j][1]) return std::nullopt;
    return segments_meet(pts, p.edges[c.i], p.edges[c.j], c.a, c.b);
  });
}

std::string message(const plc<3>& p, const intersection& x) {
  const auto& B = p.facets[x.b];
  auto facet = [&](std::uint32_t f) {
    const std::size_t l = p.facets[f].line;
    return "facet " + num(f) + (l ? " (line " + std::to_string(l) + ")" : std::string());
  };
  if (x.a == x.b) return line_of(p, B.line) + facet(x.b) + ": " + x.what;
  return line_of(p, B.line) + facet(x.b) + " intersects " + facet(x.a) + ": " + x.what;
}

std::string message(const plc<2>& p, const intersection& x) {
  auto segment = [&](std::uint32_t s) {
    return "segment " + num(s) + " (vertices " + num(p.edges[s][0]) + "-" + num(p.edges[s][1]) + ")";
  };
  if (x.a == x.b) return line_of(p, 0) + segment(x.b) + ": " + x.what;
  return line_of(p, 0) + segment(x.b) + " intersects " + segment(x.a) + ": " + x.what;
}

void require_no_self_intersections(const plc<3>& p) { require(p); }
void require_no_self_intersections(const plc<2>& p) { require(p); }

}  // namespace gsse::plc_check
