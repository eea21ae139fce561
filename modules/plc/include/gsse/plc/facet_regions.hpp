#pragma once
// Facet regions: what each input facet of a 3D PLC covers, decided once before meshing.
//
// A TetGen facet is a set of polygons (outer loops, nested loops, 2-vertex embedded edges,
// 1-vertex embedded points) and hole points; it covers the area enclosed by its polygons minus
// what a hole point reaches without crossing a polygon. Its corners need only be coplanar up to
// rounding (a rotated CAD quad): every vertex must lie within `planar_tolerance` times the
// model size (bounding-box diagonal) of the facet's plane; beyond that the facet is rejected.
//
// The region is returned as constraint edges oriented with the region on their left in the
// projection that drops the dominant axis of the facet's normal (an edge with the region on both
// sides appears in both directions), plus the vertices inside it on no edge. That is all the
// conformer needs: it triangulates the facet from these edges, whatever polygons they came from.
//
// Coplanar facets (within the same tolerance) with one marker that meet at an edge no other
// facet uses are merged, as TetGen does unless -M: the edge between them is no constraint. A
// triangulated planar face (an STL, the --triangles benchmark structures) is then one facet, and
// a diagonal of a rectangle whose corners are cocircular up to rounding needs no splitting.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "gsse/container/plc.hpp"

namespace gsse::input {

class input_error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct facet_options {
  /// Largest distance of a facet vertex from the facet's plane, relative to the bounding-box
  /// diagonal of the PLC's points (1e-12: rounding of a rotation, with room for a chain of them).
  double planar_tolerance = 1e-12;
  bool merge_coplanar = true;  // merge coplanar facets of one marker across shared edges
};

struct facet_region {
  std::vector<std::array<vertex_id, 2>> edges;  // region on the left (in the projection dropping `axis`)
  std::vector<vertex_id> points;                // inside the region, on no edge
  std::vector<std::uint32_t> members;           // input facets (ascending): members[0] names it
  point3 normal{};                              // Newell normal (area-weighted), normal[axis] > 0:
                                                // the region is counter-clockwise about it
  int axis = 2;                                 // dominant axis of `normal`
  int marker = 0;
};

/// The regions of p's facets. Throws input_error (naming the file, line and facet) for facets
/// that are not planar within the tolerance, have no area, degenerate polygons, or an embedded
/// edge or point outside the facet.
std::vector<facet_region> facet_regions(const plc<3>& p, const facet_options& o = {});

/// Bounding-box diagonal of the PLC's points (1 if they coincide).
double model_size(const plc<3>& p);

}  // namespace gsse::input
