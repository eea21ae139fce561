#pragma once
// Piecewise linear complex: the input geometry of the mesher. In 3D a facet is a set of coplanar
// polygons (outer loops, inner loops, and 1- or 2-vertex polygons for embedded points and edges)
// plus hole points in its plane; in 2D the PLC holds segments (edges). Region points name and
// number the segments of the domain; hole points mark regions that are not meshed.
#include <algorithm>
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

/// The length of the shortest input edge (2D: segment; 3D: side of a facet polygon, or a 2-vertex
/// polygon), the smallest feature the input itself draws; 0 if there is none. The summary reports
/// the mesh's shortest edge against it (a mesh edge far below it is the mesher's doing).
template <std::size_t D>
double shortest_input_edge(const plc<D>& p) {
  double best = -1;
  auto see = [&](vertex_id a, vertex_id b) {
    if (a == b || a >= p.points.size() || b >= p.points.size()) return;
    const double l = distance(p.points[a], p.points[b]);
    if (best < 0 || l < best) best = l;
  };
  if constexpr (D == 2) {
    for (const auto& e : p.edges) see(e[0], e[1]);
  } else {
    for (const auto& f : p.facets)
      for (const auto& poly : f.polygons)
        for (std::size_t i = 0; poly.size() >= 2 && i < (poly.size() == 2 ? 1 : poly.size()); ++i)
          see(poly[i], poly[(i + 1) % poly.size()]);
  }
  return std::max(best, 0.0);
}

}  // namespace gsse
