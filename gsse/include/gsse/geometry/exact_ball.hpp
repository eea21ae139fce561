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
