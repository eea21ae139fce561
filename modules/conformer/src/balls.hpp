#pragma once
// Double balls that surely contain the closed diametral ball of a subsegment or the closed
// equatorial ball of a subfacet: they bound grid scans and prefilter candidates before the exact
// encroachment test, so they must never be too small. A subfacet too flat for a reliable double
// circumcentre gets its ball constructed exactly (rare).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>

#include "gsse/geometry/circumcentre.hpp"
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

/// Two deterministic pseudo-random numbers in [-1, 1] from the bits of q. Split points on slanted
/// carriers are moved by them, a tiny fraction of their element: symmetric constructions (edge
/// midpoints, shells, mirror projections) there make configurations cocircular up to rounding,
/// whose flat tetrahedra rounding can make Delaunay; off by 1e-10 they are not ties at all.
template <std::size_t D>
std::array<double, 2> jitter(const point<D>& q) {
  std::uint64_t h = 0x9E3779B97F4A7C15ull;
  for (double x : q) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    h ^= b + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
  }
  auto next = [&] {  // splitmix64
    h += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = h;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-52 - 1.0;
  };
  return {next(), next()};
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
  cc = a + geometry::triangle_circumcentre_offset(u, v, n, nn);
  r = distance(cc, a) * (1 + 4 * rel + 1e-12) + 4 * rel * std::sqrt(std::max(uu, vv)) + 8 * eps * magnitude(cc) + 1e-300;
  return {cc, r};
}

}  // namespace gsse::conformer::detail
