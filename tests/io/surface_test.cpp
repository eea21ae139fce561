// Surface inputs as PLCs: Gmsh surface meshes with volumes and physical groups (4.1 and 2.2,
// ASCII and binary, written by gmsh from tests/data/io/msh/three_volumes.geo), region points
// placed inside their volumes (modules/plc), OFF/STL with several shells, and the .poly writers
// (read back equal). The meshes of these inputs must have the segments the files name.
#define BOOST_TEST_MODULE io_surfaces
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstring>
#include <set>
#include <sstream>

#include "gsse/io/gmsh.hpp"
#include "gsse/io/poly.hpp"
#include "gsse/pipeline/pipeline.hpp"
#include "gsse/plc/region_points.hpp"
#include "io_test_util.hpp"

using namespace gsse;

namespace {

const std::string data_dir = std::string(GSSE_SOURCE_DIR) + "/tests/data/io/msh/";

plc<3> read3(const std::string& path, std::vector<io::plc_volume>* volumes = nullptr) {
  auto any = io::read_plc(path, volumes);
  BOOST_TEST_REQUIRE(std::holds_alternative<plc<3>>(any));
  return std::get<plc<3>>(std::move(any));
}

// Same points (bit for bit, or within `rel` relative), markers, facets and regions.
template <std::size_t D>
void require_same(const plc<D>& a, const plc<D>& b, double rel = 0) {
  BOOST_TEST_REQUIRE(a.points.size() == b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i)
    for (std::size_t k = 0; k < D; ++k)
      if (rel == 0)
        BOOST_TEST_REQUIRE(std::memcmp(&a.points[i][k], &b.points[i][k], sizeof(double)) == 0);
      else
        BOOST_TEST_REQUIRE(std::abs(a.points[i][k] - b.points[i][k]) <= rel * (1 + std::abs(a.points[i][k])));
  BOOST_TEST((a.point_markers == b.point_markers));
  BOOST_TEST_REQUIRE(a.facets.size() == b.facets.size());
  for (std::size_t f = 0; f < a.facets.size(); ++f) {
    BOOST_TEST_REQUIRE((a.facets[f].polygons == b.facets[f].polygons));
    BOOST_TEST_REQUIRE(a.facets[f].marker == b.facets[f].marker);
    BOOST_TEST_REQUIRE((a.facets[f].holes == b.facets[f].holes));
  }
  BOOST_TEST((a.edges == b.edges));
  BOOST_TEST((a.edge_markers == b.edge_markers));
  BOOST_TEST((a.holes == b.holes));
  BOOST_TEST_REQUIRE(a.regions.size() == b.regions.size());
  for (std::size_t r = 0; r < a.regions.size(); ++r) {
    BOOST_TEST((a.regions[r].at == b.regions[r].at));
    BOOST_TEST(a.regions[r].number == b.regions[r].number);
    BOOST_TEST(a.regions[r].name == b.regions[r].name);
    BOOST_TEST(a.regions[r].max_volume == b.regions[r].max_volume);
  }
}

template <std::size_t D>
plc<D> write_and_read(const plc<D>& p, const test::scratch_dir& dir, const std::string& name) {
  const auto path = dir.file(name);
  if constexpr (D == 3)
    io::write_tetgen_poly(p, path);
  else
    io::write_triangle_poly(p, path);
  return std::get<plc<D>>(io::read_plc(path));
}

// Volume of each segment of a mesh, by number.
std::map<int, double> volumes_of(const domain<3>& d) {
  std::map<int, double> v;
  for (const auto& s : d.segments())
    for (const auto& c : s.cell_data()) {
      const auto& p = d.points();
      const point3 a = p[c[1]] - p[c[0]], b = p[c[2]] - p[c[0]], e = p[c[3]] - p[c[0]];
      v[s.number()] += std::abs(dot(a, cross(b, e))) / 6;
    }
  return v;
}

domain<3> mesh_verified(const plc<3>& p) {
  pipeline::options o;
  o.verify = true;
  pipeline::report r;
  auto d = pipeline::mesh(p, {}, o, r);
  BOOST_TEST(r.problems.empty());
  return d;
}

// An axis-aligned box as 12 triangles (outward normals) in ASCII STL.
void stl_box(std::ostringstream& o, point3 lo, point3 hi, bool skip_x_max = false) {
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (int q = 0; q < 6; ++q) {
    if (skip_x_max && q == 5) continue;
    auto corner = [&](int i) { return point3{i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]}; };
    for (const auto& t : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
      o << "facet normal 0 0 0\nouter loop\n";
      for (int k : t) {
        const auto c = corner(quads[q][k]);
        o << "vertex " << c[0] << ' ' << c[1] << ' ' << c[2] << '\n';
      }
      o << "endloop\nendfacet\n";
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(msh_surface_volumes_and_physical_groups) {
  std::vector<io::plc_volume> vols;
  const auto p = read3(data_dir + "three_volumes_41.msh", &vols);
  BOOST_TEST(p.regions.empty());  // region points need predicates: placed by modules/plc
  BOOST_TEST_REQUIRE(vols.size() == 3u);
  // volumes in file order: oxide (physical 12), the inclusion (no group: its entity tag), silicon
  BOOST_TEST(vols[0].number == 12);
  BOOST_TEST(vols[0].name == "oxide");
  BOOST_TEST(vols[1].number == vols[1].entity);
  BOOST_TEST(vols[1].name == "region_" + std::to_string(vols[1].entity));
  BOOST_TEST(vols[2].number == 11);
  BOOST_TEST(vols[2].name == "silicon");
  // the interface (physical surface 20) bounds oxide and silicon; the inclusion lies in silicon
  const std::set<std::size_t> oxide(vols[0].facets.begin(), vols[0].facets.end()),
      inclusion(vols[1].facets.begin(), vols[1].facets.end()), silicon(vols[2].facets.begin(), vols[2].facets.end());
  std::size_t interface = 0;
  for (std::size_t f = 0; f < p.facets.size(); ++f) {
    BOOST_TEST_REQUIRE(p.facets[f].polygons.size() == 1u);
    BOOST_TEST_REQUIRE(p.facets[f].polygons[0].size() == 3u);
    BOOST_TEST_REQUIRE(oxide.count(f) + inclusion.count(f) + silicon.count(f) >= 1u);  // no embedded surfaces here
    if (oxide.count(f) && silicon.count(f)) {
      ++interface;
      BOOST_TEST_REQUIRE(p.facets[f].marker == 20);
    }
  }
  BOOST_TEST(interface > 0u);
  for (auto f : inclusion) BOOST_TEST_REQUIRE(silicon.count(f) == 1u);
  // every node is used, and the bounding box is the model's
  std::vector<char> used(p.points.size(), 0);
  for (const auto& f : p.facets)
    for (auto v : f.polygons[0]) used[v] = 1;
  BOOST_TEST(std::count(used.begin(), used.end(), 0) == 0);
}

BOOST_AUTO_TEST_CASE(msh_versions_and_encodings_agree) {
  std::vector<io::plc_volume> v41, v41b, v22, v22b;
  const auto a = read3(data_dir + "three_volumes_41.msh", &v41);
  const auto b = read3(data_dir + "three_volumes_41b.msh", &v41b);
  // gmsh writes ASCII coordinates with 16 digits: equal to the binary doubles within an ulp or two
  require_same(a, b, 1e-15);
  BOOST_TEST_REQUIRE(v41.size() == v41b.size());
  for (std::size_t k = 0; k < v41.size(); ++k) BOOST_TEST((v41[k].facets == v41b[k].facets));
  // 2.2 has no $Entities (no volumes), and gmsh -save_all drops its physical tags: markers are the
  // elementary tags, the interface's (physical 20) included
  const auto c = read3(data_dir + "three_volumes_22.msh", &v22);
  const auto d = read3(data_dir + "three_volumes_22b.msh", &v22b);
  BOOST_TEST(v22.empty());
  BOOST_TEST(v22b.empty());
  require_same(c, d, 1e-15);
  BOOST_TEST_REQUIRE(c.facets.size() == a.facets.size());
  const std::set<std::size_t> oxide(v41[0].facets.begin(), v41[0].facets.end());
  std::set<int> interface_tags;
  for (std::size_t f = 0; f < a.facets.size(); ++f) {
    BOOST_TEST_REQUIRE((c.facets[f].polygons == a.facets[f].polygons));
    if (oxide.count(f) && a.facets[f].marker == 20)  // interface: entity tag in 2.2
      interface_tags.insert(c.facets[f].marker);
    else  // a surface of no group: its entity tag, negated in 4.1, which has a surface group
      BOOST_TEST_REQUIRE((a.facets[f].marker < 0 && c.facets[f].marker == -a.facets[f].marker));
  }
  BOOST_TEST(interface_tags.size() == 1u);
  BOOST_TEST(*interface_tags.begin() != 20);
}

BOOST_AUTO_TEST_CASE(region_points_lie_in_their_volumes) {
  std::vector<io::plc_volume> vols;
  auto p = read3(data_dir + "three_volumes_41.msh", &vols);
  plc_tools::add_region_points(p, vols, 2);
  BOOST_TEST_REQUIRE(p.regions.size() == 3u);
  // boxes: oxide [0,1]^2 x [1,1.5], inclusion [0.4,0.6]^3, silicon the unit cube without it
  auto in = [](const point3& x, point3 lo, point3 hi) {
    for (int k = 0; k < 3; ++k)
      if (!(x[k] > lo[k] && x[k] < hi[k])) return false;
    return true;
  };
  BOOST_TEST(in(p.regions[0].at, {0, 0, 1}, {1, 1, 1.5}));
  BOOST_TEST(in(p.regions[1].at, {0.4, 0.4, 0.4}, {0.6, 0.6, 0.6}));
  BOOST_TEST(in(p.regions[2].at, {0, 0, 0}, {1, 1, 1}));
  BOOST_TEST(!in(p.regions[2].at, {0.4, 0.4, 0.4}, {0.6, 0.6, 0.6}));
  // the same points for any thread count
  auto q = read3(data_dir + "three_volumes_41.msh", &vols);
  plc_tools::add_region_points(q, vols, 1);
  for (std::size_t r = 0; r < 3; ++r) BOOST_TEST((q.regions[r].at == p.regions[r].at));
  // meshed: three segments with the files' numbers and names and the volumes of the boxes
  const auto d = mesh_verified(p);
  BOOST_TEST_REQUIRE(d.segments().size() == 3u);
  const auto vol = volumes_of(d);
  BOOST_TEST(std::abs(vol.at(12) - 0.5) < 1e-9);
  BOOST_TEST(std::abs(vol.at(vols[1].number) - 0.008) < 1e-9);
  BOOST_TEST(std::abs(vol.at(11) - 0.992) < 1e-9);
  BOOST_TEST(d.find("silicon"));
  BOOST_TEST(d.find("oxide"));
}

BOOST_AUTO_TEST_CASE(region_point_missing_for_an_open_volume) {
  std::vector<io::plc_volume> vols;
  auto p = read3(data_dir + "three_volumes_41.msh", &vols);
  // the inclusion's boundary without its first face encloses nothing: no point can be confirmed
  // inside it by the parity test (unless it is closed); a volume listing no facets has none
  std::vector<std::vector<std::size_t>> lists{vols[1].facets, {}};
  lists[0].erase(lists[0].begin());
  const auto at = plc_tools::interior_points(p, lists);
  BOOST_TEST(!at[1].has_value());
  auto bad = vols;
  bad[1].facets.clear();
  BOOST_CHECK_THROW(plc_tools::add_region_points(p, bad), std::runtime_error);
}

BOOST_AUTO_TEST_CASE(stl_with_several_shells_gives_one_segment_per_cell) {
  test::scratch_dir dir("surf_stl");
  struct model {
    const char* name;
    std::vector<std::pair<point3, point3>> boxes;
    bool shared_face;  // the second box reuses the first one's x = 1 face
    std::vector<double> volumes;  // of the segments, sorted
  };
  const std::vector<model> models{{"disjoint.stl", {{{0, 0, 0}, {1, 1, 1}}, {{2, 0, 0}, {4, 2, 2}}}, false, {1, 8}},
                                  {"nested.stl", {{{0, 0, 0}, {3, 3, 3}}, {{1, 1, 1}, {2, 2, 2}}}, false, {1, 26}},
                                  {"touching.stl", {{{0, 0, 0}, {1, 1, 1}}, {{1, 0, 0}, {3, 1, 1}}}, true, {1, 2}}};
  for (const auto& m : models) {
    std::ostringstream o;
    o << "solid two\n";
    stl_box(o, m.boxes[0].first, m.boxes[0].second, m.shared_face);
    stl_box(o, m.boxes[1].first, m.boxes[1].second);
    o << "endsolid two\n";
    const auto p = read3(dir.write(m.name, o.str()));
    BOOST_TEST(p.regions.empty());
    const auto d = mesh_verified(p);
    BOOST_TEST_REQUIRE(d.segments().size() == 2u, m.name);
    std::vector<double> v;
    for (auto [n, x] : volumes_of(d)) v.push_back(x);
    std::sort(v.begin(), v.end());
    for (std::size_t k = 0; k < 2; ++k) BOOST_TEST(std::abs(v[k] - m.volumes[k]) < 1e-9, m.name);
  }
}

BOOST_AUTO_TEST_CASE(poly_writers_round_trip) {
  test::scratch_dir dir("surf_poly");
  // a surface mesh with region points, names going through the sidecar
  std::vector<io::plc_volume> vols;
  auto p = read3(data_dir + "three_volumes_41.msh", &vols);
  plc_tools::add_region_points(p, vols);
  p.regions[0].max_volume = 0.125;
  p.holes.push_back({7.0 / 3, 0.1, -1e-300});
  require_same(p, write_and_read(p, dir, "three.poly"));
  BOOST_TEST(test::slurp_file(dir.file("three.json")).find("\"oxide\"") != std::string::npos);
  // polygons with inner loops, facet holes, embedded edges, point markers
  const auto cube = dir.write("cube.poly",
                              "12 3 0 1\n"
                              "1 0 0 0 5\n2 1 0 0 5\n3 1 1 0\n4 0 1 0\n5 0 0 1\n6 1 0 1\n7 1 1 1\n8 0 1 1\n"
                              "9 0.25 0.25 0\n10 0.75 0.25 0\n11 0.75 0.75 0\n12 0.25 0.75 0\n"
                              "6 1\n"
                              "2 1 11\n4 1 2 3 4\n4 9 10 11 12\n1 0.5 0.5 0\n"
                              "2 0 12\n4 5 6 7 8\n2 5 7\n"
                              "1 0 13\n4 1 2 6 5\n1 0 14\n4 2 3 7 6\n1 0 15\n4 3 4 8 7\n1 0 16\n4 4 1 5 8\n"
                              "1\n1 2 2 2\n"
                              "2\n1 0.5 0.5 0.5 4 0.01\n2 0.1 0.1 0.9 9\n");
  const auto c = std::get<plc<3>>(io::read_plc(cube));
  require_same(c, write_and_read(c, dir, "cube2.poly"));
  // Triangle .poly
  const auto sq = dir.write("sq.poly", "5 2 0 1\n1 0 0 3\n2 1 0\n3 1 1\n4 0 1\n5 0.1 0.3\n4 1\n1 1 2 7\n2 2 3 7\n3 3 4 7\n4 4 1 8\n"
                                       "1\n1 0.9 0.9\n2\n1 0.5 0.5 2 0.05\n2 0.25 0.25 3\n");
  const auto t = std::get<plc<2>>(io::read_plc(sq));
  BOOST_TEST(t.regions.size() == 2u);
  require_same(t, write_and_read(t, dir, "sq2.poly"));
}
