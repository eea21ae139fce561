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

/// The point of the triangle abc nearest to q, by the Voronoi regions of its vertices and edges
/// (dot products only; Ericson, Real-Time Collision Detection, 5.1.5). A triangle degenerate in
/// double (the sine of its angle at a below 1e-6): the nearest point of its edges.
inline point3 triangle_closest(const point3& a, const point3& b, const point3& c, const point3& q) {
  const point3 ab = b - a, ac = c - a, aq = q - a;
  const double abab = dot(ab, ab), acac = dot(ac, ac), abac = dot(ab, ac);
  if (!(abab * acac - abac * abac > 1e-12 * abab * acac)) {  // degenerate: sin^2 of its angle at a below 1e-12
    point3 best = segment_closest(a, b, q);
    for (const point3& x : {segment_closest(b, c, q), segment_closest(c, a, q)})
      if (squared_distance(x, q) < squared_distance(best, q)) best = x;
    return best;
  }
  const double d1 = dot(ab, aq), d2 = dot(ac, aq);
  if (d1 <= 0 && d2 <= 0) return a;
  const point3 bq = q - b;
  const double d3 = dot(ab, bq), d4 = dot(ac, bq);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const point3 cq = q - c;
  const double d5 = dot(ab, cq), d6 = dot(ac, cq);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double sum = va + vb + vc;
  return a + (vb / sum) * ab + (vc / sum) * ac;
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
