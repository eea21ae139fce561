#pragma once
// The size field's inputs from files: the BASE.json sidecar's sizing keys (gsse/io/sidecar.hpp)
// and a background mesh, TetGen/Triangle BASE.node + BASE.ele with BASE.mtr (one size per node,
// TetGen's metric file: a line '<#points> 1', then one value per line).
#include <memory>
#include <string>
#include <vector>

#include "gsse/io/sidecar.hpp"
#include "gsse/sizing/size_field.hpp"

namespace gsse::sizing {

/// Reads a background size mesh: a .vtu (tetrahedra, 2D: triangles in the xy plane, with the point
/// array "size"; other cells of lower dimension are skipped, hexahedra and the like refused), or
/// BASE.node, BASE.ele and BASE.mtr (`path` is BASE or any of the three). Errors name the file and
/// line: a missing file or array, a count that does not match the nodes, a size that is not
/// positive.
template <std::size_t D>
std::shared_ptr<const typename spec<D>::background_mesh> read_background(const std::string& path);

/// The files read_background reads for `path`: the .vtu itself, or BASE.node, BASE.ele and
/// BASE.mtr (only a trailing .node, .ele or .mtr is taken off `path`; any other name is BASE).
std::vector<std::string> background_files(const std::string& path);

/// Adds the sidecar's sizing keys to `s`: segment sizes and interfaces by segment name (as the
/// PLC's regions are named) or number, boxes of the PLC's dimension, the background mesh (path
/// relative to the sidecar's folder) and the grade. Unknown names and wrong dimensions are
/// io_errors naming the sidecar file and line.
template <std::size_t D>
void add_sidecar(spec<D>& s, const io::sizing_table& t, const plc<D>& p, const std::string& sidecar_path);

}  // namespace gsse::sizing
