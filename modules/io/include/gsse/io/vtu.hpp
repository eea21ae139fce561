#pragma once
// VTK XML UnstructuredGrid (.vtu) writer, appended raw binary data, header_type UInt64: what
// ParaView and meshio read directly.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

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

/// An UnstructuredGrid as read from a .vtu: points, cells (VTK type numbers, CSR connectivity)
/// and the point data arrays, every number converted to double.
struct vtu_grid {
  struct array {
    std::string name;
    std::size_t components = 1;
    std::vector<double> values;  // point-major: values[p * components + c]
    std::size_t line = 0;        // the DataArray's line in the file
  };
  std::string source;
  std::vector<std::array<double, 3>> points;
  std::vector<std::uint8_t> cell_types;  // VTK cell types (10 tetrahedron, 5 triangle, ...)
  std::vector<std::size_t> cell_start;   // cell c's vertices: connectivity[cell_start[c] .. cell_start[c + 1])
  std::vector<std::size_t> connectivity;
  std::vector<array> point_data;
  std::size_t cells_line = 0;  // the Cells element's line (for messages about cells)
  const array* point_array(std::string_view name) const;
};

/// Reads a VTK XML UnstructuredGrid: every Piece; DataArrays in ascii, inline binary (base64) or
/// appended (raw or base64) format; header_type UInt32 or UInt64; little- or big-endian; with or
/// without vtkZLibDataCompressor. That covers what VTK, ParaView, meshio and write_vtu produce.
/// Errors (io_error) name the file and the line of the element at fault: malformed XML, a missing
/// array, a count that does not match, a vertex index out of range, a NaN or infinite coordinate,
/// an unsupported compressor (LZ4, LZMA) or data type.
vtu_grid read_vtu(const std::string& path);

}  // namespace gsse::io
