#pragma once
// The boundary, interface and marked faces of a mesh with their markers and sides: what the
// writers put in BASE.face/.edge, the Gmsh surface groups and BASE.boundary.vtu, for callers that
// want them as data (the Python module's Mesh.faces).
#include <array>
#include <string>
#include <vector>

#include "gsse/container/domain.hpp"

namespace gsse::io {

template <std::size_t D>
struct boundary_face {
  std::array<vertex_id, D> vertices;  // oriented into `segment`
  int marker;                         // the input facet's marker (domain::marked_faces), 0: none
  int segment;                        // number of the segment it faces into (lower at an interface); 0: a marked face inside a segment
  int other;                          // number of the segment behind it, 0 outside (and for a marked face inside a segment)
};

/// Every boundary and interface face once (interfaces oriented into the segment of lower
/// number), then the marked faces inside a segment; deterministic order (segments, cells,
/// faces). Throws io_error naming `what` if a face is shared by more than two cells. The domain
/// need not be finalized.
template <std::size_t D>
std::vector<boundary_face<D>> boundary_faces(const domain<D>& d, const std::string& what = "mesh");

}  // namespace gsse::io
