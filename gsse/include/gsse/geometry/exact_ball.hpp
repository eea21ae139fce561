#pragma once
// Circumballs constructed in exact rational arithmetic, rounded outward to a double ball that
// surely contains the exact one. For the rare simplices whose double construction is unreliable
// (a nearly flat tetrahedron, a sliver): a search bounded by the double ball would have to scan
// everything, one bounded by this ball scans what it must. Slow (GMP), so only a fallback; the
// results bound search regions and decide nothing.
#include <CGAL/Exact_rational.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "gsse/geometry/circumcentre.hpp"
#include "gsse/geometry/point.hpp"

namespace gsse::geometry {

namespace detail {
using exact_kernel = CGAL::Simple_cartesian<CGAL::Exact_rational>;

/// Outward-rounded double ball from an exact centre and squared radius.
template <std::size_t D, class Centre, class FT>
void round_out(const Centre& c, const FT& r2, point<D>& centre, double& radius) {
  double err = 0;
  for (std::size_t k = 0; k < D; ++k) {
    const auto iv = CGAL::to_interval(c[static_cast<int>(k)]);
    centre[k] = 0.5 * (iv.first + iv.second);
    err = std::max({err, centre[k] - iv.first, iv.second - centre[k]});
  }
  const double r = std::sqrt(CGAL::to_interval(r2).second);
  radius = r * (1 + 8 * std::numeric_limits<double>::epsilon()) + 2 * err * std::sqrt(double(D)) +
           std::numeric_limits<double>::denorm_min();
}
inline exact_kernel::Point_3 ex(const point3& p) { return {p[0], p[1], p[2]}; }
inline exact_kernel::Point_2 ex(const point2& p) { return {p[0], p[1]}; }
}  // namespace detail

/// Circumball of the tetrahedron abcd (non-degenerate): a double ball containing the exact one.
inline void exact_circumball(const point3& a, const point3& b, const point3& c, const point3& d, point3& centre,
                             double& radius) {
  using namespace detail;
  const auto o = CGAL::circumcenter(ex(a), ex(b), ex(c), ex(d));
  round_out<3>(o, CGAL::squared_distance(o, ex(a)), centre, radius);
}
/// Circumball of the tetrahedron abcd: a double ball containing the exact one, constructed in
/// doubles and padded by a bound of their rounding where that bound is below 1e-6 of the radius,
/// else exactly (`exact_circumball`). Returns false, and nothing, for a flat tetrahedron or one
/// whose double circumradius exceeds `max_radius` (no exact construction is made for it).
inline bool circumball_bound(const point3& a, const point3& b, const point3& c, const point3& d, point3& centre,
                             double& radius, double max_radius = std::numeric_limits<double>::infinity()) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const point3 u = b - a, v = c - a, w = d - a;
  double det = 0;
  const point3 off = tetrahedron_circumcentre_offset(u, v, w, det);
  if (!(std::abs(det) > 0) || !(dot(off, off) <= max_radius * max_radius)) return false;
  const double lu = std::sqrt(dot(u, u)), lv = std::sqrt(dot(v, v)), lw = std::sqrt(dot(w, w));
  const double R = std::sqrt(dot(off, off));
  // the numerator's terms are at most |u|^2 |v| |w| and the like; det's error at most a few eps
  // of |u| |v| |w|: 64 eps of each is far above what the operations round
  const double err = 64 * eps * ((lu * lu * lv * lw + lv * lv * lw * lu + lw * lw * lu * lv) / (2 * std::abs(det)) +
                                 R * lu * lv * lw / std::abs(det));
  if (std::isfinite(err) && err <= 1e-6 * R) {
    centre = a + off;
    double m = 0;
    for (double x : centre) m = std::max(m, std::abs(x));
    radius = R * (1 + 1e-12) + err + 8 * eps * m + std::numeric_limits<double>::denorm_min();
    return true;
  }
  exact_circumball(a, b, c, d, centre, radius);
  return true;
}
/// Equatorial ball of the 3D triangle abc (centre in its plane): a double ball containing it.
inline void exact_circumball(const point3& a, const point3& b, const point3& c, point3& centre, double& radius) {
  using namespace detail;
  const auto o = CGAL::circumcenter(ex(a), ex(b), ex(c));
  round_out<3>(o, CGAL::squared_distance(o, ex(a)), centre, radius);
}
/// Circumcircle of the 2D triangle abc (non-degenerate): a double disc containing it.
inline void exact_circumball(const point2& a, const point2& b, const point2& c, point2& centre, double& radius) {
  using namespace detail;
  const auto o = CGAL::circumcenter(ex(a), ex(b), ex(c));
  round_out<2>(o, CGAL::squared_distance(o, ex(a)), centre, radius);
}

}  // namespace gsse::geometry
