#pragma once
// Small hand-made 3D PLCs for tests: points are merged by coordinates, so facets given by corners
// share vertices where they touch; facet k gets input line `first_line + line_step * k`.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "gsse/container/plc.hpp"

namespace gsse::test {

struct plc_builder {
  plc<3> p;
  std::map<point3, vertex_id> ids;
  std::size_t first_line = 10, line_step = 2;
  explicit plc_builder(std::string source = "cube.poly", std::size_t step = 2) : line_step(step) { p.source = std::move(source); }

  vertex_id id(const point3& x) {
    auto [it, fresh] = ids.try_emplace(x, static_cast<vertex_id>(p.points.size()));
    if (fresh) p.points.push_back(x);
    return it->second;
  }
  std::vector<vertex_id> loop(const std::vector<point3>& corners) {
    std::vector<vertex_id> l;
    for (const auto& c : corners) l.push_back(id(c));
    return l;
  }
  std::uint32_t facet(const std::vector<std::vector<point3>>& polygons, const std::vector<point3>& holes = {},
                      int marker = 0) {
    plc_facet f;
    for (const auto& poly : polygons) f.polygons.push_back(loop(poly));
    f.holes = holes;
    f.marker = marker;
    f.line = first_line + line_step * p.facets.size();
    p.facets.push_back(f);
    return static_cast<std::uint32_t>(p.facets.size() - 1);
  }
  std::uint32_t facet(const std::vector<point3>& corners) { return facet(std::vector<std::vector<point3>>{corners}); }
  /// Axis-aligned box, facets in the order of tests/pipeline/cli_errors.sh: bottom, top, y = lo,
  /// x = hi, y = hi, x = lo.
  void box(const point3& l, const point3& h) {
    auto P = [&](int i, int j, int k) { return point3{i ? h[0] : l[0], j ? h[1] : l[1], k ? h[2] : l[2]}; };
    facet({P(0, 0, 0), P(1, 0, 0), P(1, 1, 0), P(0, 1, 0)});
    facet({P(0, 0, 1), P(1, 0, 1), P(1, 1, 1), P(0, 1, 1)});
    facet({P(0, 0, 0), P(1, 0, 0), P(1, 0, 1), P(0, 0, 1)});
    facet({P(1, 0, 0), P(1, 1, 0), P(1, 1, 1), P(1, 0, 1)});
    facet({P(1, 1, 0), P(0, 1, 0), P(0, 1, 1), P(1, 1, 1)});
    facet({P(0, 1, 0), P(0, 0, 0), P(0, 0, 1), P(0, 1, 1)});
  }
  std::string num(const point3& x) { return std::to_string(id(x) + 1); }
};

}  // namespace gsse::test
