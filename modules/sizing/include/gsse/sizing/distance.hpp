#pragma once
// Closest-point distances in double, for sizing and point placement (they decide no topology).
#include <algorithm>
#include <array>

#include "gsse/geometry/point.hpp"

namespace gsse::sizing {

/// The point of the segment [a, b] nearest to q.
template <std::size_t D>
point<D> segment_closest(const point<D>& a, const point<D>& b, const point<D>& q) {
  const point<D> e = b - a;
  const double ee = dot(e, e);
  const double t = ee > 0 ? std::clamp(dot(q - a, e) / ee, 0.0, 1.0) : 0.0;
  return a + t * e;
}

/// The point of the triangle abc nearest to q: the plane's foot if it is inside, else the
/// nearest edge point.
inline point3 triangle_closest(const point3& a, const point3& b, const point3& c, const point3& q) {
  const point3 u = b - a, v = c - a, n = cross(u, v);
  const double nn = dot(n, n);
  if (nn > 0) {
    const point3 foot = q - (dot(q - a, n) / nn) * n;
    const double l1 = dot(cross(b - foot, c - foot), n), l2 = dot(cross(c - foot, a - foot), n),
                 l3 = dot(cross(a - foot, b - foot), n);
    if (l1 >= 0 && l2 >= 0 && l3 >= 0) return foot;
  }
  point3 best = segment_closest(a, b, q);
  for (const point3& x : {segment_closest(b, c, q), segment_closest(c, a, q)})
    if (squared_distance(x, q) < squared_distance(best, q)) best = x;
  return best;
}

template <std::size_t D>
double segment_distance2(const point<D>& a, const point<D>& b, const point<D>& q) {
  return squared_distance(segment_closest(a, b, q), q);
}
inline double triangle_distance2(const point3& a, const point3& b, const point3& c, const point3& q) {
  return squared_distance(triangle_closest(a, b, c, q), q);
}

/// The point of a boundary face (a segment in 2D, a triangle in 3D) nearest to q.
template <std::size_t D>
point<D> face_closest(const std::array<point<D>, D>& f, const point<D>& q) {
  if constexpr (D == 2)
    return segment_closest(f[0], f[1], q);
  else
    return triangle_closest(f[0], f[1], f[2], q);
}
template <std::size_t D>
double face_distance2(const std::array<point<D>, D>& f, const point<D>& q) {
  return squared_distance(face_closest(f, q), q);
}

}  // namespace gsse::sizing
