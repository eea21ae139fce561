#pragma once
// The BASE.json sidecar that carries what TetGen/Triangle files cannot hold: segment names and
// their order. Format (a subset of the benchmark generator's metadata file):
//   {"segments": ["substrate", "oxide"], "numbers": [1, 7], "face_marker_base": 100,
//    "facets": {"77": "drain_contact", "78": "source_contact"}}
// names[k] belongs to numbers[k]; without "numbers", names[k] belongs to segment k+1. "facets"
// names facet markers (2D: segment markers): the names of their boundary groups in the output.
#include <map>
#include <string>
#include <vector>

#include "gsse/io/error.hpp"

namespace gsse::io {

struct segment_table {
  std::vector<std::string> names;
  std::vector<int> numbers;  // empty: names[k] is segment k+1
  int face_marker_base = 0;  // 0: not stated
  std::map<int, std::string> facet_names;  // facet marker -> name
  /// Name of segment `number`, or "" if the table has none.
  std::string name_of(int number) const;
};

/// Reads the sidecar; a missing file gives an empty table, a malformed or unreadable one an
/// io_error naming the file and line.
segment_table read_sidecar(const std::string& json_path);
/// Writes the sidecar atomically.
void write_sidecar(const std::string& json_path, const segment_table& t);
/// BASE of BASE.ext (directory kept).
std::string base_of(const std::string& path);

}  // namespace gsse::io
