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

/// Any supported PLC input, chosen by extension (.poly, .smesh, .off, .stl) and, for .poly, by
/// the dimension in its header.
using any_plc = std::variant<plc<2>, plc<3>>;
any_plc read_plc(const std::string& path);

/// Segment names from a sidecar BASE.json (`"segments": ["name1", ...]`, name k is segment k),
/// as written by the benchmark structure generator. Regions without a name get "region_<n>".
template <std::size_t D>
void assign_region_names(plc<D>& p, const std::string& path);

/// Checks shared by all PLC readers: finite coordinates, no duplicate points, indices in range.
template <std::size_t D>
void check_points(const std::string& file, const std::vector<point<D>>& pts, const std::vector<std::size_t>& lines);

}  // namespace gsse::io
