#pragma once
// Geometry kernels of the gift-wrapping front: the exact decisions (side of a face, "y beats x":
// y lies in the perturbed circumball of face+x) and the double constructions used only to bound
// the search region. A kernel provides:
//   dim, grid_dim, face (std::array<vertex_id, dim>)
//   strict()            true if "beats" is a strict order (exact perturbed balls)
//   side(f, y)          +1 if y lies on the inner (positive) side of oriented face f
//   beats(f, x, y)      true if y is inside the perturbed circumball of f+x (side(f,x) > 0)
//   ball(f, x, c, r)    centre and radius in grid coordinates of a ball containing that
//                       circumball (the projection of a ball is inside the projected ball);
//                       constructed exactly when the double construction is unreliable (a
//                       nearly flat simplex); false only if it overflows
//   prepare(f) -> probe double data of f: circumcentre cc, unit normal n, squared circumradius
//                       r2, longest edge l, tilt (a bound on the angle error of n);
//                       estimate(probe, q): the "Delaunay distance" of a point (offset of the
//                       circumcentre of f+q along f's normal; +inf behind f), a ranking hint
//                       only: every decision is confirmed exactly
//   grid_coord(v)       grid coordinates of vertex v
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>

#include "gsse/geometry/circumcentre.hpp"
#include "gsse/geometry/exact_ball.hpp"
#include "gsse/geometry/predicates.hpp"
#include "gsse/geometry/point_grid.hpp"

namespace gsse::front {

using geometry::point_grid;  // the candidate index (gsse/geometry/point_grid.hpp)

namespace detail {
inline constexpr double eps = std::numeric_limits<double>::epsilon();
// Relative error budget of a double circumcentre: beyond this the box is not trusted.
inline constexpr double max_relative_error = 1e-6;
/// Radius of a ball that surely contains the exact circumball, given the double radius, the
/// relative error bound of the centre construction and the longest edge.
inline double padded(double r, double rel, double edge) { return r * (1 + 4 * rel + 1e-12) + 4 * rel * edge + 1e-300; }
/// The ball (centre, r) grown by what rounding of coordinates of the centre's magnitude can do to
/// the double distance tests against it (|q - centre|^2 <= r^2 with q near the ball): a small
/// ball far from the origin (a thin layer 1e-5 thick at coordinate 0.5) would otherwise leave out
/// a cocircular vertex that its exact, perturbed test must see.
template <class C>
inline double rounding_padded(const C& centre, double r) {
  double m = 0;
  for (double x : centre) m = std::max(m, std::abs(x));
  return r + 16 * eps * (m + r);
}
}  // namespace detail

/// Tetrahedra in 3D.
struct volume_kernel {
  static constexpr std::size_t dim = 3, grid_dim = 3;
  using face = std::array<vertex_id, 3>;
  using coord = std::array<double, 3>;
  std::span<const point3> p;

  bool strict() const { return true; }
  int side(const face& f, vertex_id y) const { return geometry::orient3d(p[f[0]], p[f[1]], p[f[2]], p[y]); }
  bool beats(const face& f, vertex_id x, vertex_id y) const {
    return geometry::in_sphere_perturbed(p[f[0]], p[f[1]], p[f[2]], p[x], p[y]) > 0;
  }
  coord grid_coord(vertex_id v) const { return p[v]; }
  const point3& grid_coord_ref(vertex_id v) const { return p[v]; }
  bool ball(const face& f, vertex_id x, coord& centre, double& r) const {
    const bool ok = ball_unpadded(f, x, centre, r);
    r = detail::rounding_padded(centre, r);
    return ok && std::isfinite(r);
  }
  bool ball_unpadded(const face& f, vertex_id x, coord& centre, double& r) const {
    const point3& a = p[f[0]];
    const point3 u = p[f[1]] - a, v = p[f[2]] - a, w = p[x] - a;
    double det;
    const point3 c = geometry::tetrahedron_circumcentre_offset(u, v, w, det);
    const double scale = std::sqrt(dot(u, u) * dot(v, v) * dot(w, w));
    const double rel = det == 0 ? 1.0 : scale / std::abs(det) * detail::eps * 64;
    if (rel > detail::max_relative_error) {  // nearly flat: construct exactly, round outward
      geometry::exact_circumball(a, p[f[1]], p[f[2]], p[x], centre, r);
      return std::isfinite(r);
    }
    r = detail::padded(std::sqrt(dot(c, c)), rel, std::sqrt(std::max({dot(u, u), dot(v, v), dot(w, w)})));
    centre = a + c;
    return true;
  }
  struct probe {
    point3 cc, n;
    double r2, l, tilt;  // tilt: bound on the direction error of n (radians)
  };
  probe prepare(const face& f) const {
    const point3& a = p[f[0]];
    const point3 u = p[f[1]] - a, v = p[f[2]] - a;
    const point3 n = cross(u, v);
    const double nn = dot(n, n);
    const point3 c = geometry::triangle_circumcentre_offset(u, v, n, nn);
    const double l = std::sqrt(std::max({dot(u, u), dot(v, v), squared_distance(p[f[1]], p[f[2]])}));
    return {a + c, (1.0 / std::sqrt(nn)) * n, dot(c, c), l, 64 * detail::eps * l * l / std::sqrt(nn)};
  }
  static double estimate(const probe& pr, const coord& q) {
    const point3 d = q - pr.cc;
    const double h = dot(d, pr.n);
    return h > 0 ? (dot(d, d) - pr.r2) / (2 * h) : std::numeric_limits<double>::infinity();
  }
};

/// Ranking hint of an edge front (2D grids): the edge's midpoint, left unit normal, squared half
/// length, length and direction error bound, in grid coordinates.
struct edge_probe {
  point2 cc, n;
  double r2, l, tilt;
  static edge_probe of(const point2& a, const point2& b) {
    const double l = distance(a, b);
    return {0.5 * (a + b), {-(b[1] - a[1]) / l, (b[0] - a[0]) / l}, 0.25 * l * l, l, 64 * detail::eps};
  }
  static double estimate(const edge_probe& pr, const std::array<double, 2>& q) {
    const point2 d = q - pr.cc;
    const double h = dot(d, pr.n);
    return h > 0 ? (dot(d, d) - pr.r2) / (2 * h) : std::numeric_limits<double>::infinity();
  }
};

/// Triangles in 2D.
struct plane_kernel {
  static constexpr std::size_t dim = 2, grid_dim = 2;
  using face = std::array<vertex_id, 2>;
  using coord = std::array<double, 2>;
  std::span<const point2> p;

  bool strict() const { return true; }
  int side(const face& f, vertex_id y) const { return geometry::orient2d(p[f[0]], p[f[1]], p[y]); }
  bool beats(const face& f, vertex_id x, vertex_id y) const {
    return geometry::in_circle_perturbed(p[f[0]], p[f[1]], p[x], p[y]) > 0;
  }
  coord grid_coord(vertex_id v) const { return p[v]; }
  const point2& grid_coord_ref(vertex_id v) const { return p[v]; }
  bool ball(const face& f, vertex_id x, coord& centre, double& r) const {
    const bool ok = ball_unpadded(f, x, centre, r);
    r = detail::rounding_padded(centre, r);
    return ok && std::isfinite(r);
  }
  bool ball_unpadded(const face& f, vertex_id x, coord& centre, double& r) const {
    const point2& a = p[f[0]];
    const point2 u = p[f[1]] - a, v = p[x] - a;
    double d;
    const point2 c = geometry::plane_circumcentre_offset(u, v, d);
    const double scale = std::sqrt(dot(u, u) * dot(v, v));
    const double rel = d == 0 ? 1.0 : scale / std::abs(d) * detail::eps * 64;
    if (rel > detail::max_relative_error) {
      geometry::exact_circumball(a, p[f[1]], p[x], centre, r);
      return std::isfinite(r);
    }
    r = detail::padded(std::sqrt(dot(c, c)), rel, std::sqrt(std::max(dot(u, u), dot(v, v))));
    centre = a + c;
    return true;
  }
  using probe = edge_probe;
  probe prepare(const face& f) const { return edge_probe::of(p[f[0]], p[f[1]]); }
  static double estimate(const probe& pr, const coord& q) { return edge_probe::estimate(pr, q); }
};

/// Points of a facet known to lie on one PLC edge: on a slanted edge its split points are on the
/// line only up to rounding, and exact orientations would see a zig-zag whose outward corners are
/// ears of zero area. Three points of one edge are collinear by definition.
struct facet_lines {
  std::span<const std::uint32_t> edge_of;      // per point: 1 + the edge whose interior it lies on, or 0
  std::span<const std::array<vertex_id, 2>> ends;  // per edge: its end vertices
  bool on(vertex_id v, std::uint32_t e) const {
    return edge_of[v] == e + 1 || ends[e][0] == v || ends[e][1] == v;
  }
  /// True if a, b and c lie on one edge (at least one of them inside it).
  bool collinear(vertex_id a, vertex_id b, vertex_id c) const {
    for (vertex_id v : {a, b, c})
      if (const auto e = edge_of[v]; e != 0) return on(a, e - 1) && on(b, e - 1) && on(c, e - 1);
    return false;
  }
};

/// Triangles of a planar facet of a 3D PLC: 3D points, combinatorics in the projection that drops
/// `axis`, circles tested exactly as equatorial balls (see in_coplanar_circle_perturbed).
struct facet_kernel {
  static constexpr std::size_t dim = 2, grid_dim = 2;
  using face = std::array<vertex_id, 2>;
  using coord = std::array<double, 2>;
  std::span<const point3> p;
  int axis = 2;
  bool coplanar = false;  // the points are exactly coplanar (an axis-aligned facet)
  const facet_lines* lines = nullptr;

  /// "beats" is a strict order only for exactly coplanar points; a slanted facet's points are
  /// coplanar up to rounding.
  bool strict() const { return coplanar; }

  int side(const face& f, vertex_id y) const {
    if (lines && lines->collinear(f[0], f[1], y)) return 0;
    return geometry::orient_projected(p[f[0]], p[f[1]], p[y], axis);
  }
  bool beats(const face& f, vertex_id x, vertex_id y) const {
    return geometry::in_coplanar_circle_perturbed(p[f[0]], p[f[1]], p[x], p[y], axis) > 0;
  }
  coord grid_coord(vertex_id v) const { return geometry::project(p[v], axis); }
  const point3& grid_coord_ref(vertex_id v) const { return p[v]; }  // for prefetching only
  bool ball(const face& f, vertex_id x, coord& centre, double& r) const {
    const bool ok = ball_unpadded(f, x, centre, r);
    r = detail::rounding_padded(centre, r);
    return ok && std::isfinite(r);
  }
  bool ball_unpadded(const face& f, vertex_id x, coord& centre, double& r) const {
    const point3& a = p[f[0]];
    const point3 u = p[f[1]] - a, v = p[x] - a;
    const point3 n = cross(u, v);
    const double nn = dot(n, n);
    const double scale = dot(u, u) * dot(v, v);
    const double rel = nn == 0 ? 1.0 : scale / nn * detail::eps * 64;
    if (rel > detail::max_relative_error) {
      point3 c3;
      geometry::exact_circumball(a, p[f[1]], p[x], c3, r);
      centre = geometry::project(c3, axis);
      return std::isfinite(r);
    }
    const point3 c = geometry::triangle_circumcentre_offset(u, v, n, nn);
    r = detail::padded(std::sqrt(dot(c, c)), rel, std::sqrt(std::max(dot(u, u), dot(v, v))));
    centre = geometry::project(a + c, axis);
    return true;
  }
  // The ranking hint works in the projection, where circles are ellipses: rougher than in the
  // other kernels, but it only orders candidates.
  using probe = edge_probe;
  probe prepare(const face& f) const {
    return edge_probe::of(geometry::project(p[f[0]], axis), geometry::project(p[f[1]], axis));
  }
  static double estimate(const probe& pr, const coord& q) { return edge_probe::estimate(pr, q); }
};

/// Triangles of a slanted facet in an orthonormal frame of its plane: the points' frame
/// coordinates (u, v), rounded once, are the geometry; exact 2D predicates on them make "beats" a
/// strict order, as on an axis-aligned facet, so every choice is consistent. Works on positions in
/// its grid (gift_wrapper<..., true>); `ids` maps a position to the point id, for `lines`.
struct frame_kernel : plane_kernel {
  const point_grid<2>* grid = nullptr;
  const facet_lines* lines = nullptr;
  int side(const face& f, vertex_id y) const {
    if (lines && lines->collinear(grid->id_at(f[0]), grid->id_at(f[1]), grid->id_at(y))) return 0;
    return plane_kernel::side(f, y);
  }
};

}  // namespace gsse::front
