#pragma once
// Piecewise linear complex: the input geometry of the mesher. In 3D a facet is a set of coplanar
// polygons (outer loops, inner loops, and 1- or 2-vertex polygons for embedded points and edges)
// plus hole points in its plane; in 2D the PLC holds segments (edges). Region points name and
// number the segments of the domain; hole points mark regions that are not meshed.
#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "gsse/geometry/point.hpp"
#include "gsse/topology/simplex.hpp"

namespace gsse {

struct plc_facet {
  std::vector<std::vector<vertex_id>> polygons;
  std::vector<point3> holes;
  int marker = 0;
  std::size_t line = 0;  // source line, for messages
};

template <std::size_t D>
struct plc_region {
  point<D> at{};
  int number = 0;
  double max_volume = -1;  // < 0: no constraint
  std::string name;
};

template <std::size_t D>
struct plc {
  static constexpr std::size_t dimension = D;
  std::string source;  // file the PLC came from, for messages
  std::vector<point<D>> points;
  std::vector<int> point_markers;
  std::vector<plc_facet> facets;                    // 3D
  std::vector<std::array<vertex_id, 2>> edges;      // 2D segments
  std::vector<int> edge_markers;                    // 2D
  std::vector<point<D>> holes;
  std::vector<plc_region<D>> regions;
  std::map<int, std::string> marker_names;          // facet (2D: segment) marker -> name
};

}  // namespace gsse
