#pragma once
// Exact geometric predicates on CGAL's Exact_predicates_inexact_constructions_kernel, and the
// project's one global symbolic perturbation for ties.
//
// Sign conventions (all return -1, 0 or +1):
//   orient2d(a,b,c)       +1 if a,b,c turn counter-clockwise
//   orient3d(a,b,c,d)     +1 if d lies on the side (b-a)x(c-a) points to (tetra abcd positive)
//   in_circle(a,b,c,d)    +1 if d is inside the circle of the ccw triangle abc
//   in_sphere(a,b,c,d,e)  +1 if e is inside the sphere of the positive tetrahedron abcd
//   in_diametral(a,b,p)   +1 if p is inside the ball with diameter ab (2D or 3D)
//   in_equatorial(a,b,c,p)+1 if p is inside the ball whose equator is the circumcircle of abc
//
// The *_perturbed variants never return 0 for distinct points in general position of the
// simplex (precondition: the simplex is non-degenerate and positively oriented). They resolve
// a tie by the perturbation of Devillers & Teillaud ("Perturbations for Delaunay and weighted
// Delaunay 3D triangulations", CGTA 2011): points are ranked by lexicographic coordinate order,
// the lifted point of rank k is raised by eps^(n-k), and the sign of the leading non-zero term
// of the perturbed lifted determinant decides. This is the scheme CGAL's Delaunay triangulations
// use, so our meshes and CGAL's agree even on cospherical input. It defines a unique regular
// triangulation (Delaunay with infinitesimal weights) of any point set.
#include <algorithm>
#include <array>
#include <cstddef>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "gsse/geometry/fixed_predicates.hpp"
#include "gsse/geometry/point.hpp"

namespace gsse::geometry {

using kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

namespace detail {
inline kernel::Point_2 cg(const point2& p) { return {p[0], p[1]}; }
inline kernel::Point_3 cg(const point3& p) { return {p[0], p[1], p[2]}; }
inline const kernel& K() {
  static const kernel k;
  return k;
}
}  // namespace detail

inline int orient2d(const point2& a, const point2& b, const point2& c) {
  return static_cast<int>(detail::K().orientation_2_object()(detail::cg(a), detail::cg(b), detail::cg(c)));
}
/// orient3d, in_sphere and in_equatorial first try fixed_predicates.hpp (its own double filter,
/// then fixed-width integers when the coordinate differences allow: exact zeros on lattices and
/// axis-aligned facets), and CGAL's filtered predicate otherwise; the sign is exact either way.
inline int orient3d(const point3& a, const point3& b, const point3& c, const point3& d) {
  if (const int s = fixed::orient3d(a, b, c, d); s != fixed::undecided) return s;
  return static_cast<int>(
      detail::K().orientation_3_object()(detail::cg(a), detail::cg(b), detail::cg(c), detail::cg(d)));
}
/// Orientation of the projection of a,b,c onto the coordinate plane that drops `axis`.
/// (x,y,z) with axis 2 -> (x,y); axis 0 -> (y,z); axis 1 -> (z,x): each keeps right-handedness,
/// so a facet whose normal has a positive `axis` component is counter-clockwise.
inline point2 project(const point3& p, int axis) {
  switch (axis) {
    case 0: return {p[1], p[2]};
    case 1: return {p[2], p[0]};
    default: return {p[0], p[1]};
  }
}
inline int orient_projected(const point3& a, const point3& b, const point3& c, int axis) {
  return orient2d(project(a, axis), project(b, axis), project(c, axis));
}

inline int in_circle(const point2& a, const point2& b, const point2& c, const point2& d) {
  return static_cast<int>(detail::K().side_of_oriented_circle_2_object()(detail::cg(a), detail::cg(b),
                                                                         detail::cg(c), detail::cg(d)));
}
inline int in_sphere(const point3& a, const point3& b, const point3& c, const point3& d, const point3& e) {
  if (const int s = fixed::in_sphere(a, b, c, d, e); s != fixed::undecided) return s;
  return static_cast<int>(detail::K().side_of_oriented_sphere_3_object()(
      detail::cg(a), detail::cg(b), detail::cg(c), detail::cg(d), detail::cg(e)));
}
/// CGAL's Bounded_side: ON_UNBOUNDED_SIDE = -1, ON_BOUNDARY = 0, ON_BOUNDED_SIDE = +1.
inline int in_diametral(const point2& a, const point2& b, const point2& p) {
  return static_cast<int>(
      detail::K().side_of_bounded_circle_2_object()(detail::cg(a), detail::cg(b), detail::cg(p)));
}
inline int in_diametral(const point3& a, const point3& b, const point3& p) {
  return static_cast<int>(
      detail::K().side_of_bounded_sphere_3_object()(detail::cg(a), detail::cg(b), detail::cg(p)));
}
inline int in_equatorial(const point3& a, const point3& b, const point3& c, const point3& p) {
  if (const int s = fixed::in_equatorial(a, b, c, p); s != fixed::undecided) return s;
  return static_cast<int>(detail::K().side_of_bounded_sphere_3_object()(detail::cg(a), detail::cg(b),
                                                                        detail::cg(c), detail::cg(p)));
}
/// +1 if p (coplanar with a,b,c) lies inside the circumcircle of a,b,c (any orientation).
inline int in_coplanar_circle(const point3& a, const point3& b, const point3& c, const point3& p) {
  return static_cast<int>(detail::K().coplanar_side_of_bounded_circle_3_object()(
      detail::cg(a), detail::cg(b), detail::cg(c), detail::cg(p)));
}
inline bool collinear(const point3& a, const point3& b, const point3& c) {
  return detail::K().collinear_3_object()(detail::cg(a), detail::cg(b), detail::cg(c));
}

namespace detail {
// Sorts indices 0..N-1 of `pts` by decreasing perturbation rank (lexicographically largest first).
template <std::size_t N, std::size_t D>
std::array<int, N> by_decreasing_rank(const std::array<const point<D>*, N>& pts) {
  std::array<int, N> idx;
  for (std::size_t i = 0; i < N; ++i) idx[i] = static_cast<int>(i);
  std::sort(idx.begin(), idx.end(), [&](int i, int j) { return lex_less(*pts[j], *pts[i]); });
  return idx;
}
}  // namespace detail

/// Perturbed in-circle for a ccw triangle abc: +1 inside, -1 outside, never 0.
inline int in_circle_perturbed(const point2& a, const point2& b, const point2& c, const point2& d) {
  if (const int s = in_circle(a, b, c, d); s != 0) return s;
  std::array<const point2*, 4> p{&a, &b, &c, &d};
  for (int k : detail::by_decreasing_rank(p)) {
    if (k == 3) return -1;  // the query carries the largest lift: it is outside
    std::array<const point2*, 3> t{&a, &b, &c};
    t[static_cast<std::size_t>(k)] = &d;
    if (const int o = orient2d(*t[0], *t[1], *t[2]); o != 0) return o;
  }
  return -1;  // unreachable for distinct points and a non-degenerate triangle
}

/// Perturbed in-sphere for a positive tetrahedron abcd: +1 inside, -1 outside, never 0.
inline int in_sphere_perturbed(const point3& a, const point3& b, const point3& c, const point3& d,
                               const point3& e) {
  if (const int s = in_sphere(a, b, c, d, e); s != 0) return s;
  std::array<const point3*, 5> p{&a, &b, &c, &d, &e};
  for (int k : detail::by_decreasing_rank(p)) {
    if (k == 4) return -1;
    std::array<const point3*, 4> t{&a, &b, &c, &d};
    t[static_cast<std::size_t>(k)] = &e;
    if (const int o = orient3d(*t[0], *t[1], *t[2], *t[3]); o != 0) return o;
  }
  return -1;
}

/// Whether q breaks a boundary face abc kept as a Delaunay face with the apex x (the empty sphere
/// through a, b, c and x; x off the plane abc): q in the closed equatorial ball of abc, or
/// strictly across the plane from x in the closed sphere through a, b, c, x. A point on x's side
/// outside the ball breaks nothing: that sphere's cap on x's side lies in the ball. Exact.
/// (conformer::face_encroached, the front's point creation; docs/design-decisions.md, "Boundary
/// faces need to be Delaunay, not Gabriel")
inline bool breaks_face_with_apex(const point3& a, const point3& b, const point3& c, const point3& x, const point3& q) {
  if (in_equatorial(a, b, c, q) >= 0) return true;
  const int sx = orient3d(a, b, c, x), sq = orient3d(a, b, c, q);
  if (sq == 0 || sq == sx) return false;  // in the plane, or on x's side, outside the ball
  // (a, b, c, x) positively oriented: in_sphere > 0 is inside
  return sx > 0 ? in_sphere(a, b, c, x, q) >= 0 : in_sphere(b, a, c, x, q) >= 0;
}

/// Perturbed in-circle for a triangle abc of 3D points lying in (or, after rounding, near) a facet
/// plane: d is tested against the equatorial ball of abc (the ball whose equator is the circumcircle
/// of abc), which for coplanar points is exactly the in-circle test. Orientations of the
/// perturbation are measured in the projection that drops `axis`; abc must be counter-clockwise
/// there. The lifting restricted to a plane differs from the planar lifting by an affine function
/// only, so for coplanar points this agrees with in_sphere_perturbed on the 3D Delaunay
/// tetrahedralization restricted to the plane.
inline int in_coplanar_circle_perturbed(const point3& a, const point3& b, const point3& c, const point3& d,
                                        int axis) {
  if (const int s = in_equatorial(a, b, c, d); s != 0) return s;
  std::array<const point3*, 4> p{&a, &b, &c, &d};
  for (int k : detail::by_decreasing_rank(p)) {
    if (k == 3) return -1;
    std::array<const point3*, 3> t{&a, &b, &c};
    t[static_cast<std::size_t>(k)] = &d;
    if (const int o = orient_projected(*t[0], *t[1], *t[2], axis); o != 0) return o;
  }
  return -1;
}

/// Index (0,1,2) of the largest absolute component of the normal of triangle abc: the axis to drop
/// so that the projection is non-degenerate. Computed in double: any axis with a non-zero
/// projected area gives the same combinatorics, so the choice needs no exactness.
inline int dominant_axis(const point3& a, const point3& b, const point3& c) {
  const point3 n = cross(b - a, c - a);
  int ax = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(n[static_cast<std::size_t>(i)]) > std::abs(n[static_cast<std::size_t>(ax)])) ax = i;
  return ax;
}

}  // namespace gsse::geometry
