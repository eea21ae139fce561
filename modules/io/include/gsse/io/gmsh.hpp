#pragma once
// Gmsh .msh version 4.1 and 2.2, ASCII and binary (2.2 written ASCII only). Physical groups of the top
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
/// surface's first physical tag (named, in plc::marker_names, by the group's $PhysicalNames
/// entry), else its entity tag, negated when the file has surface physical groups. Points are the nodes used by these
/// elements, in file order. Each volume entity of $Entities (4.1) becomes a plc_volume in file
/// order: number = its first physical tag (volumes sharing one form one segment), else its entity
/// tag; name from $PhysicalNames, else "region_<n>"; facets = those of its bounding surfaces.
/// Surfaces that bound no volume stay facets (embedded). Errors: volume elements (a volume mesh:
/// read_msh), element types other than linear triangles and quadrangles, a volume whose boundary
/// is not closed (an edge in an odd number of its faces) or has no elements, and, without volume
/// entities, a surface that is not closed (an edge in one face).
plc<3> read_msh_plc(const std::string& path, std::vector<plc_volume>* volumes = nullptr);

enum class msh_version { v41, v22 };

/// Writes .msh 4.1 (ASCII, or binary if `binary`) or 2.2 (ASCII; the version devsim reads):
/// - one entity and one named physical group per segment (dimension D, tag = segment number), one
///   element block per segment in segment order, cell vertex order kept (Gmsh's orientation);
/// - the boundary, interface and marked faces (domain::marked_faces) as elements of dimension
///   D-1 (triangles, 2D: lines), one entity per (marker, segment on each side); a physical group
///   per nonzero facet marker (tag = the marker when positive, else after the others; name from
///   domain::marker_names, else "facet_<marker>") and per interface between two segments (name
///   "<first>:<second>", first = lower segment number; tags after the positive markers);
/// - all nodes (tag = vertex id + 1) in one block.
/// Faces in no group (unmarked outer boundary) are left out, as Gmsh leaves out elements without
/// a physical group. In 2.2 a face is written once per physical group of its entity, with the
/// same element number (Gmsh's own convention).
template <std::size_t D>
void write_msh(const domain<D>& d, const std::string& path, bool binary = false, msh_version version = msh_version::v41);

}  // namespace gsse::io
