// gsse-mesh: command-line front end. Reads a PLC and reports its segments.
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <variant>

#include "gsse/io/poly.hpp"

namespace {

void usage(std::FILE* to) {
  std::fputs(
      "usage: gsse-mesh INPUT [--quiet]\n"
      "  INPUT  TetGen .poly/.smesh (3D) or Triangle .poly (2D) piecewise linear complex\n"
      "Prints the segments (regions) of the PLC.\n",
      to);
}

template <std::size_t D>
void report(const gsse::plc<D>& p) {
  std::printf("%s: %zuD PLC, %zu points, %zu %s, %zu holes, %zu segments\n", p.source.c_str(), D, p.points.size(),
              D == 3 ? p.facets.size() : p.edges.size(), D == 3 ? "facets" : "segments (edges)", p.holes.size(),
              p.regions.size());
  for (const auto& g : p.regions) {
    std::printf("  segment %d %-16s region point (", g.number, g.name.c_str());
    for (std::size_t k = 0; k < D; ++k) std::printf(k ? ", %g" : "%g", g.at[k]);
    std::printf(")\n");
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string input;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help")) {
      usage(stdout);
      return 0;
    }
    if (!std::strcmp(argv[i], "--quiet")) continue;
    if (argv[i][0] == '-') {
      std::fprintf(stderr, "gsse-mesh: unknown option '%s'\n", argv[i]);
      usage(stderr);
      return 2;
    }
    if (!input.empty()) {
      std::fprintf(stderr, "gsse-mesh: more than one input given ('%s', '%s')\n", input.c_str(), argv[i]);
      return 2;
    }
    input = argv[i];
  }
  if (input.empty()) {
    usage(stderr);
    return 2;
  }
  try {
    std::visit([](const auto& p) { report(p); }, gsse::io::read_plc(input));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gsse-mesh: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
