#pragma once
// Triangulation of one PLC facet in the coordinate projection that drops its normal's dominant
// axis: a constrained triangulation of all its polygon vertices and edges (embedded points and
// edges included), keeping the triangles enclosed by its polygons and not reachable from its hole
// points without crossing a polygon edge. All decisions are exact orientations (and perturbed
// in-circle tests, which only choose among valid triangulations) of the projected points, which
// are the input coordinates without one of them: a facet that is planar only up to rounding
// gets the triangulation of its exact projection.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "gsse/container/plc.hpp"

namespace gsse::plc_check::detail {

struct facet_triangles {
  int axis = 2;                                     // dropped coordinate
  std::vector<std::array<vertex_id, 3>> triangles;  // PLC vertex ids, counter-clockwise in the projection
  std::vector<std::uint8_t> polygon_edges;          // per triangle, bit i: edge (v[i], v[i+1]) is a polygon edge
  std::string problem;  // non-empty: the facet's own polygons intersect (then no triangles)
};

facet_triangles triangulate_facet(const std::vector<point3>& points, const plc_facet& f);

}  // namespace gsse::plc_check::detail
