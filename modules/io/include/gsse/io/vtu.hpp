#pragma once
// VTK XML UnstructuredGrid (.vtu) writer, appended raw binary data, header_type UInt64: what
// ParaView and meshio read directly.
#include <string>

#include "gsse/container/domain.hpp"
#include "gsse/io/error.hpp"

namespace gsse::io {

/// Writes all points and the cells of every segment (in segment order) with:
///  - cell data "segment": the segment number of each cell (Int32);
///  - every double (Float64) and int (Int32) vertex quantity as point data "<segment>/<quantity>"
///    (vertex columns are per segment over all domain vertices; the column is written as stored);
///  - every double/int cell quantity as cell data "<quantity>" when all segments with cells have
///    it with the same type, else "<segment>/<quantity>" with 0 on the other segments' cells.
/// Quantities of other types are skipped. 2D points get z = 0.
/// Beside it, boundary_vtu_path(path) (BASE.boundary.vtu): the same points and the boundary,
/// interface and marked faces (triangles; 2D: lines) with cell data "marker" (the input facet's
/// marker, 0 if none), "segment" (the segment the face is oriented into; the lower number at an
/// interface) and "other_segment" (the segment on the other side, 0 outside; both 0 for a marked
/// face inside a segment). Both files are written, or neither.
template <std::size_t D>
void write_vtu(const domain<D>& d, const std::string& path);
/// BASE.boundary.vtu for BASE.vtu.
std::string boundary_vtu_path(const std::string& path);

}  // namespace gsse::io
