// check_files INPUT.poly MESH_BASE [--threads N]: runs gsse::verify::check on a mesh read from
// MESH_BASE.node/.ele (element attribute = segment number) against the PLC; prints the problems
// and "verify: PASS" or "verify: FAIL"; exit 0 on PASS, 1 on FAIL, 2 on unreadable input.
// For the shell test that compares the verifier with ../shared's meshcheck on the same files.
#include <chrono>
#include <cstdio>
#include <string>
#include <variant>

#include "gsse/io/node_ele.hpp"
#include "gsse/io/poly.hpp"
#include "gsse/verify/verify.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: check_files INPUT.poly MESH_BASE [--threads N]\n");
    return 2;
  }
  gsse::verify::options o;
  if (argc >= 5 && std::string(argv[3]) == "--threads") o.threads = static_cast<unsigned>(std::stoul(argv[4]));
  try {
    return std::visit(
        [&](const auto& p) {
          constexpr std::size_t D = std::decay_t<decltype(p)>::dimension;
          const auto d = gsse::io::read_node_ele<D>(argv[2]);
          const auto t0 = std::chrono::steady_clock::now();
          const auto r = gsse::verify::check(d, p, o);
          const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          for (const auto& x : r.problems) std::printf("  %s\n", x.c_str());
          std::printf("cells %zu, faces %zu (hull %zu, interface %zu, inexact %zu, spanning %zu), components %zu, "
                      "volume error %.3g, Delaunay ties %zu, deepest %.3g; %.3f s\n",
                      r.cells, r.faces, r.hull_faces, r.interface_faces, r.inexact_faces, r.spanning_faces, r.components,
                      r.volume_error, r.delaunay_ties, r.deepest_delaunay, s);
          std::printf("verify: %s\n", r.ok() ? "PASS" : "FAIL");
          return r.ok() ? 0 : 1;
        },
        gsse::io::read_plc(argv[1]));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "check_files: %s\n", e.what());
    return 2;
  }
}
