// Helper for the meshio cross-check (check_meshio.py):
//   io_write_samples DIR              writes 2D/3D samples as .vtu, ASCII .msh and binary .msh,
//                                     plus DIR/manifest.txt with the counts a reader must find
//   io_write_samples --read FILE N M  reads FILE (.msh) and checks N points and M cells; prints
//                                     "segment <number> <cells>" lines for the caller to compare
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "../support/fixtures.hpp"
#include "gsse/io/gmsh.hpp"
#include "gsse/io/vtu.hpp"

namespace {

template <std::size_t D>
gsse::domain<D> sample() {
  std::array<int, D> n;
  n.fill(2);
  n[0] = 4;
  auto d = gsse::test::make_two_segment_domain<D>(n, 2.5);
  d.segments()[0].set_name("silicon");
  d.segments()[0].set_number(4);
  d.segments()[1].set_name("oxide");
  d.segments()[1].set_number(2);
  // values the reader can check: silicon's potential is x + 2y (+ 3z) at every vertex, oxide's
  // 0.5 but its segment number at vertex 0; each cell's "volume" is its signed volume (area in
  // 2D), so coordinates, connectivity, orientation and cell data are checked together
  for (auto& s : d.segments()) {
    auto q = gsse::add_quantity<double>(s, gsse::on_vertices, "potential", 0.5);
    auto pv = gsse::values(s, q);
    if (s.name() == "silicon")
      for (std::size_t v = 0; v < d.points().size(); ++v) {
        const auto& x = d.points()[v];
        pv[v] = D == 3 ? x[0] + 2 * x[1] + 3 * x[D - 1] : x[0] + 2 * x[1];
      }
    else
      pv[0] = static_cast<double>(s.number());
    auto vol = gsse::add_quantity<double>(s, gsse::on_cells, "volume", 1.0);
    auto cv = gsse::values(s, vol);
    for (std::size_t c = 0; c < s.num_cells(); ++c) {
      const auto cell = s.cell(static_cast<gsse::cell_id>(c));
      const auto& a = d.points()[cell[0]];
      std::array<std::array<double, D>, D> m;
      for (std::size_t i = 0; i < D; ++i)
        for (std::size_t k = 0; k < D; ++k) m[i][k] = d.points()[cell[i + 1]][k] - a[k];
      if constexpr (D == 3)
        cv[c] = (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])) / 6;
      else
        cv[c] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / 2;
    }
  }
  return d;
}

template <std::size_t D>
void write(const std::string& dir, std::ofstream& manifest) {
  const auto d = sample<D>();
  const std::string stem = dir + "/sample" + std::to_string(D) + "d";
  gsse::io::write_vtu(d, stem + ".vtu");
  gsse::io::write_msh(d, stem + ".msh", false);
  gsse::io::write_msh(d, stem + "_binary.msh", true);
  std::size_t cells = 0;
  for (const auto& s : d.segments()) cells += s.num_cells();
  for (const char* f : {".vtu", ".msh", "_binary.msh"}) {
    manifest << stem << f << ' ' << d.points().size() << ' ' << cells;
    for (const auto& s : d.segments()) manifest << ' ' << s.number() << ' ' << s.num_cells();
    manifest << '\n';
  }
}

}  // namespace

int main(int argc, char** argv) try {
  if (argc == 5 && std::string(argv[1]) == "--read") {
    auto any = gsse::io::read_msh_any(argv[2]);
    return std::visit(
        [&](const auto& d) {
          std::size_t cells = 0;
          for (const auto& s : d.segments()) {
            cells += s.num_cells();
            std::printf("segment %d %zu %s\n", s.number(), s.num_cells(), s.name().c_str());
          }
          const bool ok = d.points().size() == std::stoul(argv[3]) && cells == std::stoul(argv[4]);
          if (!ok) std::fprintf(stderr, "read %zu points, %zu cells\n", d.points().size(), cells);
          return ok ? 0 : 1;
        },
        any);
  }
  if (argc != 2) {
    std::fprintf(stderr, "usage: io_write_samples DIR | --read FILE POINTS CELLS\n");
    return 2;
  }
  std::filesystem::create_directories(argv[1]);
  std::ofstream manifest(std::string(argv[1]) + "/manifest.txt");
  write<2>(argv[1], manifest);
  write<3>(argv[1], manifest);
  return manifest ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "io_write_samples: %s\n", e.what());
  return 1;
}
