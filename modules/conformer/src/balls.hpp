#pragma once
// Double balls that surely contain the closed diametral ball of a subsegment or the closed
// equatorial ball of a subfacet: they bound grid scans and prefilter candidates before the exact
// encroachment test, so they must never be too small. A subfacet too flat for a reliable double
// circumcentre gets its ball constructed exactly (rare).
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "gsse/geometry/exact_ball.hpp"
#include "gsse/geometry/point.hpp"

namespace gsse::conformer::detail {

inline constexpr double eps = std::numeric_limits<double>::epsilon();

template <std::size_t D>
double magnitude(const point<D>& c) {
  double m = 0;
  for (double x : c) m = std::max(m, std::abs(x));
  return m;
}

/// Centre and radius of a ball holding the closed diametral ball of ab.
template <std::size_t D>
std::pair<point<D>, double> diametral_bound(const point<D>& a, const point<D>& b) {
  const point<D> c = 0.5 * (a + b);
  const double r = 0.5 * distance(a, b) * (1 + 1e-12) + 8 * eps * magnitude(c) + 1e-300;
  return {c, r};
}

/// Centre and radius of a ball holding the closed equatorial ball of triangle abc.
inline std::pair<point3, double> equatorial_bound(const point3& a, const point3& b, const point3& c) {
  const point3 u = b - a, v = c - a, n = cross(u, v);
  const double nn = dot(n, n), uu = dot(u, u), vv = dot(v, v);
  const double rel = nn > 0 ? uu * vv / nn * eps * 64 : 1.0;
  point3 cc;
  double r;
  if (!(rel <= 1e-6)) {
    geometry::exact_circumball(a, b, c, cc, r);
    return {cc, r};
  }
  cc = a + (1.0 / (2 * nn)) * cross(uu * v - vv * u, n);
  r = distance(cc, a) * (1 + 4 * rel + 1e-12) + 4 * rel * std::sqrt(std::max(uu, vv)) + 8 * eps * magnitude(cc) + 1e-300;
  return {cc, r};
}

}  // namespace gsse::conformer::detail
