#pragma once
// Gmsh .msh version 4.1 (and 2.2 for reading), ASCII and binary. Physical groups of the top
// dimension are the segments (physical tag = segment number, $PhysicalNames = segment name);
// triangles make a 2D mesh, tetrahedra a 3D one; lower-dimensional elements are read and skipped.
// A file without volume elements can also be read as a surface PLC (read_msh_plc).
#include <string>
#include <variant>
#include <vector>

#include "gsse/container/domain.hpp"
#include "gsse/io/error.hpp"
#include "gsse/io/poly.hpp"

namespace gsse::io {

/// Reads a .msh 4.1 or 2.2 file as a domain<D>. Each element block of dimension D goes to the segment
/// of its entity's first physical tag (entity without one: number = entity tag, "region_<tag>").
/// Segments appear in order of their first element block; points are all nodes in file order.
template <std::size_t D>
domain<D> read_msh(const std::string& path);
/// Reads a .msh 4.1 or 2.2 file; 3D if it has tetrahedra, else 2D.
std::variant<domain<2>, domain<3>> read_msh_any(const std::string& path);

/// Reads a Gmsh surface mesh (4.1 or 2.2, ASCII or binary, e.g. `gmsh -2 -save_all`) as a PLC:
/// every triangle and quadrangle (one polygon) of a surface entity is a facet whose marker is the
/// surface's first physical tag, else its entity tag. Points are the nodes used by these
/// elements, in file order. Each volume entity of $Entities (4.1) becomes a plc_volume in file
/// order: number = its first physical tag (volumes sharing one form one segment), else its entity
/// tag; name from $PhysicalNames, else "region_<n>"; facets = those of its bounding surfaces.
/// Surfaces that bound no volume stay facets (embedded). Errors: volume elements (a volume mesh:
/// read_msh), element types other than linear triangles and quadrangles, a volume whose boundary
/// is not closed (an edge in an odd number of its faces) or has no elements, and, without volume
/// entities, a surface that is not closed (an edge in one face).
plc<3> read_msh_plc(const std::string& path, std::vector<plc_volume>* volumes = nullptr);

/// Writes .msh 4.1 (ASCII, or binary if `binary`): one entity and one named physical group per
/// segment (tag = segment number), all nodes (tag = vertex id + 1) in one block, and one element
/// block per segment in segment order. Cell vertex order is kept (Gmsh's positive orientation).
template <std::size_t D>
void write_msh(const domain<D>& d, const std::string& path, bool binary = false);

}  // namespace gsse::io
