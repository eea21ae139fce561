#pragma once
// Self-intersections of an input PLC, found before meshing: a PLC whose facets (3D) or segments
// (2D) intersect other than in shared vertices and edges has no conforming mesh, and the
// conformer would refine it forever.
//
// 3D: every facet is triangulated in the coordinate projection that drops its normal's dominant
// axis (a constrained triangulation of its polygons, minus the areas outside them and those
// reachable from its hole points, TetGen's semantics); triangles of different facets are tested
// with exact predicates. Facets may share vertices and edges; anything else they have in common
// is reported: crossing facets, a vertex of one facet inside or on an edge of another (a
// T-junction), coplanar overlap. Within one facet, polygon edges that cross or touch other than at
// shared vertices are reported, and so is a PLC point on no facet that lies on a facet.
// 2D: segments that cross, overlap collinearly, or have a vertex in another's interior, and PLC
// points on no segment that lie on a segment.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "gsse/container/plc.hpp"
#include "gsse/plc/facet_regions.hpp"

namespace gsse::plc_check {

/// The input is not a valid PLC; the message names the file and the facets or segments. The
/// module's one error type for bad input (facet_regions throws it too).
using input_error = input::input_error;

/// Facet (3D) or segment (2D) indices into the PLC, 0-based, a <= b. a == b: a problem of one
/// facet or segment alone (its own polygon edges intersect, or a point on no facet lies on it).
/// `what` says what was found, in the file's 1-based numbering ("they cross", "vertex 12 lies
/// inside facet 2", ...).
struct intersection {
  std::uint32_t a = 0, b = 0;
  std::string what;
};

/// Up to `max_reports` intersecting pairs, the smallest (a, b) first; one report per pair.
std::vector<intersection> self_intersections(const plc<3>& p, std::size_t max_reports = 16);
std::vector<intersection> self_intersections(const plc<2>& p, std::size_t max_reports = 16);

/// One line naming the file, both facets (with their input lines) or segments (with their
/// vertices) and what was found: `cube.poly:31: facet 7 (line 31) intersects facet 2 (line 21):
/// they cross`.
std::string message(const plc<3>& p, const intersection& x);
std::string message(const plc<2>& p, const intersection& x);

/// Throws input_error with the message of the first intersection (and how many more were found).
void require_no_self_intersections(const plc<3>& p);
void require_no_self_intersections(const plc<2>& p);

}  // namespace gsse::plc_check
