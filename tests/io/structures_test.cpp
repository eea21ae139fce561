// Every benchmark structure of ../shared/bench/structures.py, in 2D and 3D, reads with the
// numbers of points, facets (segments in 2D) and segments its generator reports in NAME.json.
// Without ../shared the test prints "SKIPPED: ../shared absent", which ctest reports as skipped.
#define BOOST_TEST_MODULE io_structures
#include <boost/test/unit_test.hpp>

#include <cstdlib>
#include <iostream>
#include <set>

#include "gsse/io/poly.hpp"
#include "gsse/io/sidecar.hpp"
#include "io_test_util.hpp"

using namespace gsse;

namespace {
// GSSE_SHARED_DIR overrides the location (and lets the skip path be tried)
const std::string script = std::string(std::getenv("GSSE_SHARED_DIR") ? std::getenv("GSSE_SHARED_DIR")
                                                                       : GSSE_SOURCE_DIR "/../shared") +
                           "/bench/structures.py";

long json_number(const std::string& json, const std::string& key) {
  const auto k = json.find("\"" + key + "\":");
  BOOST_TEST_REQUIRE(k != std::string::npos, key << " missing from the generator's json");
  return std::strtol(json.c_str() + k + key.size() + 3, nullptr, 10);
}

template <class P>
std::size_t distinct_region_numbers(const P& p) {
  std::set<int> s;
  for (const auto& r : p.regions) s.insert(r.number);
  return s.size();
}
}  // namespace

BOOST_AUTO_TEST_CASE(benchmark_structures_read) {
  if (!std::filesystem::exists(script)) {
    std::cout << "SKIPPED: ../shared absent (" << script << ")" << std::endl;
    BOOST_TEST_MESSAGE("SKIPPED: ../shared absent");
    return;
  }
  test::scratch_dir dir("structures");
  for (const char* name : {"mosfet", "diffusion", "trench", "finfet"})
    for (int dim : {2, 3}) {
      const auto out = dir.file(std::to_string(dim) + "d");
      const std::string cmd = "python3 '" + script + "' " + name + " --dim " + std::to_string(dim) + " --out '" + out + "' > /dev/null";
      BOOST_TEST_REQUIRE(std::system(cmd.c_str()) == 0, cmd);
      const auto base = out + "/" + name;
      const auto json = test::slurp_file(base + ".json");
      const auto names = io::read_sidecar(base + ".json").names;
      const auto any = io::read_plc(base + ".poly");
      BOOST_TEST_CONTEXT(name << " " << dim << "D") {
        if (dim == 3) {
          BOOST_TEST_REQUIRE(std::holds_alternative<plc<3>>(any));
          const auto& p = std::get<plc<3>>(any);
          BOOST_TEST(static_cast<long>(p.points.size()) == json_number(json, "points"));
          BOOST_TEST(static_cast<long>(p.facets.size()) == json_number(json, "facets"));
          BOOST_TEST(distinct_region_numbers(p) == names.size());
          for (const auto& r : p.regions) BOOST_TEST(r.name == names.at(static_cast<std::size_t>(r.number - 1)));
        } else {
          BOOST_TEST_REQUIRE(std::holds_alternative<plc<2>>(any));
          const auto& p = std::get<plc<2>>(any);
          BOOST_TEST(static_cast<long>(p.points.size()) == json_number(json, "points"));
          BOOST_TEST(static_cast<long>(p.edges.size()) == json_number(json, "facets"));
          BOOST_TEST(distinct_region_numbers(p) == names.size());
          for (const auto& r : p.regions) BOOST_TEST(r.name == names.at(static_cast<std::size_t>(r.number - 1)));
        }
      }
    }
}
