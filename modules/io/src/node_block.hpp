#pragma once
// Internal: the point block shared by .poly and .node/.ele readers.
#include <cstddef>
#include <vector>

#include "gsse/geometry/point.hpp"
#include "gsse/io/text_reader.hpp"

namespace gsse::io::detail {
/// Reads `count` point lines (numbered from 0 or 1). Returns the index base (0 or 1).
template <std::size_t D>
long read_node_block(text_reader& r, long count, long attributes, long markers, std::vector<point<D>>& pts,
                     std::vector<int>& point_markers, std::vector<std::size_t>& lines);
}  // namespace gsse::io::detail
