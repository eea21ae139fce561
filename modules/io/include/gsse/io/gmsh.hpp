#pragma once
// Gmsh .msh version 4.1, ASCII and binary. Physical groups of the top dimension are the
// segments (physical tag = segment number, $PhysicalNames = segment name); triangles make a 2D
// mesh, tetrahedra a 3D one; lower-dimensional elements are read and skipped.
#include <string>
#include <variant>

#include "gsse/container/domain.hpp"
#include "gsse/io/error.hpp"

namespace gsse::io {

/// Reads a .msh 4.1 file as a domain<D>. Each element block of dimension D goes to the segment
/// of its entity's first physical tag (entity without one: number = entity tag, "region_<tag>").
/// Segments appear in order of their first element block; points are all nodes in file order.
template <std::size_t D>
domain<D> read_msh(const std::string& path);
/// Reads a .msh 4.1 file; 3D if it has tetrahedra, else 2D.
std::variant<domain<2>, domain<3>> read_msh_any(const std::string& path);

/// Writes .msh 4.1 (ASCII, or binary if `binary`): one entity and one named physical group per
/// segment (tag = segment number), all nodes (tag = vertex id + 1) in one block, and one element
/// block per segment in segment order. Cell vertex order is kept (Gmsh's positive orientation).
template <std::size_t D>
void write_msh(const domain<D>& d, const std::string& path, bool binary = false);

}  // namespace gsse::io
