#pragma once
// The BASE.json sidecar that carries what TetGen/Triangle files cannot hold: segment names and
// their order. Format (a subset of the benchmark generator's metadata file):
//   {"segments": ["substrate", "oxide"], "numbers": [1, 7], "face_marker_base": 100,
//    "facets": {"77": "drain_contact", "78": "source_contact"}}
// names[k] belongs to numbers[k]; without "numbers", names[k] belongs to segment k+1. "facets"
// names facet markers (2D: segment markers): the names of their boundary groups in the output.
// Sizing (modules/sizing), all optional:
//   "sizes": {"oxide": 0.002, "3": 0.1}          maximum size per segment (name or number)
//   "refine": [{"lo": [x, y, z], "hi": [x, y, z], "size": h}]   size inside a box
//   "interfaces": [{"between": ["oxide", "silicon"], "size": h}]  size on an interface
//     (a box or interface may add "grade": g, its own growth away from it; else "grade" below)
//   "background": "bg.node"                       a background mesh BASE.node/.ele/.mtr or a .vtu, relative
//                                                 to the sidecar's folder
//   "grade": 1.3                                  the grading limit (--grade overrides it)
#include <map>
#include <string>
#include <vector>

#include "gsse/io/error.hpp"

namespace gsse::io {

struct sizing_table {
  struct size_entry {
    std::string segment;  // a name, or a number written as a string
    double size;
    std::size_t line;
  };
  std::vector<size_entry> sizes;
  struct box {
    std::vector<double> lo, hi;  // 2 or 3 coordinates
    double size;
    std::size_t line;
    double grade = 0;  // its own growth rate; 0: the table's
  };
  std::vector<box> boxes;
  struct interface_layer {
    std::string a, b;
    double size;
    std::size_t line;
    double grade = 0;  // its own growth rate; 0: the table's
  };
  std::vector<interface_layer> interfaces;
  std::string background;  // path as written in the file
  double grade = 0;        // 0: not stated
  bool empty() const { return sizes.empty() && boxes.empty() && interfaces.empty() && background.empty() && grade == 0; }
};

struct segment_table {
  std::vector<std::string> names;
  std::vector<int> numbers;  // empty: names[k] is segment k+1
  int face_marker_base = 0;  // 0: not stated
  std::map<int, std::string> facet_names;  // facet marker -> name
  sizing_table sizing;                     // read only, never written back
  /// Name of segment `number`, or "" if the table has none.
  std::string name_of(int number) const;
};

/// Reads the sidecar; a missing file gives an empty table, a malformed or unreadable one an
/// io_error naming the file and line.
segment_table read_sidecar(const std::string& json_path);
/// `n` as a JSON string: quoted, with '"' and '\\' escaped, newline and tab as \n and \t.
std::string json_string(const std::string& n);
/// Writes the sidecar atomically.
void write_sidecar(const std::string& json_path, const segment_table& t);
/// BASE of BASE.ext (directory kept).
std::string base_of(const std::string& path);

}  // namespace gsse::io
