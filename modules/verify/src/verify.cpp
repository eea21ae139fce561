#include "gsse/verify/verify.hpp"

#include <CGAL/Interval_nt.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <span>

#include "facets.hpp"
#include "gsse/container/union_find.hpp"
#include "gsse/geometry/exact_ball.hpp"
#include "gsse/geometry/point_grid.hpp"
#include "gsse/geometry/predicates.hpp"
#include "gsse/traversal/for_each.hpp"
#include "gsse/traversal/parallel_sort.hpp"

namespace gsse::verify {
namespace {

namespace g = gsse::geometry;
using detail::facet_set;

constexpr double rel_tol = 1e-9;          // facet coverage and volume
constexpr std::size_t examples = 3;       // offenders named per kind
constexpr std::size_t chunk = 4096;       // cells or vertices per parallel task

template <std::size_t D>
using cell_t = std::array<vertex_id, D + 1>;

std::string num(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}
template <std::size_t D>
std::string str(const point<D>& p) {
  std::string s = "(";
  for (std::size_t k = 0; k < D; ++k) s += (k ? ", " : "") + num(p[k]);
  return s + ")";
}

/// Offenders of one kind: how many, and the first few described.
struct tally {
  std::size_t n = 0;
  std::vector<std::string> named;
  template <class F>
  void add(F&& describe) {
    if (n++ < examples) named.push_back(describe());
  }
  void merge(const tally& t) {
    for (std::size_t i = 0; i < t.named.size() && named.size() < examples; ++i) named.push_back(t.named[i]);
    n += t.n;
  }
  void emit(report& r, std::size_t& count, const std::string& what) const {
    count = n;
    if (n == 0) return;
    std::string s = std::to_string(n) + " " + what;
    for (std::size_t i = 0; i < named.size(); ++i) s += (i ? "; " : ", e.g. ") + named[i];
    r.problems.push_back(std::move(s));
  }
};

/// Runs fn(begin, end, task) over [0, n) in tasks of `chunk`, on `threads` threads; results that
/// fn stores per task are merged by the caller in task order, so they do not depend on threads.
template <class F>
std::size_t in_tasks(unsigned threads, std::size_t n, F&& fn) {
  std::vector<std::size_t> tasks((n + chunk - 1) / chunk);
  std::iota(tasks.begin(), tasks.end(), std::size_t{0});
  gsse::for_each(execution::par(threads), tasks, [&](std::size_t t) { fn(t * chunk, std::min(n, (t + 1) * chunk), t); });
  return tasks.size();
}


template <std::size_t D>
int orientation(const std::array<point<D>, D + 1>& x) {
  if constexpr (D == 2)
    return g::orient2d(x[0], x[1], x[2]);
  else
    return g::orient3d(x[0], x[1], x[2], x[3]);
}

/// The faces of a positively oriented cell, opposite each vertex, listed outward (in 2D the
/// boundary edges counter-clockwise; in 3D the vertices turn clockwise seen from inside).
template <std::size_t D>
constexpr auto outward = [] {
  if constexpr (D == 2)
    return std::array<std::array<int, 2>, 3>{{{1, 2}, {2, 0}, {0, 1}}};
  else
    return std::array<std::array<int, 3>, 4>{{{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};
}();

/// The mesh flattened: every cell with its segment number.
template <std::size_t D>
struct mesh_view {
  const domain<D>& d;
  std::vector<cell_t<D>> cells;
  std::vector<int> number;
  std::vector<std::uint32_t> segment, local;
  const std::vector<point<D>>& p;

  explicit mesh_view(const domain<D>& m) : d(m), p(m.points()) {
    std::uint32_t s = 0;
    for (const auto& seg : m.segments()) {
      std::uint32_t k = 0;
      for (const auto& c : seg.cell_data()) {
        cells.push_back(c);
        number.push_back(seg.number());
        segment.push_back(s);
        local.push_back(k++);
      }
      ++s;
    }
  }
  std::array<point<D>, D + 1> corners(std::size_t c) const {
    std::array<point<D>, D + 1> x;
    for (std::size_t k = 0; k <= D; ++k) x[k] = p[cells[c][k]];
    return x;
  }
  std::string name(std::size_t c) const {
    std::string s = "cell " + std::to_string(local[c]) + " of segment '" + d.segments()[segment[c]].name() + "' (vertices";
    for (auto v : cells[c]) s += " " + std::to_string(v);
    return s + ")";
  }
  std::string vertex(vertex_id v) const { return "vertex " + std::to_string(v) + " " + str(p[v]); }
};

/// For every mesh vertex, the facets it lies on (CSR), each with whether exactly.
struct vertex_facets {
  std::vector<std::size_t> start;
  std::vector<std::pair<std::uint32_t, signed char>> list;  // (facet, facet_set::on_facet's answer)
  bool any(vertex_id v) const { return start[v] != start[v + 1]; }
  /// facet_set::on_facet's answer for v and f: -1 not on it, 0 within the tolerance, 1 exactly,
  /// 2 within the tolerance of its edge but outside its region (3D).
  int kind(vertex_id v, std::uint32_t f) const {
    for (auto k = start[v]; k < start[v + 1]; ++k)
      if (list[k].first == f) return list[k].second;
    return -1;
  }
  /// -1: v is not on facet f; 0: within the tolerance; 1: exactly.
  int on(vertex_id v, std::uint32_t f) const {
    const int k = kind(v, f);
    return k == 2 ? 0 : k;
  }
};

template <std::size_t D>
vertex_facets classify_vertices(const std::vector<point<D>>& p, const facet_set<D>& fs, unsigned threads) {
  std::vector<std::vector<std::tuple<vertex_id, std::uint32_t, signed char>>> found((p.size() + chunk - 1) / chunk);
  in_tasks(threads, p.size(), [&](std::size_t b, std::size_t e, std::size_t t) {
    for (std::size_t v = b; v < e; ++v)
      fs.near(p[v], [&](std::uint32_t f) {
        if (const int on = fs.on_facet(f, p[v]); on >= 0) found[t].emplace_back(static_cast<vertex_id>(v), f, static_cast<signed char>(on));
      });
  });
  vertex_facets vf;
  vf.start.assign(p.size() + 1, 0);
  for (const auto& l : found)
    for (const auto& [v, f, on] : l) {
      ++vf.start[v + 1];
      vf.list.emplace_back(f, on);
    }
  std::partial_sum(vf.start.begin(), vf.start.end(), vf.start.begin());
  return vf;
}

/// Where a face lies: on no facet; inside one; across coplanar facets of one marker; inside one
/// but for a sliver (a vertex rounded just off its edge); across facets of different markers.
enum class placement { off, inside, spanning, rounded, mixed_markers };

struct hit {
  std::uint32_t facet;
  double share;
  bool exact;
};

/// What rounding alone can make of a face's measure: its vertices are doubles, so one that should
/// lie on a slanted edge or line is off it by up to an ulp of its coordinates, and a clipped share
/// is off by that much times the face's perimeter (a thin face far from the origin: a sliver of
/// 1e-17 may be 1e-8 of its area). The relative tolerance alone would call such a face off its
/// facet; this is added to it (8 ulps of the largest coordinate along the perimeter).
template <std::size_t D>
double rounding_slack(const std::vector<point<D>>& p, const std::array<vertex_id, D>& v) {
  double mag = 0, perimeter = 0;
  for (std::size_t i = 0; i < D; ++i) {
    for (std::size_t k = 0; k < D; ++k) mag = std::max(mag, std::abs(p[v[i]][k]));
    if (D == 3 || i == 0) perimeter += distance(p[v[i]], p[v[(i + 1) % D]]);
  }
  constexpr double eps = std::numeric_limits<double>::epsilon();
  return D == 3 ? 8 * eps * mag * perimeter : 8 * eps * mag;
}

template <std::size_t D>
placement place(const facet_set<D>& fs, const vertex_facets& vf, const std::vector<point<D>>& p,
                const std::array<vertex_id, D>& v, double size, std::vector<hit>& hits, std::vector<std::uint32_t>& scratch) {
  const double slack = rel_tol * size + rounding_slack(p, v);
  hits.clear();
  for (auto x : v)
    if (!vf.any(x)) return placement::off;
  point<D> centre{};
  for (auto x : v) centre = centre + (1.0 / D) * p[x];
  std::array<point<D>, D> corners;
  for (std::size_t k = 0; k < D; ++k) corners[k] = p[v[k]];
  // one facet holding every vertex (and, in 3D, the centroid). `loose`: one that holds them only
  // with a vertex rounded off its region, just across its edge: used if the face does not split
  // into shares of coplanar facets (a face across the seam of two coplanar facets of one marker,
  // its vertex 1e-10 inside the neighbour, is that neighbour's share, not a rounding)
  std::vector<hit> loose;
  scratch.clear();
  for (auto x : v)
    for (auto k = vf.start[x]; k < vf.start[x + 1]; ++k) scratch.push_back(vf.list[k].first);
  std::sort(scratch.begin(), scratch.end());
  scratch.erase(std::unique(scratch.begin(), scratch.end()), scratch.end());
  for (auto f : scratch) {
    bool all = true, exact = true, off = false;
    for (auto x : v) {
      const int on = vf.kind(x, f);
      all = all && on >= 0;
      exact = exact && on == 1;
      off = off || on == 2;
    }
    if (!all) continue;
    if (!exact && !fs.face_in_plane(f, corners)) continue;
    if constexpr (D == 3)
      if (!fs.in_region(f, centre)) continue;
    (off ? loose : hits).push_back({f, size, exact});
  }
  auto inside = [&](std::vector<hit>& h) {
    if (std::any_of(h.begin(), h.end(), [](const hit& x) { return x.exact; }))
      std::erase_if(h, [](const hit& x) { return !x.exact; });
    return placement::inside;
  };
  if (!hits.empty()) return inside(hits);
  // coplanar facets sharing the face: their clipped shares must add up to it
  point<D> lo = p[v[0]], hi = lo;
  for (auto x : v)
    for (std::size_t k = 0; k < D; ++k) lo[k] = std::min(lo[k], p[x][k]), hi[k] = std::max(hi[k], p[x][k]);
  double covered = 0;
  fs.near(lo, hi, scratch, [&](std::uint32_t f) {
    bool exact = true;
    for (auto x : v) {
      int on = vf.on(x, f);
      if (on < 0) on = fs.on_plane(f, p[x]);
      if (on < 0) return;
      exact = exact && on == 1;
    }
    if (!exact && !fs.face_in_plane(f, corners)) return;
    // every share counts towards its facet's coverage (a face across the seam of a thin facet
    // has 1e-10 of its area there, which is all of that facet's coverage near it)
    if (const double s = fs.share(f, corners); s > 0) {
      hits.push_back({f, s, exact});
      covered += s;
    }
  });
  if (hits.empty() || std::abs(covered - size) > slack) {
    hits.clear();
    if (!loose.empty()) {
      hits = std::move(loose);
      return inside(hits);
    }
    return placement::off;
  }
  // but where the face lies is decided by its shares beyond rounding: a vertex rounded an ulp
  // across the common edge of two coplanar facets does not make the face span them
  std::size_t significant = 0;
  bool one_marker = true;
  int marker = 0;  // of the first share beyond rounding
  for (const auto& h : hits)
    if (h.share > slack) {
      if (significant++ == 0) marker = fs[h.facet].marker;
      one_marker = one_marker && fs[h.facet].marker == marker;
    }
  if (significant <= 1) return placement::rounded;
  return one_marker ? placement::spanning : placement::mixed_markers;
}

/// For each query point, the cells whose closure holds it (exact; positive cells only).
template <std::size_t D>
std::vector<std::vector<std::uint32_t>> locate(const mesh_view<D>& m, const std::vector<std::int8_t>& orient,
                                               const std::vector<point<D>>& q, unsigned threads) {
  std::vector<std::vector<std::uint32_t>> where(q.size());
  if (q.empty()) return where;
  std::vector<std::uint32_t> by_x(q.size());
  std::iota(by_x.begin(), by_x.end(), 0u);
  std::sort(by_x.begin(), by_x.end(), [&](auto a, auto b) { return q[a][0] < q[b][0]; });
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> found((m.cells.size() + chunk - 1) / chunk);
  in_tasks(threads, m.cells.size(), [&](std::size_t b, std::size_t e, std::size_t t) {
    for (std::size_t c = b; c < e; ++c) {
      if (orient[c] <= 0) continue;
      const auto x = m.corners(c);
      point<D> lo = x[0], hi = x[0];
      for (const auto& y : x)
        for (std::size_t k = 0; k < D; ++k) lo[k] = std::min(lo[k], y[k]), hi[k] = std::max(hi[k], y[k]);
      auto it = std::lower_bound(by_x.begin(), by_x.end(), lo[0], [&](std::uint32_t i, double v) { return q[i][0] < v; });
      for (; it != by_x.end() && q[*it][0] <= hi[0]; ++it) {
        const auto& y = q[*it];
        bool box = true;
        for (std::size_t k = 1; k < D; ++k) box = box && lo[k] <= y[k] && y[k] <= hi[k];
        bool in = box;
        for (std::size_t i = 0; i <= D && in; ++i) {
          auto z = x;
          z[i] = y;
          in = orientation<D>(z) >= 0;
        }
        if (in) found[t].emplace_back(*it, static_cast<std::uint32_t>(c));
      }
    }
  });
  for (const auto& l : found)
    for (auto [i, c] : l) where[i].push_back(c);
  return where;
}

/// A ball surely holding the circumsphere (circle) of the cell: interval arithmetic, or exact
/// rationals when the intervals cannot tell the cell from a flat one.
template <std::size_t D>
void circumball(const std::array<point<D>, D + 1>& x, point<D>& centre, double& radius) {
  {
    using I = CGAL::Interval_nt_advanced;
    CGAL::Protect_FPU_rounding<true> upward;
    std::array<I, D> rel;
    rel.fill(I(0));
    I den;
    if constexpr (D == 3) {
      std::array<I, 3> u, w, t;
      for (std::size_t k = 0; k < 3; ++k) u[k] = I(x[1][k]) - x[0][k], w[k] = I(x[2][k]) - x[0][k], t[k] = I(x[3][k]) - x[0][k];
      auto cr = [](const std::array<I, 3>& a, const std::array<I, 3>& b) {
        return std::array<I, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
      };
      auto dt = [](const std::array<I, 3>& a, const std::array<I, 3>& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
      const auto wt = cr(w, t), tu = cr(t, u), uw = cr(u, w);
      den = 2 * dt(u, wt);
      if (den.inf() > 0 || den.sup() < 0) {
        const I uu = dt(u, u), ww = dt(w, w), tt = dt(t, t);
        for (std::size_t k = 0; k < 3; ++k) rel[k] = (uu * wt[k] + ww * tu[k] + tt * uw[k]) / den;
      }
    } else {
      const I u0 = I(x[1][0]) - x[0][0], u1 = I(x[1][1]) - x[0][1], w0 = I(x[2][0]) - x[0][0], w1 = I(x[2][1]) - x[0][1];
      den = 2 * (u0 * w1 - u1 * w0);
      if (den.inf() > 0 || den.sup() < 0) {
        const I uu = u0 * u0 + u1 * u1, ww = w0 * w0 + w1 * w1;
        rel = {(w1 * uu - u1 * ww) / den, (u0 * ww - w0 * uu) / den};
      }
    }
    if (den.inf() > 0 || den.sup() < 0) {
      I r2 = 0, dev2 = 0;
      for (std::size_t k = 0; k < D; ++k) {
        const I c = rel[k] + x[0][k];
        r2 += rel[k] * rel[k];
        centre[k] = 0.5 * (c.inf() + c.sup());
        const double dev = std::max((I(c.sup()) - centre[k]).sup(), (I(centre[k]) - c.inf()).sup());
        dev2 += I(dev) * I(dev);
      }
      radius = (CGAL::sqrt(r2) + CGAL::sqrt(dev2)).sup();
      return;
    }
  }
  if constexpr (D == 3)
    g::exact_circumball(x[0], x[1], x[2], x[3], centre, radius);
  else
    g::exact_circumball(x[0], x[1], x[2], centre, radius);
}

struct delaunay_result {
  std::size_t ties = 0;
  long double deepest = 0;
  tally bad;
};

}  // namespace

template <std::size_t D>
report check(const domain<D>& d, const plc<D>& input, const options& o) {
  report r;
  const mesh_view<D> m(d);
  const auto& p = m.p;
  const std::size_t nc = m.cells.size();
  r.cells = nc;
  const unsigned threads = std::max(1u, o.threads);

  // ---- validity --------------------------------------------------------------------------
  tally bad_ids;
  for (std::size_t c = 0; c < nc; ++c)
    for (auto v : m.cells[c])
      if (v >= p.size()) bad_ids.add([&] { return m.name(c) + " names vertex " + std::to_string(v) + " of " + std::to_string(p.size()); });
  if (nc >= (std::size_t{1} << 32) / (D + 1)) throw std::length_error("gsse::verify: more than 2^32/(D+1) cells");
  bad_ids.emit(r, r.bad_vertex_ids, "cells name a vertex the mesh does not have");
  if (bad_ids.n) return r;  // nothing else can be checked safely

  std::vector<std::int8_t> orient(nc);
  in_tasks(threads, nc, [&](std::size_t b, std::size_t e, std::size_t) {
    for (std::size_t c = b; c < e; ++c) orient[c] = static_cast<std::int8_t>(orientation<D>(m.corners(c)));
  });
  tally inverted, degenerate;
  for (std::size_t c = 0; c < nc; ++c) {
    if (orient[c] < 0) inverted.add([&] { return m.name(c); });
    if (orient[c] == 0) degenerate.add([&] { return m.name(c); });
  }
  inverted.emit(r, r.inverted_cells, "cells are inverted (negative exact orientation)");
  degenerate.emit(r, r.degenerate_cells, "cells are degenerate (zero exact orientation)");

  std::vector<vertex_id> by_position(p.size());
  std::iota(by_position.begin(), by_position.end(), vertex_id{0});
  std::sort(by_position.begin(), by_position.end(), [&](auto a, auto b) { return p[a] < p[b] || (p[a] == p[b] && a < b); });
  tally duplicates, missing;
  for (std::size_t i = 1; i < by_position.size(); ++i)
    if (p[by_position[i]] == p[by_position[i - 1]])
      duplicates.add([&] { return m.vertex(by_position[i]) + " repeats vertex " + std::to_string(by_position[i - 1]); });
  for (std::size_t i = 0; i < input.points.size(); ++i) {
    const auto& x = input.points[i];
    auto it = std::lower_bound(by_position.begin(), by_position.end(), x, [&](vertex_id v, const point<D>& y) { return p[v] < y; });
    if (it == by_position.end() || p[*it] != x) missing.add([&] { return "PLC vertex " + std::to_string(i + 1) + " " + str(x); });
  }

  // faces: (sorted vertices, cell * (D+1) + opposite vertex), sorted
  struct face_rec {
    std::array<vertex_id, D> v;
    std::uint32_t owner;
  };
  // bucketed by their smallest vertex (counting sort, in cell order), each bucket sorted: small
  // sorts in cache instead of one sort of all faces
  std::vector<std::size_t> bucket(p.size() + 1, 0);
  auto face_of = [&](std::size_t c, std::size_t i) {
    face_rec f;
    for (std::size_t k = 0; k < D; ++k) f.v[k] = m.cells[c][static_cast<std::size_t>(outward<D>[i][k])];
    std::sort(f.v.begin(), f.v.end());
    f.owner = static_cast<std::uint32_t>(c * (D + 1) + i);
    return f;
  };
  for (const auto& c : m.cells) {
    for (std::size_t i = 0; i <= D; ++i) {  // the smallest vertex of the face opposite vertex i
      vertex_id low = ~vertex_id{0};
      for (std::size_t k = 0; k <= D; ++k)
        if (k != i) low = std::min(low, c[k]);
      ++bucket[low + 1];
    }
  }
  std::partial_sum(bucket.begin(), bucket.end(), bucket.begin());
  std::vector<face_rec> faces(nc * (D + 1));
  {
    auto fill = bucket;
    for (std::size_t c = 0; c < nc; ++c)
      for (std::size_t i = 0; i <= D; ++i) {
        const auto f = face_of(c, i);
        faces[fill[f.v[0]]++] = f;
      }
  }
  in_tasks(threads, p.size(), [&](std::size_t b, std::size_t e, std::size_t) {
    for (std::size_t v = b; v < e; ++v)
      std::sort(faces.begin() + static_cast<std::ptrdiff_t>(bucket[v]), faces.begin() + static_cast<std::ptrdiff_t>(bucket[v + 1]),
                [](const face_rec& x, const face_rec& y) { return x.v < y.v || (x.v == y.v && x.owner < y.owner); });
  });

  // ---- conformity ------------------------------------------------------------------------
  point<D> lo{}, hi{};
  if (!input.points.empty()) lo = hi = input.points[0];
  for (const auto& x : input.points)
    for (std::size_t k = 0; k < D; ++k) lo[k] = std::min(lo[k], x[k]), hi[k] = std::max(hi[k], x[k]);
  const double tol = o.facet_tolerance * distance(lo, hi);
  const point<D> origin = 0.5 * (lo + hi);
  const facet_set<D> fs(input, tol);
  const auto vf = classify_vertices(p, fs, threads);

  struct coverage {
    double all = 0, hull_plus = 0, hull_minus = 0, hull_flux = 0;
    double slack = 0;  // the rounding slack of the faces on it (rounding_slack)
  };
  std::vector<coverage> cov(fs.size());
  gsse::union_find<> uf(nc);
  tally nonmanifold, folded, off_facet, mixed_markers;
  double off_facet_flux = 0;
  std::vector<hit> hits;
  std::vector<std::uint32_t> scratch;
  auto face_name = [&](const std::array<vertex_id, D>& v) {
    std::string s = D == 3 ? "face" : "edge";
    for (auto x : v) s += " " + std::to_string(x);
    return s;
  };
  auto oriented = [&](std::uint32_t owner) {  // the face outward from its cell
    const std::size_t c = owner / (D + 1), i = owner % (D + 1);
    std::array<vertex_id, D> v;
    for (std::size_t k = 0; k < D; ++k) v[k] = m.cells[c][static_cast<std::size_t>(outward<D>[i][k])];
    return v;
  };
  auto odd = [](const std::array<vertex_id, D>& v) {
    int inv = 0;
    for (std::size_t i = 0; i < D; ++i)
      for (std::size_t j = i + 1; j < D; ++j) inv += v[i] > v[j];
    return inv % 2 == 1;
  };
  for (std::size_t i = 0, j; i < faces.size(); i = j) {
    for (j = i + 1; j < faces.size() && faces[j].v == faces[i].v;) ++j;
    const auto& v = faces[i].v;
    ++r.faces;
    const std::uint32_t c0 = faces[i].owner / (D + 1);
    if (j - i > 2) {
      nonmanifold.add([&] { return face_name(v) + " of " + std::to_string(j - i) + " cells, e.g. " + m.name(c0); });
      continue;
    }
    const bool hull = j - i == 1;
    const std::uint32_t c1 = hull ? c0 : faces[i + 1].owner / (D + 1);
    if (!hull && orient[c0] > 0 && orient[c1] > 0 && odd(oriented(faces[i].owner)) == odd(oriented(faces[i + 1].owner)))
      folded.add([&] { return face_name(v) + ": " + m.name(c0) + " and " + m.name(c1) + " lie on the same side"; });
    const bool bounding = hull || m.number[c0] != m.number[c1];
    if (!bounding && std::any_of(v.begin(), v.end(), [&](vertex_id x) { return !vf.any(x); })) {
      uf.unite(c0, c1);  // a vertex on no facet: the face is on none
      continue;
    }
    // outward size vector of the face (from c0); flux = divergence-theorem volume term
    const auto ov = oriented(faces[i].owner);
    point<D> sv;
    if constexpr (D == 3)
      sv = 0.5 * cross(p[ov[1]] - p[ov[0]], p[ov[2]] - p[ov[0]]);
    else
      sv = {p[ov[1]][1] - p[ov[0]][1], p[ov[0]][0] - p[ov[1]][0]};
    point<D> centre{};
    for (auto x : v) centre = centre + (1.0 / D) * p[x];
    const double size = std::sqrt(dot(sv, sv)), flux = dot(centre - origin, sv) / D;
    const placement pl = place(fs, vf, p, v, size, hits, scratch);
    const bool on = pl != placement::off;
    const double face_slack = hits.empty() ? 0 : rounding_slack(p, v);
    for (const auto& h : hits) {
      auto& cv = cov[h.facet];
      cv.all += h.share;
      cv.slack += face_slack;
      if (hull) {
        (dot(sv, fs[h.facet].normal) > 0 ? cv.hull_plus : cv.hull_minus) += h.share;
        cv.hull_flux += size > 0 ? flux * h.share / size : 0;
      }
    }
    r.hull_faces += hull;
    r.interface_faces += !hull && bounding;
    auto describe = [&] {
      std::string s = face_name(v) + (hull ? " (hull face of " + m.name(c0) + ")"
                                           : " (between segments " + std::to_string(m.number[c0]) + " and " +
                                                 std::to_string(m.number[c1]) + ", " + m.name(c0) + ")");
      for (const auto& h : hits) s += ", " + fs.name(h.facet) + " marker " + std::to_string(fs[h.facet].marker);
      return s;
    };
    if (bounding && !on) off_facet.add(describe);
    if (bounding && on && std::none_of(hits.begin(), hits.end(), [](const hit& h) { return h.exact; })) ++r.inexact_faces;
    if (pl == placement::spanning) ++r.spanning_faces;
    if (pl == placement::mixed_markers) mixed_markers.add(describe);
    if (hull && !on) off_facet_flux += flux;
    if (!hull && !on) uf.unite(c0, c1);
  }
  nonmanifold.emit(r, r.nonmanifold_faces, std::string(D == 3 ? "faces" : "edges") + " are shared by more than two cells");
  folded.emit(r, r.folded_faces, std::string(D == 3 ? "faces" : "edges") + " have both their cells on one side");
  duplicates.emit(r, r.duplicate_vertices, "vertices repeat the position of another");
  missing.emit(r, r.missing_plc_vertices, "PLC vertices are not mesh vertices");
  off_facet.emit(r, r.off_facet_faces,
                 std::string(D == 3 ? "hull/interface faces lie on no input facet" : "hull/interface edges lie on no input segment"));
  mixed_markers.emit(r, r.mixed_marker_faces,
                     std::string(D == 3 ? "faces span coplanar facets" : "edges span collinear segments") + " of different markers");

  // facet coverage; a facet with no face on it must lie where no cell reaches (in a hole)
  tally uncovered, overcovered;
  std::vector<std::uint32_t> bare;
  std::vector<point<D>> probes;
  for (std::uint32_t f = 0; f < fs.size(); ++f) {
    if (!fs[f].usable) continue;
    const double area = fs[f].size, got = cov[f].all;
    if (std::abs(got - area) <= rel_tol * area + cov[f].slack) continue;
    if (got == 0 && !input.holes.empty()) {  // without hole points every facet bounds a meshed region
      if (const auto x = fs.sample(f)) {
        bare.push_back(f);
        probes.push_back(*x);
        continue;
      }
    }
    (got > area ? overcovered : uncovered).add([&] {
      return fs.name(f) + ": " + (D == 3 ? "area " : "length ") + num(area) + ", faces on it " + num(got);
    });
  }
  if (!probes.empty()) {
    const auto where = locate(m, orient, probes, threads);
    for (std::size_t k = 0; k < bare.size(); ++k) {
      if (where[k].empty()) {
        ++r.facets_in_holes;
        continue;
      }
      uncovered.add([&] { return fs.name(bare[k]) + " has no face on it, but " + m.name(where[k][0]) + " holds its point " + str(probes[k]); });
    }
  }
  uncovered.emit(r, r.uncovered_facets, std::string(D == 3 ? "facets" : "segments") + " are not covered by the faces on them");
  overcovered.emit(r, r.overcovered_facets,
                   std::string(D == 3 ? "facets" : "segments") + " are covered more than once by the faces on them (overlapping or flat cells)");

  // volume: the cells against the divergence theorem over the PLC's hull facets
  // compensated (Neumaier) sum: a plain sum of 1e5-1e6 cell volumes drifts by some 1e-12 of the
  // total, the order of the error this check should see
  double plc_volume = off_facet_flux, cell_volume = 0, carry = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    const auto x = m.corners(c);
    double v;
    if constexpr (D == 3)
      v = std::abs(dot(x[1] - x[0], cross(x[2] - x[0], x[3] - x[0]))) / 6;
    else
      v = std::abs((x[1][0] - x[0][0]) * (x[2][1] - x[0][1]) - (x[2][0] - x[0][0]) * (x[1][1] - x[0][1])) / 2;
    const double t = cell_volume + v;
    carry += std::abs(cell_volume) >= std::abs(v) ? (cell_volume - t) + v : (v - t) + cell_volume;
    cell_volume = t;
  }
  cell_volume += carry;
  for (std::size_t f = 0; f < fs.size(); ++f) {
    const auto& cv = cov[f];
    const double hull = cv.hull_plus + cv.hull_minus;
    if (hull == 0) continue;
    if ((cv.hull_plus == 0 || cv.hull_minus == 0) && std::abs(hull - fs[f].size) <= rel_tol * fs[f].size + cv.slack)
      plc_volume += (cv.hull_plus > 0 ? 1 : -1) * dot(fs[f].corner[0] - origin, fs[f].normal) * fs[f].size / D;
    else
      plc_volume += cv.hull_flux;
  }
  r.volume_error = plc_volume != 0 ? std::abs(cell_volume - plc_volume) / std::abs(plc_volume) : (cell_volume != 0 ? 1 : 0);
  if (r.volume_error > rel_tol) {
    r.volume_mismatch = 1;
    r.problems.push_back(std::string(D == 3 ? "volume" : "area") + " of the cells " + num(cell_volume) + " differs from the " +
                         num(plc_volume) + " bounded by the PLC (relative error " + num(r.volume_error) + ")");
  }

  // ---- labels ----------------------------------------------------------------------------
  std::vector<std::int64_t> comp_of_root(nc, -1);
  std::vector<std::uint32_t> comp(nc);
  std::vector<int> comp_number;
  std::vector<char> comp_mixed;
  tally mixed;
  for (std::size_t c = 0; c < nc; ++c) {
    const auto root = uf.find(static_cast<std::uint32_t>(c));
    if (comp_of_root[root] < 0) {
      comp_of_root[root] = static_cast<std::int64_t>(comp_number.size());
      comp_number.push_back(m.number[c]);
      comp_mixed.push_back(0);
    }
    const auto k = comp[c] = static_cast<std::uint32_t>(comp_of_root[root]);
    if (m.number[c] != comp_number[k] && !comp_mixed[k]) {
      comp_mixed[k] = 1;
      mixed.add([&] { return "segments " + std::to_string(comp_number[k]) + " and " + std::to_string(m.number[c]) + " at " + m.name(c); });
    }
  }
  r.components = comp_number.size();
  mixed.emit(r, r.mixed_components, "components (cells joined across faces on no facet) carry more than one segment number");
  std::vector<point<D>> queries;
  for (const auto& x : input.regions) queries.push_back(x.at);
  queries.insert(queries.end(), input.holes.begin(), input.holes.end());
  const auto where = locate(m, orient, queries, threads);
  tally misplaced, meshed_holes;
  for (std::size_t i = 0; i < input.regions.size(); ++i) {
    const auto& x = input.regions[i];
    const std::string nm = "region point " + std::to_string(i + 1) + " (number " + std::to_string(x.number) + ") " + str(x.at);
    if (where[i].empty()) misplaced.add([&] { return nm + " lies in no cell"; });
    for (auto c : where[i])
      if (comp_number[comp[c]] != x.number) {
        misplaced.add([&] { return nm + " lies in " + m.name(c) + ", of a component of segment " + std::to_string(comp_number[comp[c]]); });
        break;
      }
  }
  for (std::size_t i = 0; i < input.holes.size(); ++i)
    if (const auto& w = where[input.regions.size() + i]; !w.empty())
      meshed_holes.add([&] { return "hole point " + std::to_string(i + 1) + " " + str(input.holes[i]) + " lies in " + m.name(w[0]); });
  misplaced.emit(r, r.misplaced_region_points, "region points lie in no cell or in a component of another segment number");
  meshed_holes.emit(r, r.meshed_hole_points, "hole points lie in a cell");

  // ---- Delaunay --------------------------------------------------------------------------
  if (o.delaunay && nc) {
    // nested where points crowd (a uniform grid read 12 s on a CAD hammer's 69k points)
    const geometry::point_grid<D> grid{std::span<const point<D>>(p)};
    std::vector<delaunay_result> res((nc + chunk - 1) / chunk);
    in_tasks(threads, nc, [&](std::size_t b, std::size_t e, std::size_t t) {
      auto& out = res[t];
      for (std::size_t c = b; c < e; ++c) {
        if (orient[c] <= 0) continue;
        const auto x = m.corners(c);
        const auto& cv = m.cells[c];
        point<D> centre;
        double radius;
        circumball<D>(x, centre, radius);
        const double r2 = radius * radius * (1 + 1e-9);
        long double R2 = 0;
        for (std::size_t k = 0; k < D; ++k) R2 += static_cast<long double>(x[0][k] - centre[k]) * (x[0][k] - centre[k]);
        vertex_id inside = no_cell;
        // cells within the padded radius: the grid pads its cells by 1e-10 of its extent only, too
        // little against rounding in (r + pad)^2 for a ball much larger than the mesh
        grid.visit_ball(centre, radius * (1 + 1e-9), [&](vertex_id y, const point<D>& q) {
          if (std::find(cv.begin(), cv.end(), y) != cv.end()) return true;
          if (squared_distance(q, centre) > r2) return true;  // outside the enclosing ball: outside the sphere
          int s;
          if constexpr (D == 3)
            s = g::in_sphere(x[0], x[1], x[2], x[3], q);
          else
            s = g::in_circle(x[0], x[1], x[2], q);
          if (s == 0) ++out.ties;
          if (s <= 0) return true;
          long double d2 = 0;
          for (std::size_t k = 0; k < D; ++k) d2 += static_cast<long double>(q[k] - centre[k]) * (q[k] - centre[k]);
          if (R2 > 0) out.deepest = std::max(out.deepest, (R2 - d2) / R2);
          if (inside == no_cell || y < inside) inside = y;
          return true;
        });
        if (inside != no_cell) out.bad.add([&] { return m.name(c) + " has " + m.vertex(inside) + " inside its circumsphere"; });
      }
    });
    delaunay_result all;
    for (const auto& x : res) {
      all.ties += x.ties;
      all.deepest = std::max(all.deepest, x.deepest);
      all.bad.merge(x.bad);
    }
    r.delaunay_ties = all.ties;
    r.deepest_delaunay = static_cast<double>(all.deepest);
    all.bad.emit(r, r.non_delaunay_cells,
                 "cells have a vertex strictly inside their circumsphere (deepest " + num(r.deepest_delaunay) + " of R^2)");
  }
  return r;
}

template report check<2>(const domain<2>&, const plc<2>&, const options&);
template report check<3>(const domain<3>&, const plc<3>&, const options&);

}  // namespace gsse::verify
