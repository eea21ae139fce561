#include "facet_triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "gsse/geometry/predicates.hpp"

namespace gsse::plc_check::detail {
namespace {

using geometry::orient2d;

struct triangle {
  std::array<int, 3> v{};
  std::array<int, 3> n{-1, -1, -1};  // n[i]: neighbour across edge i = (v[i], v[i+1])
  std::uint8_t fixed = 0;            // bit i: edge i is a polygon edge
};

constexpr int nxt(int i) { return i == 2 ? 0 : i + 1; }
constexpr int prv(int i) { return i == 0 ? 2 : i - 1; }

// A constrained triangulation of points in the plane: a triangulation of their convex hull built
// in lexicographic order, made Delaunay by flips (so that a polygon edge crosses few triangles),
// then the polygon edges inserted one by one, each replacing the triangles it crosses by the
// triangulations of the two pseudo-polygons on its sides (Anglada 1997). Any polygon edge that
// crosses an earlier one, or runs through a vertex, is a problem of the facet.
class cdt {
 public:
  cdt(std::vector<point2> pts, const std::vector<vertex_id>& ids) : p_(std::move(pts)), ids_(ids) {}

  std::string problem;
  std::vector<triangle> t;

  /// Triangulates the convex hull; false if all points are collinear (no triangle) or two coincide.
  bool build() {
    const int m = static_cast<int>(p_.size());
    std::vector<int> o(static_cast<std::size_t>(m));
    std::iota(o.begin(), o.end(), 0);
    std::sort(o.begin(), o.end(), [&](int a, int b) { return lex_less(p_[a], p_[b]); });
    for (int i = 1; i < m; ++i)
      if (p_[o[i]] == p_[o[i - 1]]) {
        problem = "vertices " + id(std::min(o[i], o[i - 1])) + " and " + id(std::max(o[i], o[i - 1])) +
                  " coincide in its projection (it is not planar)";
        return false;
      }
    int k = 2;
    while (k < m && orient2d(p_[o[0]], p_[o[1]], p_[o[k]]) == 0) ++k;
    if (k >= m) return false;
    std::vector<int> next(static_cast<std::size_t>(m), -1), prev(next), hull_tri(next);
    const int c = o[k];
    const bool ccw = orient2d(p_[o[0]], p_[o[1]], p_[c]) > 0;
    // fan from c over the collinear chain o[0..k)
    for (int i = 0; i + 1 < k; ++i) {
      const int a = o[i], b = o[i + 1];
      const int ti = ccw ? add(a, b, c) : add(b, a, c);
      if (i > 0) link_shared(ti, ti - 1);
      if (ccw) next[a] = b, prev[b] = a, hull_tri[a] = ti;
      else next[b] = a, prev[a] = b, hull_tri[b] = ti;
    }
    const int last_fan = k - 2;
    if (ccw) {
      next[o[k - 1]] = c, prev[c] = o[k - 1], hull_tri[o[k - 1]] = last_fan;
      next[c] = o[0], prev[o[0]] = c, hull_tri[c] = 0;
    } else {
      next[c] = o[k - 1], prev[o[k - 1]] = c, hull_tri[c] = last_fan;
      next[o[0]] = c, prev[c] = o[0], hull_tri[o[0]] = 0;
    }
    // every later point is lexicographically larger than all before, hence outside their hull and
    // seeing an edge at the previous point
    int last = c;
    for (int j = k + 1; j < m; ++j) {
      const int q = o[j];
      int s = last, e = last;
      while (orient2d(p_[prev[s]], p_[s], p_[q]) < 0) s = prev[s];
      while (orient2d(p_[e], p_[next[e]], p_[q]) < 0) e = next[e];
      if (s == e) throw std::logic_error("facet triangulation: a new point sees no hull edge");
      int first = -1, before = -1;
      for (int u = s; u != e; u = next[u]) {
        const int ti = add(next[u], u, q);
        link_shared(ti, hull_tri[u]);
        if (before >= 0) link_shared(ti, before);
        if (first < 0) first = ti;
        before = ti;
      }
      next[s] = q, prev[q] = s, next[q] = e, prev[e] = q;
      hull_tri[s] = first, hull_tri[q] = before;
      last = q;
    }
    vt_.assign(static_cast<std::size_t>(m), -1);
    for (int ti = 0; ti < static_cast<int>(t.size()); ++ti)
      for (int v : t[ti].v) vt_[v] = ti;
    make_delaunay();
    return true;
  }

  /// Inserts polygon edge (u, w); false (and `problem`) if it crosses an earlier one or runs
  /// through a vertex.
  bool insert(int u, int w) {
    if (u == w) return true;
    const auto fan = around(u);
    for (int ti : fan) {
      const int i = index_of(ti, u);
      if (t[ti].v[nxt(i)] == w) return fix(ti, i), true;
      if (t[ti].v[prv(i)] == w) return fix(ti, prv(i)), true;
    }
    int start = -1, r = -1, l = -1;
    for (int ti : fan) {
      const int i = index_of(ti, u);
      const int a = t[ti].v[nxt(i)], b = t[ti].v[prv(i)];
      const int oa = orient2d(p_[u], p_[a], p_[w]), ob = orient2d(p_[u], p_[b], p_[w]);
      for (auto [x, ox] : {std::pair{a, oa}, std::pair{b, ob}})
        if (ox == 0 && lex_less(p_[u], p_[x]) == lex_less(p_[u], p_[w])) return on_edge(x, u, w);
      if (oa > 0 && ob < 0) {
        start = ti, r = a, l = b;
        break;
      }
    }
    if (start < 0) throw std::logic_error("facet triangulation: no triangle at a vertex contains the edge");
    std::vector<int> crossed{start}, left{l}, right{r};
    for (int cur = start;;) {
      const int e = edge_of(cur, r, l);
      if (t[cur].fixed >> e & 1) {
        problem = "its polygon edges " + id(u) + "-" + id(w) + " and " + id(r) + "-" + id(l) + " cross";
        return false;
      }
      const int nx = t[cur].n[e];
      if (nx < 0) throw std::logic_error("facet triangulation: an edge leaves the hull");
      crossed.push_back(nx);
      const int c = t[nx].v[prv(edge_of(nx, l, r))];
      if (c == w) break;
      const int oc = orient2d(p_[u], p_[w], p_[c]);
      if (oc == 0) return on_edge(c, u, w);
      if (oc > 0) left.push_back(c), l = c;
      else right.push_back(c), r = c;
      cur = nx;
    }
    // the cavity's boundary: edges of crossed triangles whose neighbour was not crossed
    struct side {
      int a, b, tri, edge;  // key a < b; triangle and edge (tri < 0: outside the hull)
      bool fixed;
    };
    std::vector<side> sides;
    std::sort(crossed.begin(), crossed.end());
    auto is_crossed = [&](int x) { return std::binary_search(crossed.begin(), crossed.end(), x); };
    for (int ti : crossed)
      for (int i = 0; i < 3; ++i)
        if (const int nb = t[ti].n[i]; nb < 0 || !is_crossed(nb)) {
          const int a = t[ti].v[i], b = t[ti].v[nxt(i)];
          sides.push_back({std::min(a, b), std::max(a, b), nb, nb < 0 ? -1 : edge_of(nb, a, b), (t[ti].fixed >> i & 1) != 0});
        }
    std::vector<std::array<int, 3>> fresh;
    pseudo_polygon(u, w, left, fresh);
    std::reverse(right.begin(), right.end());
    pseudo_polygon(w, u, right, fresh);
    if (fresh.size() != crossed.size()) throw std::logic_error("facet triangulation: cavity re-triangulation");
    for (std::size_t k = 0; k < fresh.size(); ++k) {
      t[crossed[k]] = triangle{fresh[k]};
      for (int v : fresh[k]) vt_[v] = crossed[k];
      for (int i = 0; i < 3; ++i) {
        const int a = fresh[k][i], b = fresh[k][nxt(i)];
        sides.push_back({std::min(a, b), std::max(a, b), crossed[k], i, false});
      }
    }
    // each key appears twice: new-new (inside the cavity, or u-w), new-old (the cavity's boundary)
    std::sort(sides.begin(), sides.end(), [](const side& x, const side& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
    for (std::size_t k = 0; k + 1 < sides.size(); k += 2) {
      const side &x = sides[k], &y = sides[k + 1];
      if (x.a != y.a || x.b != y.b) throw std::logic_error("facet triangulation: cavity edges do not match");
      const bool fx = x.fixed || y.fixed || (x.a == std::min(u, w) && x.b == std::max(u, w));
      for (const auto& [s1, s2] : {std::pair{x, y}, std::pair{y, x}})
        if (s1.tri >= 0) {
          auto& T = t[s1.tri];
          T.n[s1.edge] = s2.tri;
          T.fixed = static_cast<std::uint8_t>(fx ? T.fixed | 1u << s1.edge : T.fixed & ~(1u << s1.edge));
        }
    }
    return true;
  }

  /// Keeps the triangles enclosed by polygon edges and not reachable from a hole point.
  std::vector<char> inside(const std::vector<point2>& holes) const {
    std::vector<char> in(t.size(), 1);
    std::vector<int> stack;
    auto remove = [&](int ti) {
      if (in[ti]) in[ti] = 0, stack.push_back(ti);
    };
    for (int ti = 0; ti < static_cast<int>(t.size()); ++ti)
      for (int i = 0; i < 3; ++i)
        if (t[ti].n[i] < 0 && !(t[ti].fixed >> i & 1)) remove(ti);
    for (const auto& h : holes)
      for (int ti = 0; ti < static_cast<int>(t.size()); ++ti) {
        const auto& v = t[ti].v;
        if (orient2d(p_[v[0]], p_[v[1]], h) >= 0 && orient2d(p_[v[1]], p_[v[2]], h) >= 0 &&
            orient2d(p_[v[2]], p_[v[0]], h) >= 0) {
          remove(ti);
          break;
        }
      }
    while (!stack.empty()) {
      const int ti = stack.back();
      stack.pop_back();
      for (int i = 0; i < 3; ++i)
        if (const int nb = t[ti].n[i]; nb >= 0 && !(t[ti].fixed >> i & 1)) remove(nb);
    }
    return in;
  }

 private:
  std::vector<point2> p_;
  const std::vector<vertex_id>& ids_;
  std::vector<int> vt_;  // a triangle at each vertex

  std::string id(int local) const { return std::to_string(ids_[static_cast<std::size_t>(local)] + 1); }

  bool on_edge(int x, int u, int w) {
    problem = "vertex " + id(x) + " lies on its polygon edge " + id(u) + "-" + id(w);
    return false;
  }

  int add(int a, int b, int c) {
    t.push_back(triangle{{a, b, c}});
    return static_cast<int>(t.size()) - 1;
  }
  int index_of(int ti, int v) const {
    const auto& V = t[ti].v;
    return V[0] == v ? 0 : V[1] == v ? 1 : 2;
  }
  /// Edge of triangle ti with endpoints {a, b}.
  int edge_of(int ti, int a, int b) const {
    for (int i = 0; i < 3; ++i) {
      const int x = t[ti].v[i], y = t[ti].v[nxt(i)];
      if ((x == a && y == b) || (x == b && y == a)) return i;
    }
    throw std::logic_error("facet triangulation: edge not in triangle");
  }
  void link_shared(int x, int y) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (t[x].v[i] == t[y].v[nxt(j)] && t[x].v[nxt(i)] == t[y].v[j]) {
          t[x].n[i] = y, t[y].n[j] = x;
          return;
        }
    throw std::logic_error("facet triangulation: triangles share no edge");
  }
  void fix(int ti, int i) {
    t[ti].fixed = static_cast<std::uint8_t>(t[ti].fixed | 1u << i);
    if (const int nb = t[ti].n[i]; nb >= 0) {
      const int j = edge_of(nb, t[ti].v[i], t[ti].v[nxt(i)]);
      t[nb].fixed = static_cast<std::uint8_t>(t[nb].fixed | 1u << j);
    }
  }
  /// Triangles around vertex u, counter-clockwise (from the hull if u is on it).
  std::vector<int> around(int u) const {
    std::vector<int> out;
    const int t0 = vt_[u];
    int ti = t0;
    do {
      out.push_back(ti);
      ti = t[ti].n[prv(index_of(ti, u))];
    } while (ti >= 0 && ti != t0);
    if (ti < 0) {
      std::vector<int> back;
      for (ti = t[t0].n[index_of(t0, u)]; ti >= 0; ti = t[ti].n[index_of(ti, u)]) back.push_back(ti);
      out.insert(out.begin(), back.rbegin(), back.rend());
    }
    return out;
  }

  void make_delaunay() {
    std::vector<std::pair<int, int>> stack;
    for (int ti = 0; ti < static_cast<int>(t.size()); ++ti)
      for (int i = 0; i < 3; ++i)
        if (t[ti].n[i] > ti) stack.push_back({ti, i});
    while (!stack.empty()) {
      auto [ta, i] = stack.back();
      stack.pop_back();
      const int tb = t[ta].n[i];
      if (tb < 0) continue;
      const int a = t[ta].v[i], b = t[ta].v[nxt(i)], c = t[ta].v[prv(i)];
      const int j = edge_of(tb, a, b);
      const int d = t[tb].v[prv(j)];
      if (geometry::in_circle(p_[a], p_[b], p_[c], p_[d]) <= 0) continue;
      const int nbc = t[ta].n[nxt(i)], nca = t[ta].n[prv(i)], nad = t[tb].n[nxt(j)], ndb = t[tb].n[prv(j)];
      t[ta] = triangle{{a, d, c}, {nad, tb, nca}};
      t[tb] = triangle{{b, c, d}, {nbc, ta, ndb}};
      if (nad >= 0) t[nad].n[edge_of(nad, a, d)] = ta;
      if (nbc >= 0) t[nbc].n[edge_of(nbc, b, c)] = tb;
      vt_[a] = vt_[c] = ta, vt_[b] = vt_[d] = tb;
      stack.push_back({ta, 0}), stack.push_back({ta, 2}), stack.push_back({tb, 0}), stack.push_back({tb, 2});
    }
  }

  /// Triangulates the pseudo-polygon a, b, P[n-1], ..., P[0] (P from a to b, all left of a->b):
  /// the vertex of P whose circle through a and b holds no other is the apex of ab; recurse on
  /// both sides.
  void pseudo_polygon(int a, int b, const std::vector<int>& P, std::vector<std::array<int, 3>>& out) const {
    struct job {
      int a, b;
      std::size_t lo, hi;
    };
    std::vector<job> jobs{{a, b, 0, P.size()}};
    while (!jobs.empty()) {
      const job j = jobs.back();
      jobs.pop_back();
      if (j.lo == j.hi) continue;
      std::size_t c = j.lo;
      for (std::size_t i = j.lo + 1; i < j.hi; ++i)
        if (geometry::in_circle_perturbed(p_[j.a], p_[j.b], p_[P[c]], p_[P[i]]) > 0) c = i;
      out.push_back({j.a, j.b, P[c]});
      jobs.push_back({j.a, P[c], j.lo, c});
      jobs.push_back({P[c], j.b, c + 1, j.hi});
    }
  }
};

}  // namespace

facet_triangles triangulate_facet(const std::vector<point3>& points, const plc_facet& f) {
  facet_triangles out;
  std::vector<vertex_id> ids;
  for (const auto& poly : f.polygons) ids.insert(ids.end(), poly.begin(), poly.end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  if (ids.size() < 3) return out;
  // normal: Newell vector of the polygon of largest area (loops of one facet may be oriented
  // either way, so their sum could cancel)
  point3 normal{0, 0, 0};
  double best = 0;
  for (const auto& poly : f.polygons) {
    point3 n{0, 0, 0};
    for (std::size_t i = 0; i < poly.size() && poly.size() >= 3; ++i) {
      const point3 &a = points[poly[i]], &b = points[poly[(i + 1) % poly.size()]];
      n[0] += (a[1] - b[1]) * (a[2] + b[2]);
      n[1] += (a[2] - b[2]) * (a[0] + b[0]);
      n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    if (const double s = n[0] * n[0] + n[1] * n[1] + n[2] * n[2]; s > best) best = s, normal = n;
  }
  if (best == 0) return out;  // no polygon with area: the conformer reports it
  out.axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(normal[static_cast<std::size_t>(k)]) > std::abs(normal[static_cast<std::size_t>(out.axis)])) out.axis = k;
  std::vector<point2> proj;
  proj.reserve(ids.size());
  for (vertex_id v : ids) proj.push_back(geometry::project(points[v], out.axis));
  cdt T(std::move(proj), ids);
  if (!T.build()) {
    out.problem = std::move(T.problem);
    return out;
  }
  auto local = [&](vertex_id v) { return static_cast<int>(std::lower_bound(ids.begin(), ids.end(), v) - ids.begin()); };
  for (const auto& poly : f.polygons) {
    if (poly.size() < 2) continue;
    const std::size_t n = poly.size() == 2 ? 1 : poly.size();
    for (std::size_t i = 0; i < n; ++i)
      if (!T.insert(local(poly[i]), local(poly[(i + 1) % poly.size()]))) {
        out.problem = std::move(T.problem);
        return out;
      }
  }
  std::vector<point2> holes;
  for (const auto& h : f.holes) holes.push_back(geometry::project(h, out.axis));
  const auto in = T.inside(holes);
  for (std::size_t ti = 0; ti < T.t.size(); ++ti)
    if (in[ti]) {
      const auto& tr = T.t[ti];
      out.triangles.push_back({ids[static_cast<std::size_t>(tr.v[0])], ids[static_cast<std::size_t>(tr.v[1])],
                               ids[static_cast<std::size_t>(tr.v[2])]});
      out.polygon_edges.push_back(tr.fixed);
    }
  return out;
}

}  // namespace gsse::plc_check::detail
