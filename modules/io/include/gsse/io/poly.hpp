#pragma once
// TetGen (.poly, .smesh, .node) and Triangle (.poly, .node) readers for PLCs and point clouds.
#include <string>
#include <variant>
#include <vector>

#include "gsse/container/plc.hpp"
#include "gsse/io/error.hpp"

namespace gsse::io {

/// TetGen .poly or .smesh (by extension). A node count of 0 reads the points from BASE.node.
plc<3> read_tetgen_poly(const std::string& path);
/// Triangle .poly. A vertex count of 0 reads the vertices from BASE.node.
plc<2> read_triangle_poly(const std::string& path);
/// Points of a TetGen/Triangle .node file of the given dimension (attributes, markers skipped).
template <std::size_t D>
std::vector<point<D>> read_node(const std::string& path);
/// Dimension stated in the header of a .poly/.node file (2 or 3).
int poly_dimension(const std::string& path);

/// A volume of a surface model (Gmsh .msh): the facets (indices into plc.facets) that bound it,
/// and the segment it belongs to. Several volumes may share a number (one physical group).
struct plc_volume {
  int number = 0;
  std::string name;
  int entity = 0;                    // the volume's entity tag in the file
  std::vector<std::size_t> facets;   // sorted, each once
};

/// Any supported PLC input, chosen by extension (.poly, .smesh, .off, .stl, .msh) and, for .poly,
/// by the dimension in its header. Surface models name their volumes but have no region points:
/// a point inside each volume needs exact predicates, which the I/O module does not use. Their
/// volumes go to `*volumes` (see read_msh_plc) and the PLC's `regions` stay empty; the caller
/// places one region point per volume (gsse::plc_tools::interior_points, modules/plc). Without
/// `volumes`, or for a file without volume entities, the PLC has no regions: every bounded cell
/// becomes a segment of its own, as for OFF and STL.
using any_plc = std::variant<plc<2>, plc<3>>;
any_plc read_plc(const std::string& path, std::vector<plc_volume>* volumes = nullptr);

/// Writes a TetGen .poly: points (indices from 1, with markers), facets (polygons, facet holes,
/// markers), hole points and region points (number, maximum volume). Coordinates are written as
/// the shortest decimal that reads back to the same double. When the PLC has regions, their
/// names go to the sidecar BASE.json ("segments" and "numbers"), which read_tetgen_poly reads.
void write_tetgen_poly(const plc<3>& p, const std::string& path);
/// Writes a Triangle .poly (points, segments with markers, holes, regions with maximum area);
/// region names to BASE.json as for write_tetgen_poly.
void write_triangle_poly(const plc<2>& p, const std::string& path);

/// Segment names from a sidecar BASE.json (`"segments": ["name1", ...]`, name k is segment k),
/// as written by the benchmark structure generator. Regions without a name get "region_<n>".
template <std::size_t D>
void assign_region_names(plc<D>& p, const std::string& path);

/// Checks shared by all PLC readers: finite coordinates, no duplicate points, indices in range.
template <std::size_t D>
void check_points(const std::string& file, const std::vector<point<D>>& pts, const std::vector<std::size_t>& lines);

}  // namespace gsse::io
