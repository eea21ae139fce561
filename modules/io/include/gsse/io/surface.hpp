#pragma once
// Closed triangulated/polygonal surfaces (OFF; STL ASCII and binary) read as a 3D PLC: one or
// several shells, disjoint, nested or sharing faces. Such a PLC has no region points: `regions`
// is empty, and the labelling makes every bounded cell a segment (numbered 1, 2, ... in its
// order); a single cell is named single_segment_name(plc.source) (the file stem).
#include <string>

#include "gsse/container/plc.hpp"
#include "gsse/io/error.hpp"

namespace gsse::io {

/// OFF: 'OFF' header, '<#vertices> <#faces> <#edges>', vertices, faces 'n i0 .. in-1' (0-based).
/// Every face is one facet (marker 0). The surface must be closed (each edge in two or more faces).
plc<3> read_off(const std::string& path);
/// STL, ASCII or binary (detected from the size stated in the binary header). Vertices with
/// bitwise-equal coordinates are merged (-0.0 counts as 0.0); each triangle is one facet.
plc<3> read_stl(const std::string& path);
/// Segment name of a PLC without region points: the stem of its source file.
std::string single_segment_name(const std::string& source);

}  // namespace gsse::io
