#pragma once
// Internal: the point block shared by .poly and .node/.ele readers.
#include <cstddef>
#include <string>
#include <vector>

#include "gsse/geometry/point.hpp"
#include "gsse/io/text_reader.hpp"

namespace gsse::io::detail {

/// Reads a point reference (numbered from `base`) and checks it against the `n` points read.
inline vertex_id vertex_ref(text_reader& r, long base, std::size_t n, const char* what) {
  const long v = r.integer(what);
  if (v < base || v >= base + static_cast<long>(n))
    r.fail(std::string(what) + " " + std::to_string(v) + " out of range [" + std::to_string(base) + ", " +
           std::to_string(base + static_cast<long>(n) - 1) + "]");
  return static_cast<vertex_id>(v - base);
}
/// Reads `count` point lines (numbered from 0 or 1). Returns the index base (0 or 1).
template <std::size_t D>
long read_node_block(text_reader& r, long count, long attributes, long markers, std::vector<point<D>>& pts,
                     std::vector<int>& point_markers, std::vector<std::size_t>& lines);
}  // namespace gsse::io::detail
