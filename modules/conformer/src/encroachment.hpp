#pragma once
// Encroachment with the exact tie rule.
//
// A vertex strictly inside the diametral ball of a subsegment (equatorial ball of a subfacet)
// encroaches it. A vertex exactly on that sphere encroaches it unless the element is a face of the
// perturbed Delaunay triangulation of Q = the element's vertices plus every vertex on the sphere.
// All other vertices lie strictly outside the sphere, so a witness sphere for the element in DT(Q)
// can be taken arbitrarily close to the diametral/equatorial one and stays empty of them: the
// element is then a face of the perturbed Delaunay triangulation of all vertices.
//
// Face test on cospherical Q: a triangle abc is a face iff, taking x = the perturbed gift-wrap
// apex among the points of Q on one side of abc, the tetrahedron abcx is perturbed-empty of Q; if
// no point of Q is off the plane, iff abc passes the perturbed in-plane circle test against the
// coplanar ones. An edge ab is a face iff some triangle abc, c in Q, is. In 2D an edge ab is a face
// iff the triangle abx (x the apex on one side) is perturbed-empty of Q.
#include <span>
#include <vector>

#include "gsse/geometry/predicates.hpp"

namespace gsse::conformer::detail {

using geometry::orient2d;
using geometry::orient3d;

inline bool triangle_in_cospherical_dt(std::span<const point3> p, vertex_id a, vertex_id b, vertex_id c,
                                       const std::vector<vertex_id>& q) {
  if (geometry::collinear(p[a], p[b], p[c])) return false;
  std::vector<vertex_id> pos, neg, flat;
  for (vertex_id y : q) {
    if (y == a || y == b || y == c) continue;
    const int s = orient3d(p[a], p[b], p[c], p[y]);
    (s > 0 ? pos : s < 0 ? neg : flat).push_back(y);
  }
  if (pos.empty() && neg.empty()) {
    const int axis = geometry::dominant_axis(p[a], p[b], p[c]);
    vertex_id u = a, v = b;
    if (geometry::orient_projected(p[a], p[b], p[c], axis) < 0) std::swap(u, v);
    for (vertex_id y : flat)
      if (geometry::in_coplanar_circle_perturbed(p[u], p[v], p[c], p[y], axis) > 0) return false;
    return true;
  }
  // apex on one side: tetrahedron (u,v,c,x) positively oriented
  vertex_id u = a, v = b;
  const std::vector<vertex_id>& side = pos.empty() ? neg : pos;
  if (pos.empty()) std::swap(u, v);
  vertex_id x = side[0];
  for (vertex_id y : side)
    if (y != x && geometry::in_sphere_perturbed(p[u], p[v], p[c], p[x], p[y]) > 0) x = y;
  for (vertex_id y : q) {
    if (y == a || y == b || y == c || y == x) continue;
    if (geometry::in_sphere_perturbed(p[u], p[v], p[c], p[x], p[y]) > 0) return false;
  }
  return true;
}

inline bool edge_in_cospherical_dt(std::span<const point3> p, vertex_id a, vertex_id b,
                                   const std::vector<vertex_id>& q) {
  bool any = false;
  for (vertex_id c : q) {
    if (c == a || c == b) continue;
    any = true;
    std::vector<vertex_id> all = q;
    all.push_back(a);
    all.push_back(b);
    if (triangle_in_cospherical_dt(p, a, b, c, all)) return true;
  }
  return !any;
}

inline bool edge_in_cocircular_dt(std::span<const point2> p, vertex_id a, vertex_id b,
                                  const std::vector<vertex_id>& q) {
  std::vector<vertex_id> pos, neg;
  for (vertex_id y : q) {
    if (y == a || y == b) continue;
    (orient2d(p[a], p[b], p[y]) > 0 ? pos : neg).push_back(y);
  }
  if (pos.empty() && neg.empty()) return true;
  vertex_id u = a, v = b;
  const std::vector<vertex_id>& side = pos.empty() ? neg : pos;
  if (pos.empty()) std::swap(u, v);
  vertex_id x = side[0];
  for (vertex_id y : side)
    if (y != x && geometry::in_circle_perturbed(p[u], p[v], p[x], p[y]) > 0) x = y;
  for (vertex_id y : q) {
    if (y == a || y == b || y == x) continue;
    if (geometry::in_circle_perturbed(p[u], p[v], p[x], p[y]) > 0) return false;
  }
  return true;
}

}  // namespace gsse::conformer::detail
