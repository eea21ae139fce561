#pragma once
// The input facets (3D) or segments (2D) as the verifier sees them: plane, region, area, and a grid
// to find the facets near a point or box. Regions follow TetGen: the area enclosed by the facet's
// polygons minus what is reachable from its hole points. Polygons are taken as non-crossing loops
// (nested or side by side, boundaries may touch), so the part of the plane a point lies in is
// named by the innermost loop around it; a hole point removes that loop's direct interior (inside
// it, outside its children). Membership is decided by exact point-in-polygon in the projection
// that drops the facet normal's largest axis; areas and distances are measures, in double.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "gsse/container/plc.hpp"
#include "gsse/geometry/predicates.hpp"

namespace gsse::verify::detail {

namespace g = gsse::geometry;

/// A closed polygon of a facet (at least three corners), projected.
struct loop {
  std::vector<point2> p;  // projected corners
  std::vector<point3> q;  // the corners in 3D (distances)
  double area = 0;        // signed, in the projection
  point2 lo{}, hi{};
  int parent = -1;  // innermost loop that strictly contains it
  bool in = true;   // its direct interior belongs to the facet (no hole point in it)
};

/// +1 q strictly inside the loop, -1 strictly outside, 0 on its boundary (exact).
inline int point_in_loop(const loop& l, const point2& q) {
  if (q[0] < l.lo[0] || q[0] > l.hi[0] || q[1] < l.lo[1] || q[1] > l.hi[1]) return -1;
  bool inside = false;
  const std::size_t n = l.p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const point2 &a = l.p[i], &b = l.p[(i + 1) % n];
    const bool box = std::min(a[0], b[0]) <= q[0] && q[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= q[1] &&
                     q[1] <= std::max(a[1], b[1]);
    const bool straddles = (a[1] > q[1]) != (b[1] > q[1]);
    if (!box && !straddles) continue;
    const int o = g::orient2d(a, b, q);
    if (o == 0 && box) return 0;
    // the edge crosses the ray from q towards +x
    if (straddles && (o > 0) == (b[1] > a[1])) inside = !inside;
  }
  return inside ? 1 : -1;
}

/// Area of the intersection of two convex ccw polygons (Sutherland-Hodgman clip of `p` by `c`).
inline double convex_overlap(std::vector<point2> p, const std::array<point2, 3>& c) {
  std::vector<point2> out;
  for (std::size_t i = 0; i < 3 && p.size() >= 3; ++i) {
    const point2 &a = c[i], &b = c[(i + 1) % 3];
    auto side = [&](const point2& x) { return (b[0] - a[0]) * (x[1] - a[1]) - (b[1] - a[1]) * (x[0] - a[0]); };
    out.clear();
    for (std::size_t j = 0; j < p.size(); ++j) {
      const point2 &x = p[j], &y = p[(j + 1) % p.size()];
      const double sx = side(x), sy = side(y);
      if (sx >= 0) out.push_back(x);
      if ((sx > 0 && sy < 0) || (sx < 0 && sy > 0)) {
        const double w = sx / (sx - sy);
        out.push_back({x[0] + w * (y[0] - x[0]), x[1] + w * (y[1] - x[1])});
      }
    }
    p.swap(out);
  }
  // shoelace relative to a corner: absolute coordinates would cancel away a small polygon's area
  double a = 0;
  for (std::size_t i = 1; i + 1 < p.size(); ++i)
    a += (p[i][0] - p[0][0]) * (p[i + 1][1] - p[0][1]) - (p[i + 1][0] - p[0][0]) * (p[i][1] - p[0][1]);
  return p.size() >= 3 ? std::abs(a) / 2 : 0;
}

inline double distance_to_segment(const point3& p, const point3& a, const point3& b) {
  const point3 d = b - a;
  const double dd = dot(d, d);
  const double t = dd > 0 ? std::clamp(dot(p - a, d) / dd, 0.0, 1.0) : 0.0;
  return distance(p, a + t * d);
}

/// One input facet (3D: polygons of a plane; 2D: a segment).
template <std::size_t D>
struct facet_data {
  std::size_t line = 0;
  int marker = 0;
  bool usable = false;               // has area (length)
  bool planar = true;                // 3D: all corners exactly coplanar
  double deviation = 0;              // 3D: the largest distance of a corner from the plane (measured)
  std::array<point<D>, D> corner{};  // 3D: three non-collinear corners spanning the plane; 2D: the ends
  point<D> normal{};                 // unit
  int axis = 2;                      // 3D: the axis dropped by the projection
  double size = 0;                   // area (length), hole parts removed
  point<D> lo{}, hi{};               // bounding box
  std::vector<loop> loops;           // 3D
};

template <std::size_t D>
class facet_set {
 public:
  using pt = point<D>;

  facet_set(const plc<D>& p, double tol) : tol_(tol) {
    if constexpr (D == 3) {
      for (const auto& f : p.facets) facets_.push_back(prepare(p, f));
    } else {
      for (std::size_t i = 0; i < p.edges.size(); ++i) {
        facet_data<2> f;
        f.corner = {p.points[p.edges[i][0]], p.points[p.edges[i][1]]};
        f.marker = i < p.edge_markers.size() ? p.edge_markers[i] : 0;
        f.line = i + 1;
        f.size = distance(f.corner[0], f.corner[1]);
        f.usable = f.size > 0;
        if (f.usable) f.normal = {(f.corner[1][1] - f.corner[0][1]) / f.size, -(f.corner[1][0] - f.corner[0][0]) / f.size};
        for (std::size_t k = 0; k < 2; ++k)
          f.lo[k] = std::min(f.corner[0][k], f.corner[1][k]), f.hi[k] = std::max(f.corner[0][k], f.corner[1][k]);
        facets_.push_back(f);
      }
    }
    build_grid(p);
  }

  std::size_t size() const { return facets_.size(); }
  const facet_data<D>& operator[](std::size_t i) const { return facets_[i]; }
  std::string name(std::size_t i) const {
    return (D == 3 ? "facet " : "segment ") + std::to_string(i + 1) + (D == 3 ? " (line " + std::to_string(facets_[i].line) + ")" : "");
  }

  /// -1: x is off the plane (line) of facet f; 0: within the tolerance of it; +1: exactly on it.
  int on_plane(std::size_t i, const pt& x) const {
    const auto& f = facets_[i];
    if constexpr (D == 3) {
      if (f.planar && g::orient3d(f.corner[0], f.corner[1], f.corner[2], x) == 0) return 1;
    } else {
      if (g::orient2d(f.corner[0], f.corner[1], x) == 0) return 1;
    }
    return std::abs(dot(x - f.corner[0], f.normal)) <= tol_ ? 0 : -1;
  }

  /// Whether a face (its D vertices) lies in the plane of facet i closely enough for its shape:
  /// every vertex within `face_tilt` times the face's width (3D: its least altitude, twice its
  /// area over its longest edge; 2D: its length) of the plane, or within what the facet's own
  /// corners deviate and rounding allow (a point computed on a slanted facet is off it by up to
  /// a few thousand ulps of its coordinates, rounding_ulps). The tolerance of on_plane is a length
  /// of the model's scale: a face far smaller or thinner than it near a facet (a cell of 6e-8 next
  /// to a facet of 1e-4, a needle 4e-3 long and 6e-9 wide with a vertex 3e-9 off it, in a model 70
  /// across) would count as lying on it, and its cell as flat on it.
  bool face_in_plane(std::size_t i, const std::array<pt, D>& face) const {
    const auto& f = facets_[i];
    double longest = 0, far = 0, mag = 0;
    for (std::size_t k = 0; k < D; ++k) {
      longest = std::max(longest, distance(face[k], face[(k + 1) % D]));
      far = std::max(far, std::abs(dot(face[k] - f.corner[0], f.normal)));
      for (std::size_t a = 0; a < D; ++a) mag = std::max({mag, std::abs(face[k][a]), std::abs(f.corner[0][a])});
    }
    double width = longest;
    if constexpr (D == 3) {
      const point3 n = cross(face[1] - face[0], face[2] - face[0]);
      width = longest > 0 ? std::sqrt(dot(n, n)) / longest : 0;
    }
    constexpr double eps = std::numeric_limits<double>::epsilon();
    return far <= std::max(face_tilt * width, 2 * f.deviation + rounding_ulps * eps * mag);
  }
  // a face tilted out of the plane by less than this (over its width) lies flat in it: genuine
  // faces seen up to 3.1e-6 (GEB: a Steiner point 9.6e-14 off, the face 3.1e-8 wide), cells of
  // the conformer's that are not on the facet 0.5 and more (example010)
  static constexpr double face_tilt = 1e-5;
  // what a Steiner point computed on a slanted facet may be off its plane, in units of its
  // coordinates' magnitude: up to 2,900 ulps seen (a point 5.2e-12 off a needle facet at
  // coordinates 13, OpenSCAD's CSG-modules), 8192 allowed
  static constexpr double rounding_ulps = 8192;

  /// -1: x is not on facet f; 0: within the tolerance of its plane and in its region; +1: exactly
  /// on both; 2 (3D): on its plane (within the tolerance) but outside its region, within the
  /// tolerance of its edge.
  int on_facet(std::size_t i, const pt& x) const {
    const auto& f = facets_[i];
    for (std::size_t k = 0; k < D; ++k)
      if (x[k] < f.lo[k] - tol_ || x[k] > f.hi[k] + tol_) return -1;
    const int on = on_plane(i, x);
    if (on < 0) return -1;
    if constexpr (D == 3) {
      if (in_region(i, x)) return on;
      for (const auto& l : f.loops)  // a vertex rounded just off the region's edge
        for (std::size_t k = 0; k < l.q.size(); ++k)
          if (distance_to_segment(x, l.q[k], l.q[(k + 1) % l.q.size()]) <= tol_) return 2;
      return -1;
    } else {
      const bool between = f.lo[0] <= x[0] && x[0] <= f.hi[0] && f.lo[1] <= x[1] && x[1] <= f.hi[1];
      if (on == 1 && between) return 1;
      const point2 d = f.corner[1] - f.corner[0];
      const double t = std::clamp(dot(x - f.corner[0], d) / dot(d, d), 0.0, 1.0);
      return distance(x, f.corner[0] + t * d) <= tol_ ? 0 : -1;
    }
  }

  /// Whether the projection of x lies in the closed region of facet f (3D; exact).
  bool in_region(std::size_t i, const point3& x) const {
    const auto& f = facets_[i];
    const point2 q = g::project(x, f.axis);
    int innermost = -1;
    for (std::size_t k = 0; k < f.loops.size(); ++k) {
      const auto& l = f.loops[k];
      const int s = point_in_loop(l, q);
      if (s == 0 && (l.in || (l.parent >= 0 && f.loops[static_cast<std::size_t>(l.parent)].in))) return true;
      if (s > 0 && (innermost < 0 || std::abs(l.area) < std::abs(f.loops[static_cast<std::size_t>(innermost)].area)))
        innermost = static_cast<int>(k);
    }
    return innermost >= 0 && f.loops[static_cast<std::size_t>(innermost)].in;
  }

  /// Measure of the part of the face (D points) that lies in facet f's region: for a triangle, the
  /// area of its projection clipped to the region; for an edge, its overlap with the segment.
  double share(std::size_t i, const std::array<pt, D>& face) const {
    const auto& f = facets_[i];
    if constexpr (D == 2) {
      const point2 d = f.corner[1] - f.corner[0];
      const double dd = dot(d, d), s = dot(face[0] - f.corner[0], d) / dd, t = dot(face[1] - f.corner[0], d) / dd;
      return std::max(0.0, std::min(1.0, std::max(s, t)) - std::max(0.0, std::min(s, t))) * std::sqrt(dd);
    } else {
      std::array<point2, 3> t{g::project(face[0], f.axis), g::project(face[1], f.axis), g::project(face[2], f.axis)};
      const double a2 = (t[1][0] - t[0][0]) * (t[2][1] - t[0][1]) - (t[2][0] - t[0][0]) * (t[1][1] - t[0][1]);
      if (a2 == 0) return 0;
      if (a2 < 0) std::swap(t[1], t[2]);
      point2 lo = t[0], hi = t[0];
      for (const auto& x : t)
        for (std::size_t k = 0; k < 2; ++k) lo[k] = std::min(lo[k], x[k]), hi[k] = std::max(hi[k], x[k]);
      const point2 o{(t[0][0] + t[1][0] + t[2][0]) / 3, (t[0][1] + t[1][1] + t[2][1]) / 3};
      // region = sum over loops of (in(loop) - in(parent)) x inside(loop); inside(loop) as the
      // signed sum of the fan triangles (o, a, b) over its edges
      double total = 0;
      for (const auto& l : f.loops) {
        const int c = int(l.in) - int(l.parent >= 0 && f.loops[static_cast<std::size_t>(l.parent)].in);
        if (c == 0 || l.hi[0] < lo[0] || l.lo[0] > hi[0] || l.hi[1] < lo[1] || l.lo[1] > hi[1]) continue;
        double inside = 0;
        for (std::size_t k = 0; k < l.p.size(); ++k) {
          const point2 &a = l.p[k], &b = l.p[(k + 1) % l.p.size()];
          if (std::max({o[0], a[0], b[0]}) < lo[0] || std::min({o[0], a[0], b[0]}) > hi[0] ||
              std::max({o[1], a[1], b[1]}) < lo[1] || std::min({o[1], a[1], b[1]}) > hi[1])
            continue;
          const double s = (a[0] - o[0]) * (b[1] - o[1]) - (b[0] - o[0]) * (a[1] - o[1]);
          if (s == 0) continue;
          inside += (s > 0 ? 1 : -1) * convex_overlap(s > 0 ? std::vector<point2>{o, a, b} : std::vector<point2>{o, b, a}, t);
        }
        total += c * (l.area > 0 ? inside : -inside);
      }
      return std::max(0.0, total) / std::abs(f.normal[static_cast<std::size_t>(f.axis)]);
    }
  }

  /// A point inside facet f's region, off every loop (to ask whether any cell reaches the facet).
  std::optional<pt> sample(std::size_t i) const {
    const auto& f = facets_[i];
    if constexpr (D == 2) {
      return pt{(f.corner[0][0] + f.corner[1][0]) / 2, (f.corner[0][1] + f.corner[1][1]) / 2};
    } else {
      for (const auto& l : f.loops) {
        if (!l.in) continue;
        // the lexicographically smallest corner is convex: step from it into the loop
        std::size_t m = 0;
        for (std::size_t k = 1; k < l.p.size(); ++k)
          if (lex_less(l.p[k], l.p[m])) m = k;
        const point2 &v = l.p[m], &u = l.p[(m + l.p.size() - 1) % l.p.size()], &w = l.p[(m + 1) % l.p.size()];
        const point2 mid{(u[0] + w[0]) / 2 - v[0], (u[1] + w[1]) / 2 - v[1]};
        for (double t = 0.25; t > 1e-6; t /= 8) {
          const point2 q{v[0] + t * mid[0], v[1] + t * mid[1]};
          const point3 x = lift(f, q);
          bool on_loop = false;
          for (const auto& k : f.loops) on_loop = on_loop || point_in_loop(k, q) == 0;
          if (!on_loop && in_region(i, x)) return x;
        }
      }
      return std::nullopt;
    }
  }

  /// Calls fn(facet) for every usable facet whose box, grown by the tolerance, may meet [lo, hi]
  /// (each at most once, in increasing order).
  template <class F>
  void near(const pt& lo, const pt& hi, std::vector<std::uint32_t>& scratch, F&& fn) const {
    scratch.clear();
    for_cells(lo, hi, [&](std::size_t idx) {
      scratch.insert(scratch.end(), ids_.begin() + static_cast<std::ptrdiff_t>(start_[idx]),
                     ids_.begin() + static_cast<std::ptrdiff_t>(start_[idx + 1]));
    });
    std::sort(scratch.begin(), scratch.end());
    scratch.erase(std::unique(scratch.begin(), scratch.end()), scratch.end());
    for (auto f : scratch) {
      const auto& x = facets_[f];
      bool meets = true;
      for (std::size_t k = 0; k < D; ++k) meets = meets && x.lo[k] - tol_ <= hi[k] && lo[k] <= x.hi[k] + tol_;
      if (meets) fn(f);
    }
  }
  /// The same for one point: the facets of its grid cell (no duplicates there).
  template <class F>
  void near(const pt& x, F&& fn) const {
    std::size_t idx = 0;
    for (std::size_t k = D; k-- > 0;) idx = idx * n_[k] + cell_index(x, k);
    for (auto i = start_[idx]; i < start_[idx + 1]; ++i) fn(ids_[i]);
  }

  double tolerance() const { return tol_; }
  std::vector<std::string> warnings;

 private:
  static point3 lift(const facet_data<3>& f, const point2& q) {
    // the inverse of geometry::project, onto the facet's plane
    const auto ax = static_cast<std::size_t>(f.axis), u = (ax + 1) % 3, w = (ax + 2) % 3;
    point3 x{};
    x[u] = q[0];
    x[w] = q[1];
    const point3& a = f.corner[0];
    x[ax] = a[ax] - (f.normal[u] * (x[u] - a[u]) + f.normal[w] * (x[w] - a[w])) / f.normal[ax];
    return x;
  }

  facet_data<3> prepare(const plc<3>& p, const plc_facet& in) {
    facet_data<3> f;
    f.line = in.line;
    f.marker = in.marker;
    std::vector<vertex_id> vs;
    for (const auto& poly : in.polygons) vs.insert(vs.end(), poly.begin(), poly.end());
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    const std::string nm = "facet " + std::to_string(facets_.size() + 1) + " (line " + std::to_string(in.line) + ")";
    if (vs.empty()) {
      warnings.push_back(nm + " has no vertices");
      return f;
    }
    f.lo = f.hi = p.points[vs[0]];
    for (auto v : vs)
      for (std::size_t k = 0; k < 3; ++k) f.lo[k] = std::min(f.lo[k], p.points[v][k]), f.hi[k] = std::max(f.hi[k], p.points[v][k]);
    // plane through a corner, the corner farthest from it, and the corner making the largest triangle
    const point3& a = p.points[vs[0]];
    vertex_id q = vs[0], r = vs[0];
    for (auto v : vs)
      if (squared_distance(p.points[v], a) > squared_distance(p.points[q], a)) q = v;
    point3 n{};
    for (auto v : vs)
      if (const point3 c = cross(p.points[q] - a, p.points[v] - a); dot(c, c) > dot(n, n)) n = c, r = v;
    if (!(dot(n, n) > 0) || g::collinear(a, p.points[q], p.points[r])) {
      warnings.push_back(nm + " has no area");
      return f;
    }
    f.corner = {a, p.points[q], p.points[r]};
    f.normal = (1 / std::sqrt(dot(n, n))) * n;
    f.axis = g::dominant_axis(a, p.points[q], p.points[r]);
    for (auto v : vs) f.planar = f.planar && g::orient3d(f.corner[0], f.corner[1], f.corner[2], p.points[v]) == 0;
    if (!f.planar)
      for (auto v : vs) f.deviation = std::max(f.deviation, std::abs(dot(p.points[v] - a, f.normal)));
    for (const auto& poly : in.polygons) {
      if (poly.size() < 3) continue;  // embedded points and edges enclose nothing
      loop l;
      for (auto v : poly) {
        const point2 x = g::project(p.points[v], f.axis);
        if (!l.p.empty() && l.p.back() == x) continue;
        l.p.push_back(x);
        l.q.push_back(p.points[v]);
      }
      while (l.p.size() > 1 && l.p.back() == l.p.front()) l.p.pop_back(), l.q.pop_back();
      if (l.p.size() < 3) continue;
      l.lo = l.hi = l.p[0];
      for (std::size_t k = 0; k < l.p.size(); ++k) {
        const point2 &x = l.p[k], &y = l.p[(k + 1) % l.p.size()], &o = l.p[0];
        l.area += ((x[0] - o[0]) * (y[1] - o[1]) - (y[0] - o[0]) * (x[1] - o[1])) / 2;
        for (std::size_t c = 0; c < 2; ++c) l.lo[c] = std::min(l.lo[c], x[c]), l.hi[c] = std::max(l.hi[c], x[c]);
      }
      if (l.area != 0) f.loops.push_back(std::move(l));
    }
    // nesting: the parent of a loop is the smallest loop containing it
    for (std::size_t i = 0; i < f.loops.size(); ++i)
      for (std::size_t j = 0; j < f.loops.size(); ++j)
        if (i != j && inside(f.loops[i], f.loops[j], i > j)) {
          auto& par = f.loops[i].parent;
          if (par < 0 || std::abs(f.loops[j].area) < std::abs(f.loops[static_cast<std::size_t>(par)].area)) par = static_cast<int>(j);
        }
    // a hole point removes the direct interior of the innermost loop around it
    for (const auto& h : in.holes) {
      const point2 x = g::project(h, f.axis);
      int innermost = -1;
      for (std::size_t k = 0; k < f.loops.size(); ++k)
        if (point_in_loop(f.loops[k], x) > 0 &&
            (innermost < 0 || std::abs(f.loops[k].area) < std::abs(f.loops[static_cast<std::size_t>(innermost)].area)))
          innermost = static_cast<int>(k);
      if (innermost >= 0) f.loops[static_cast<std::size_t>(innermost)].in = false;
    }
    double area = 0;
    for (const auto& l : f.loops)
      area += (int(l.in) - int(l.parent >= 0 && f.loops[static_cast<std::size_t>(l.parent)].in)) * std::abs(l.area);
    f.size = area / std::abs(f.normal[static_cast<std::size_t>(f.axis)]);
    f.usable = f.size > 0;
    if (!f.usable) warnings.push_back(nm + " encloses no area");
    return f;
  }

  /// Whether loop a lies inside loop b (non-crossing loops): decided by a corner of a off b's
  /// boundary, else by an edge midpoint, else (the same loop twice) by `later`.
  static bool inside(const loop& a, const loop& b, bool later) {
    for (const auto& x : a.p)
      if (const int s = point_in_loop(b, x); s != 0) return s > 0;
    for (std::size_t k = 0; k < a.p.size(); ++k) {
      const point2 m{(a.p[k][0] + a.p[(k + 1) % a.p.size()][0]) / 2, (a.p[k][1] + a.p[(k + 1) % a.p.size()][1]) / 2};
      if (const int s = point_in_loop(b, m); s != 0) return s > 0;
    }
    return later;
  }

  std::size_t cell_index(const pt& x, std::size_t k) const {
    const double t = std::floor((x[k] - lo_[k]) * inv_[k]);
    return static_cast<std::size_t>(std::clamp(t, 0.0, static_cast<double>(n_[k] - 1)));
  }

  /// Calls fn(index) for the grid cells the box [lo, hi] meets.
  template <class F>
  void for_cells(const pt& lo, const pt& hi, F&& fn) const {
    std::array<std::size_t, D> a, b;
    for (std::size_t k = 0; k < D; ++k) a[k] = cell_index(lo, k), b[k] = cell_index(hi, k);
    auto c = a;
    for (;;) {
      std::size_t idx = 0;
      for (std::size_t k = D; k-- > 0;) idx = idx * n_[k] + c[k];
      fn(idx);
      std::size_t k = 0;
      while (k < D && ++c[k] > b[k]) c[k] = a[k], ++k;
      if (k == D) return;
    }
  }

  void build_grid(const plc<D>& p) {
    lo_ = hi_ = p.points.empty() ? pt{} : p.points[0];
    for (const auto& x : p.points)
      for (std::size_t k = 0; k < D; ++k) lo_[k] = std::min(lo_[k], x[k]), hi_[k] = std::max(hi_[k], x[k]);
    const double per_axis = D == 3 ? std::cbrt(static_cast<double>(facets_.size())) : std::sqrt(static_cast<double>(facets_.size()));
    std::size_t cells = 1;
    for (std::size_t k = 0; k < D; ++k) {
      n_[k] = static_cast<std::size_t>(std::clamp(2 * per_axis, 1.0, 64.0));
      const double w = hi_[k] > lo_[k] ? (hi_[k] - lo_[k]) / static_cast<double>(n_[k]) : 1;
      inv_[k] = 1 / w;
      cells *= n_[k];
    }
    std::vector<std::vector<std::uint32_t>> lists(cells);
    for (std::uint32_t i = 0; i < facets_.size(); ++i) {
      if (!facets_[i].usable) continue;
      pt lo = facets_[i].lo, hi = facets_[i].hi;
      for (std::size_t k = 0; k < D; ++k) lo[k] -= tol_, hi[k] += tol_;
      for_cells(lo, hi, [&](std::size_t idx) { lists[idx].push_back(i); });
    }
    start_.assign(cells + 1, 0);
    for (std::size_t c = 0; c < cells; ++c) start_[c + 1] = start_[c] + lists[c].size();
    for (const auto& l : lists) ids_.insert(ids_.end(), l.begin(), l.end());
  }

  double tol_;
  std::vector<facet_data<D>> facets_;
  pt lo_{}, hi_{}, inv_{};
  std::array<std::size_t, D> n_{};
  std::vector<std::size_t> start_;
  std::vector<std::uint32_t> ids_;
};

}  // namespace gsse::verify::detail
