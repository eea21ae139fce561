#pragma once
// TetGen (.node/.ele/.face) and Triangle (.node/.ele/.edge) meshes. The element attribute is the
// segment number; segment names and order travel in the BASE.json sidecar (gsse/io/sidecar.hpp).
#include <string>

#include "gsse/container/domain.hpp"
#include "gsse/io/error.hpp"

namespace gsse::io {

/// Reads BASE.node and BASE.ele (`path` is BASE or BASE.node/.ele/.face/.edge) into a domain with
/// one segment per element attribute value, in order of first appearance (no attribute: segment 1).
/// Names come from BASE.json, else "region_<n>". BASE.face (3D) / BASE.edge (2D) is checked if
/// present (indices in range) but not kept: interfaces follow from the cells.
template <std::size_t D>
domain<D> read_node_ele(const std::string& path);
inline domain<3> read_tetgen_mesh(const std::string& path) { return read_node_ele<3>(path); }
inline domain<2> read_triangle_mesh(const std::string& path) { return read_node_ele<2>(path); }

/// Writes BASE.node, BASE.ele (attribute = segment number, indices from 1), BASE.face (3D) or
/// BASE.edge (2D) with every boundary and interface facet once, and BASE.json. A facet between
/// segments a and b (number a < b) is oriented into a (its vertices are a facet of a's cell) and
/// has marker a*M + b; a boundary facet of a is oriented into a with marker a*M, where
/// M = face_marker_base in BASE.json (100 when all numbers are below 100). All files are
/// committed only after every one of them was written. `threads` format the text in parallel; the
/// bytes are the same for any number.
template <std::size_t D>
void write_node_ele(const domain<D>& d, const std::string& base, unsigned threads = 1);

}  // namespace gsse::io
