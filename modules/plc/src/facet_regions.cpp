#include "gsse/plc/facet_regions.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>

#include "gsse/container/union_find.hpp"
#include "gsse/geometry/predicates.hpp"

namespace gsse::input {
namespace {

using geometry::orient2d;
using geometry::project;

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

std::string facet_where(const plc<3>& p, std::size_t f) {
  return p.source + ":" + std::to_string(p.facets[f].line) + ": facet " + std::to_string(f + 1);
}

point3 newell(const plc<3>& p, const std::vector<vertex_id>& poly) {
  point3 n{0, 0, 0};
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const point3 &a = p.points[poly[i]], &b = p.points[poly[(i + 1) % poly.size()]];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  return n;
}

int dominant(const point3& n) {
  int ax = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[static_cast<std::size_t>(k)]) > std::abs(n[static_cast<std::size_t>(ax)])) ax = k;
  return ax;
}

/// A plane for the tolerance test: unit normal and a point on it.
struct plane {
  point3 unit, at;
  double offset(const point3& q) const { return dot(q - at, unit); }
};

bool on_segment(const point2& a, const point2& b, const point2& q) {
  if (orient2d(a, b, q) != 0) return false;
  return std::min(a[0], b[0]) <= q[0] && q[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= q[1] &&
         q[1] <= std::max(a[1], b[1]);
}

/// Winding number of the closed polygon about q (exact), or nullopt if q is on its boundary.
std::optional<int> winding(const std::vector<point2>& poly, const point2& q) {
  int wn = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const point2 &a = poly[i], &b = poly[(i + 1) % poly.size()];
    if (on_segment(a, b, q)) return std::nullopt;
    if (a[1] <= q[1]) {
      if (b[1] > q[1] && orient2d(a, b, q) > 0) ++wn;
    } else if (b[1] <= q[1] && orient2d(a, b, q) < 0) {
      --wn;
    }
  }
  return wn;
}

/// One input facet's region in its own projection (see facet_region).
struct single {
  facet_region r;
  plane pl;
  std::vector<vertex_id> vertices;  // every vertex of the facet
};

single one_facet(const plc<3>& p, std::size_t f, double tol) {
  const auto& F = p.facets[f];
  const std::string where = facet_where(p, f);
  single out;
  out.r.members = {static_cast<std::uint32_t>(f)};
  out.r.marker = F.marker;
  // the plane: the Newell normal of the polygon of largest area, through that polygon's centroid
  std::size_t big = F.polygons.size();
  double best = 0;
  for (std::size_t i = 0; i < F.polygons.size(); ++i) {
    if (F.polygons[i].size() < 3) continue;
    const point3 n = newell(p, F.polygons[i]);
    if (dot(n, n) > best) best = dot(n, n), big = i;
  }
  if (big == F.polygons.size()) throw input_error(where + ": has no polygon with area");
  const point3 n = newell(p, F.polygons[big]);
  point3 c{0, 0, 0};
  for (vertex_id v : F.polygons[big]) c = c + p.points[v];
  c = (1.0 / static_cast<double>(F.polygons[big].size())) * c;
  out.r.axis = dominant(n);
  out.r.normal = n[static_cast<std::size_t>(out.r.axis)] > 0 ? n : -1.0 * n;  // region ccw about it
  out.pl = {(1.0 / std::sqrt(dot(n, n))) * out.r.normal, c};
  const int axis = out.r.axis;
  for (const auto& poly : F.polygons)
    for (vertex_id v : poly) {
      out.vertices.push_back(v);
      const double off = std::abs(out.pl.offset(p.points[v]));
      if (!(off <= tol))
        throw input_error(where + ": vertex " + std::to_string(v + 1) + " is not in the facet's plane: " +
                          number(off) + " from it, more than the tolerance " + number(tol) + " (1e-12 of the model size)");
    }
  std::sort(out.vertices.begin(), out.vertices.end());
  out.vertices.erase(std::unique(out.vertices.begin(), out.vertices.end()), out.vertices.end());
  auto at = [&](vertex_id v) { return project(p.points[v], axis); };
  // polygons with area, counter-clockwise in the projection
  std::vector<std::vector<vertex_id>> loops;
  for (const auto& poly : F.polygons) {
    if (poly.size() < 3) continue;
    auto sorted = poly;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      throw input_error(where + ": a polygon repeats a vertex");
    std::size_t m = 0;  // the lexicographically smallest corner is convex
    for (std::size_t i = 1; i < poly.size(); ++i)
      if (lex_less(at(poly[i]), at(poly[m]))) m = i;
    const int o = orient2d(at(poly[(m + poly.size() - 1) % poly.size()]), at(poly[m]), at(poly[(m + 1) % poly.size()]));
    if (o == 0) throw input_error(where + ": polygon is degenerate at vertex " + std::to_string(poly[m] + 1));
    loops.push_back(poly);
    if (o < 0) std::reverse(loops.back().begin(), loops.back().end());
  }
  std::vector<std::vector<point2>> shapes(loops.size());
  for (std::size_t i = 0; i < loops.size(); ++i)
    for (vertex_id v : loops[i]) shapes[i].push_back(at(v));
  // nesting: loop i lies inside loop j if one of its vertices off j's boundary is inside j
  const std::size_t L = loops.size();
  std::vector<std::vector<char>> inside(L, std::vector<char>(L, 0));
  std::vector<int> depth(L, 0);
  for (std::size_t i = 0; i < L; ++i)
    for (std::size_t j = 0; j < L; ++j) {
      if (i == j) continue;
      for (const point2& q : shapes[i])
        if (const auto w = winding(shapes[j], q)) {
          inside[i][j] = *w != 0;
          break;
        }
      depth[i] += inside[i][j];
    }
  std::vector<long> parent(L, -1);
  for (std::size_t i = 0; i < L; ++i)
    for (std::size_t j = 0; j < L; ++j)
      if (inside[i][j] && depth[j] == depth[i] - 1) parent[i] = static_cast<long>(j);
  // the loop (annulus: inside it, outside its children) holding q strictly, or -1 (outside all)
  auto container = [&](const point2& q, bool& on_boundary) {
    long best_loop = -1;
    on_boundary = false;
    for (std::size_t j = 0; j < L; ++j) {
      const auto w = winding(shapes[j], q);
      if (!w) {
        on_boundary = true;
        continue;
      }
      if (*w != 0 && (best_loop < 0 || depth[j] > depth[static_cast<std::size_t>(best_loop)])) best_loop = static_cast<long>(j);
    }
    return best_loop;
  };
  std::vector<char> in(L, 1);  // annulus of loop i is part of the facet
  for (const point3& h : F.holes) {
    bool edge = false;
    const long j = container(project(h, axis), edge);
    if (j >= 0 && !edge) in[static_cast<std::size_t>(j)] = 0;
  }
  auto inside_of = [&](long j) { return j >= 0 && in[static_cast<std::size_t>(j)]; };
  for (std::size_t i = 0; i < L; ++i) {
    const bool left = in[i], right = inside_of(parent[i]);
    for (std::size_t k = 0; k < loops[i].size(); ++k) {
      const vertex_id u = loops[i][k], v = loops[i][(k + 1) % loops[i].size()];
      if (left) out.r.edges.push_back({u, v});
      if (right) out.r.edges.push_back({v, u});
    }
  }
  // embedded edges and points: inside a part of the facet, or on its boundary (points only)
  for (const auto& poly : F.polygons) {
    if (poly.size() == 2) {
      if (poly[0] == poly[1]) throw input_error(where + ": embedded edge repeats vertex " + std::to_string(poly[0] + 1));
      bool edge = false;
      const point2 mid = 0.5 * (at(poly[0]) + at(poly[1]));
      if (!inside_of(container(mid, edge)) || edge)
        throw input_error(where + ": embedded edge (" + std::to_string(poly[0] + 1) + ", " + std::to_string(poly[1] + 1) +
                          ") does not lie inside the facet");
      out.r.edges.push_back({poly[0], poly[1]});
      out.r.edges.push_back({poly[1], poly[0]});
    } else if (poly.size() == 1) {
      bool edge = false;
      const long j = container(at(poly[0]), edge);
      if (!edge && !inside_of(j))
        throw input_error(where + ": embedded point " + std::to_string(poly[0] + 1) + " does not lie inside the facet");
      if (!edge) out.r.points.push_back(poly[0]);
    }
  }
  std::sort(out.r.edges.begin(), out.r.edges.end());
  out.r.edges.erase(std::unique(out.r.edges.begin(), out.r.edges.end()), out.r.edges.end());
  if (out.r.edges.empty()) throw input_error(where + ": covers no area (every part is a hole)");
  return out;
}


/// Edges of a region re-expressed in the projection dropping `axis` (the orientation flips when
/// the normal's components along the two axes have opposite signs).
std::vector<std::array<vertex_id, 2>> in_projection(const facet_region& r, int axis) {
  auto e = r.edges;
  const double a = r.normal[static_cast<std::size_t>(r.axis)], b = r.normal[static_cast<std::size_t>(axis)];
  if ((a > 0) != (b > 0))
    for (auto& x : e) std::swap(x[0], x[1]);
  return e;
}

}  // namespace

double model_size(const plc<3>& p) {
  if (p.points.empty()) return 1;
  point3 lo = p.points[0], hi = lo;
  for (const auto& q : p.points)
    for (std::size_t k = 0; k < 3; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
  const double d = distance(lo, hi);
  return d > 0 ? d : 1;
}

std::vector<facet_region> facet_regions(const plc<3>& p, const facet_options& o) {
  const double tol = o.planar_tolerance * model_size(p);
  std::vector<single> one;
  one.reserve(p.facets.size());
  for (std::size_t f = 0; f < p.facets.size(); ++f) one.push_back(one_facet(p, f, tol));
  const auto F = static_cast<std::uint32_t>(one.size());
  // which facets use each (undirected) edge
  std::map<std::array<vertex_id, 2>, std::vector<std::uint32_t>> users;
  for (std::uint32_t f = 0; f < F; ++f)
    for (const auto& e : one[f].r.edges) {
      auto& u = users[{std::min(e[0], e[1]), std::max(e[0], e[1])}];
      if (u.empty() || u.back() != f) u.push_back(f);
    }
  gsse::union_find<> groups(F);
  auto coplanar = [&](const single& a, const single& b) {
    for (vertex_id v : b.vertices)
      if (!(std::abs(a.pl.offset(p.points[v])) <= tol)) return false;
    for (vertex_id v : a.vertices)
      if (!(std::abs(b.pl.offset(p.points[v])) <= tol)) return false;
    return true;
  };
  // directions of edge e in region r, in the projection dropping axis: bit 0 forward, bit 1 back
  auto directions = [](const std::vector<std::array<vertex_id, 2>>& edges, const std::array<vertex_id, 2>& e) {
    int d = 0;
    for (const auto& x : edges) d |= (x == e ? 1 : 0) | (x[0] == e[1] && x[1] == e[0] ? 2 : 0);
    return d;
  };
  if (o.merge_coplanar)
    for (const auto& [e, u] : users) {
      if (u.size() != 2) continue;
      const single &a = one[u[0]], &b = one[u[1]];
      if (a.r.marker != b.r.marker || groups.find(u[0]) == groups.find(u[1])) continue;
      // regions on opposite sides of e (in a's projection), each on one side only
      const int da = directions(a.r.edges, e), db = directions(in_projection(b.r, a.r.axis), e);
      if (!((da == 1 && db == 2) || (da == 2 && db == 1))) continue;
      if (!coplanar(a, b)) continue;
      groups.unite(u[0], u[1]);
    }
  std::map<std::uint32_t, std::vector<std::uint32_t>> members;
  for (std::uint32_t f = 0; f < F; ++f) members[groups.find(f)].push_back(f);
  std::vector<facet_region> out;
  for (auto& [root, ms] : members) {
    if (ms.size() == 1) {
      out.push_back(std::move(one[ms[0]].r));
      continue;
    }
    // the group's plane: area-weighted normal (members turned to agree with the first)
    point3 n{0, 0, 0}, c{0, 0, 0};
    double w = 0;
    for (auto f : ms) {
      const point3& m = one[f].r.normal;
      n = n + (dot(m, one[ms[0]].r.normal) < 0 ? -1.0 : 1.0) * m;
      const double a = std::sqrt(dot(m, m));
      c = c + a * one[f].pl.at;
      w += a;
    }
    const plane pl{(1.0 / std::sqrt(dot(n, n))) * n, (1.0 / w) * c};
    bool flat = true;
    for (auto f : ms)
      for (vertex_id v : one[f].vertices) flat = flat && std::abs(pl.offset(p.points[v])) <= tol;
    if (!flat) {  // a long chain of nearly coplanar facets drifted: keep them apart
      for (auto f : ms) out.push_back(std::move(one[f].r));
      continue;
    }
    facet_region g;
    g.members = ms;
    g.marker = one[ms[0]].r.marker;
    g.axis = dominant(n);
    g.normal = n[static_cast<std::size_t>(g.axis)] > 0 ? n : -1.0 * n;
    // directed edges of the members, by undirected edge
    std::map<std::array<vertex_id, 2>, std::vector<std::array<vertex_id, 2>>> by_key;
    for (auto f : ms) {
      for (const auto& x : in_projection(one[f].r, g.axis)) by_key[{std::min(x[0], x[1]), std::max(x[0], x[1])}].push_back(x);
      g.points.insert(g.points.end(), one[f].r.points.begin(), one[f].r.points.end());
    }
    // an edge that two members use in opposite directions, and no other facet, is merged away
    std::vector<vertex_id> freed;
    for (const auto& [k, xs] : by_key) {
      const bool merged = users[k].size() == 2 && xs.size() == 2 && xs[0][0] == xs[1][1] && xs[0][1] == xs[1][0];
      if (merged) {
        freed.push_back(k[0]);
        freed.push_back(k[1]);
      } else {
        g.edges.insert(g.edges.end(), xs.begin(), xs.end());
      }
    }
    std::sort(g.edges.begin(), g.edges.end());
    g.edges.erase(std::unique(g.edges.begin(), g.edges.end()), g.edges.end());
    std::vector<vertex_id> on_edges;
    for (const auto& x : g.edges) on_edges.push_back(x[0]), on_edges.push_back(x[1]);
    std::sort(on_edges.begin(), on_edges.end());
    for (vertex_id v : freed)
      if (!std::binary_search(on_edges.begin(), on_edges.end(), v)) g.points.push_back(v);
    std::sort(g.points.begin(), g.points.end());
    g.points.erase(std::unique(g.points.begin(), g.points.end()), g.points.end());
    out.push_back(std::move(g));
  }
  std::sort(out.begin(), out.end(), [](const facet_region& a, const facet_region& b) { return a.members[0] < b.members[0]; });
  return out;
}

}  // namespace gsse::input
