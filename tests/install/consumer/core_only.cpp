// The header-only core alone: a domain, a segment, its boundary facets.
#include <cstdio>

#include "gsse/gsse.hpp"

int main() {
  gsse::domain<2> d;
  for (auto [x, y] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}}) d.add_point({x, y});
  auto& s = d.add_segment("silicon", 1);
  s.add_cell({0, 1, 2});
  s.add_cell({1, 3, 2});
  s.finalize();
  std::printf("%zu\n", gsse::boundary_facets(s).size());
  return gsse::boundary_facets(s).size() == 4 ? 0 : 1;
}
