// Meshes a .poly given on the command line through the installed library and prints
// "<points> <cells> <problems>"; the test compares it with gsse-mesh on the same input.
#include <cstdio>
#include <variant>

#include "gsse/io/poly.hpp"
#include "gsse/pipeline/pipeline.hpp"

int main(int argc, char** argv) {
  if (argc < 3) return 2;
  const auto input = gsse::io::read_plc(argv[1]);
  const auto& p = std::get<gsse::plc<3>>(input);
  gsse::pipeline::options o;
  o.size = std::atof(argv[2]);
  o.verify = true;
  gsse::pipeline::report r;
  const auto d = gsse::pipeline::mesh(p, {}, o, r);
  std::size_t cells = 0;
  for (const auto& s : d.segments()) cells += s.num_cells();
  std::printf("%zu %zu %zu\n", d.points().size(), cells, r.problems.size());
  return r.problems.empty() ? 0 : 1;
}
