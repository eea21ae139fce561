#pragma once
// Circumcentres in double precision, as offsets from the simplex's first vertex a, with the
// denominator that bounds their rounding error (callers switch to the exact construction of
// exact_ball.hpp when it is too small). One copy of each formula for the whole library: the front
// mesher's kernels, its point creation, and the quality measure use these.
#include "gsse/geometry/point.hpp"

namespace gsse::geometry {

/// Tetrahedron a, a+u, a+v, a+w: its circumcentre minus a; `det` receives u . (v x w) (0: flat,
/// and the offset is not finite).
inline point3 tetrahedron_circumcentre_offset(const point3& u, const point3& v, const point3& w, double& det) {
  const point3 vw = cross(v, w), wu = cross(w, u), uv = cross(u, v);
  det = dot(u, vw);
  return (1.0 / (2 * det)) * (dot(u, u) * vw + dot(v, v) * wu + dot(w, w) * uv);
}

/// Triangle a, a+u, a+v in the plane: its circumcentre minus a; `d` receives 2 (u x v) (0: flat,
/// and the offset is not finite).
inline point2 plane_circumcentre_offset(const point2& u, const point2& v, double& d) {
  d = 2 * (u[0] * v[1] - u[1] * v[0]);
  return {(v[1] * dot(u, u) - u[1] * dot(v, v)) / d, (u[0] * dot(v, v) - v[0] * dot(u, u)) / d};
}

/// Triangle a, a+u, a+v in space, n = u x v and nn = n . n given: its circumcentre minus a.
inline point3 triangle_circumcentre_offset(const point3& u, const point3& v, const point3& n, double nn) {
  return (1.0 / (2 * nn)) * cross(dot(u, u) * v - dot(v, v) * u, n);
}

}  // namespace gsse::geometry
