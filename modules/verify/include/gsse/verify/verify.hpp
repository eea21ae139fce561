#pragma once
// Library verifier: checks a mesh against the input PLC itself, not against anything the mesher
// derived from it (its conformed boundary, its labels). It shares with the mesher only the core
// containers and CGAL's exact predicates, and decides by brute force where that is cheap.
//
//   validity    every cell positively oriented (exact orientation), each face in at most two
//               cells and the two on opposite sides, no two vertices at one position, every PLC
//               vertex a mesh vertex (exact coordinates)
//   conformity  every hull face (one cell) and interface face (cells of two segment numbers) lies
//               on input facets (segments in 2D): on the facet's plane (exactly, or within
//               facet_tolerance x the PLC's bounding-box diagonal) and inside its region (polygons
//               minus what the facet's hole points reach, exact point-in-polygon), or across
//               coplanar facets of one marker whose shares add up to the face; every facet is
//               covered by the faces on it (area within 1e-9 relative) unless no cell reaches it
//               (a facet inside a hole); cell volume = volume bounded by the PLC's hull facets
//   labels      cells joined across faces on no facet form components of one segment number;
//               every region point lies in a cell (exact point-in-simplex) of its region's number;
//               no hole point lies in a cell
//   delaunay    no vertex strictly inside any cell's circumsphere (exact in-sphere on the vertices
//               in an outward-rounded bounding ball); the deepest violation is measured
#include <cstddef>
#include <string>
#include <vector>

#include "gsse/container/domain.hpp"
#include "gsse/container/plc.hpp"

namespace gsse::verify {

struct options {
  double facet_tolerance = 1e-9;  // distance of a face's vertices from a facet plane, relative to the PLC's diagonal
  bool delaunay = true;           // run the (most expensive) empty-circumsphere check
  unsigned threads = 1;           // threads for the orientation, vertex and Delaunay passes; the report is the same for any number
};

struct report {
  /// One line per kind of problem found (count and a few examples), at most about 20 lines.
  /// Empty: the mesh is valid, conforming, correctly labelled and (if checked) Delaunay.
  std::vector<std::string> problems;
  bool ok() const { return problems.empty(); }

  // figures
  std::size_t cells = 0, faces = 0, hull_faces = 0, interface_faces = 0;
  std::size_t inexact_faces = 0;     // hull/interface faces on a facet only within the tolerance (informational)
  std::size_t spanning_faces = 0;    // faces across coplanar facets of one marker (accepted, informational)
  std::size_t facets_in_holes = 0;   // facets no cell reaches, hence with no face on them (accepted)
  std::size_t components = 0;
  double volume_error = 0;           // |cell volume - PLC volume| / PLC volume
  double deepest_delaunay = 0;       // (R^2 - d^2)/R^2 of the deepest vertex inside a circumsphere (0: none)
  std::size_t delaunay_ties = 0;     // vertices exactly on a circumsphere (allowed)

  // problems, by kind (each non-zero count is one line of `problems`)
  std::size_t bad_vertex_ids = 0;        // cells naming a vertex the domain does not have
  std::size_t inverted_cells = 0;        // exact orientation < 0
  std::size_t degenerate_cells = 0;      // exact orientation = 0
  std::size_t nonmanifold_faces = 0;     // faces of more than two cells
  std::size_t folded_faces = 0;          // faces whose two cells lie on the same side
  std::size_t duplicate_vertices = 0;    // vertices at the position of another
  std::size_t missing_plc_vertices = 0;  // PLC vertices that are no mesh vertex
  std::size_t off_facet_faces = 0;       // hull/interface faces on no input facet
  std::size_t mixed_marker_faces = 0;    // faces across coplanar facets of different markers
  std::size_t uncovered_facets = 0;      // facets whose faces cover less than their area (by more than 1e-9 relative)
  std::size_t overcovered_facets = 0;    // facets whose faces add up to more than their area (faces overlap)
  std::size_t volume_mismatch = 0;       // 1 if volume_error > 1e-9
  std::size_t mixed_components = 0;      // components with cells of more than one segment number
  std::size_t misplaced_region_points = 0;  // region points in no cell, or in a component of another number
  std::size_t meshed_hole_points = 0;    // hole points inside a cell
  std::size_t non_delaunay_cells = 0;    // cells with a vertex strictly inside their circumsphere
};

/// Checks `mesh` (cells labelled by their segment's number) against the PLC it was made from.
template <std::size_t D>
report check(const domain<D>& mesh, const plc<D>& input, const options& o = {});

}  // namespace gsse::verify
