// libFuzzer target for one reader, chosen at compile time by GSSE_FUZZ_READER. The input is
// written to a file (the readers take paths, as the CLI does) and read; gsse::io::io_error is the
// only acceptable failure: anything else (crash, sanitizer report, other exception, a leak, a
// timeout or an out-of-memory from an unbounded count) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "gsse/io/gmsh.hpp"
#include "gsse/io/node_ele.hpp"
#include "gsse/io/poly.hpp"
#include "gsse/io/sidecar.hpp"
#include "gsse/io/surface.hpp"
#include "gsse/io/vtu.hpp"

#ifndef GSSE_FUZZ_READER
#error "define GSSE_FUZZ_READER"
#endif

namespace {
const std::string& dir() {
  // leaked on purpose: the exit handler below runs after static destructors would have run
  static const std::string* d = [] {
    auto p = std::filesystem::temp_directory_path() / ("gsse_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(p);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(dir(), ec);
    });
    return new std::string(p.string());
  }();
  return *d;
}
std::string put(const std::string& name, const char* data, std::size_t size) {
  const auto p = dir() + "/" + name;
  std::ofstream(p, std::ios::binary | std::ios::trunc).write(data, static_cast<std::streamsize>(size));
  return p;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  const auto* data = reinterpret_cast<const char*>(bytes);
  const std::string reader = GSSE_FUZZ_READER;
  try {
    if (reader == "poly") {
      (void)gsse::io::read_plc(put("in.poly", data, size));
    } else if (reader == "smesh") {
      (void)gsse::io::read_plc(put("in.smesh", data, size));
    } else if (reader == "node") {
      (void)gsse::io::read_node<3>(put("in.node", data, size));
    } else if (reader == "off") {
      (void)gsse::io::read_plc(put("in.off", data, size));
    } else if (reader == "stl") {
      (void)gsse::io::read_plc(put("in.stl", data, size));
    } else if (reader == "msh") {
      (void)gsse::io::read_msh_any(put("in.msh", data, size));
    } else if (reader == "msh_plc") {  // a surface mesh read as a PLC, with its volumes
      std::vector<gsse::io::plc_volume> volumes;
      (void)gsse::io::read_plc(put("in.msh", data, size), &volumes);
    } else if (reader == "vtu") {
      (void)gsse::io::read_vtu(put("in.vtu", data, size));
    } else if (reader == "sidecar") {
      (void)gsse::io::read_sidecar(put("in.json", data, size));
    } else if (reader == "node_ele") {
      // input: the .node file, a line "---", then the .ele file
      const std::string s(data, size);
      const auto cut = s.find("\n---\n");
      std::filesystem::remove(dir() + "/m.json");
      put("m.node", s.data(), cut == std::string::npos ? s.size() : cut + 1);
      const std::string ele = cut == std::string::npos ? std::string() : s.substr(cut + 5);
      put("m.ele", ele.data(), ele.size());
      (void)gsse::io::read_tetgen_mesh(dir() + "/m");
    }
  } catch (const gsse::io::io_error&) {
  }
  return 0;
}
