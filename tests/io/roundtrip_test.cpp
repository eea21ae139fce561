// Round trips through every format: what we write reads back with the same points (bit for bit),
// segment names, numbers and order, cells (vertex order, hence orientation) and interfaces; the
// read-only formats (.poly, .smesh, OFF, STL) read hand-written files with known content.
#define BOOST_TEST_MODULE io_roundtrip
#include <boost/test/unit_test.hpp>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "../support/fixtures.hpp"
#include "gsse/io/atomic_file.hpp"
#include "gsse/io/gmsh.hpp"
#include "gsse/io/node_ele.hpp"
#include "gsse/io/poly.hpp"
#include "gsse/io/sidecar.hpp"
#include "gsse/io/vtu.hpp"
#include "gsse/io/surface.hpp"
#include "io_test_util.hpp"

using namespace gsse;

namespace {

// Two segments with non-trivial numbers, given in non-sorted order, and names that need quoting
// in some formats; the segment order must survive too.
template <std::size_t D>
domain<D> sample() {
  std::array<int, D> n;
  n.fill(2);
  n[0] = 3;
  auto d = test::make_two_segment_domain<D>(n, 1.5);
  d.segments()[0].set_name("p doped silicon");
  d.segments()[0].set_number(7);
  d.segments()[1].set_name("oxide");
  d.segments()[1].set_number(3);
  // irrational coordinates check that text formats keep every bit
  for (auto& p : d.mutable_points())
    for (auto& x : p) x = x / 3.0 + 0.1;
  return d;
}

template <std::size_t D>
void require_same(const domain<D>& a, const domain<D>& b) {
  BOOST_TEST_REQUIRE(a.points().size() == b.points().size());
  for (std::size_t i = 0; i < a.points().size(); ++i)
    BOOST_TEST_REQUIRE(std::memcmp(a.points()[i].data(), b.points()[i].data(), sizeof(double) * D) == 0);
  BOOST_TEST_REQUIRE(a.segments().size() == b.segments().size());
  for (std::size_t k = 0; k < a.segments().size(); ++k) {
    const auto &s = a.segments()[k], &t = b.segments()[k];
    BOOST_TEST(s.name() == t.name());
    BOOST_TEST(s.number() == t.number());
    BOOST_TEST_REQUIRE(s.num_cells() == t.num_cells());
    for (std::size_t c = 0; c < s.num_cells(); ++c)
      BOOST_TEST_REQUIRE((s.cell(static_cast<cell_id>(c)) == t.cell(static_cast<cell_id>(c))));
  }
  // interface orientation: the facets between segments 0 and 1, as seen from segment 0
  auto fa = interface_facets(a, 0, 1), fb = interface_facets(b, 0, 1);
  BOOST_TEST_REQUIRE(fa.size() == fb.size());
  BOOST_TEST(!fa.empty());
  for (std::size_t i = 0; i < fa.size(); ++i)
    BOOST_TEST((vertices(a.segments()[0], fa[i].first) == vertices(b.segments()[0], fb[i].first)));
}

template <std::size_t D>
domain<D> finalized(domain<D> d) {
  for (auto& s : d.segments()) s.finalize();
  return d;
}

}  // namespace

BOOST_AUTO_TEST_CASE(node_ele_face_3d) {
  test::scratch_dir dir("rt_ne3");
  const auto d = finalized(sample<3>());
  io::write_node_ele(d, dir.file("mesh"));
  auto r = io::read_tetgen_mesh(dir.file("mesh.ele"));
  require_same(d, r);
  // .face: every boundary facet of each segment plus the interface once, oriented into the
  // segment of lower number (oxide, 3) with marker 3*100 + 7
  const auto t = io::read_sidecar(dir.file("mesh.json"));
  BOOST_TEST(t.face_marker_base == 100);
  std::istringstream in(test::slurp_file(dir.file("mesh.face")));
  std::string line;
  std::getline(in, line);  // comment
  std::size_t n = 0;
  in >> n >> line;
  std::size_t interface = 0, outer = 0;
  const auto ifs = interface_facets(d, 1, 0);  // oriented into segment index 1 (number 3)
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t id;
    std::array<vertex_id, 3> v;
    long marker;
    in >> id >> v[0] >> v[1] >> v[2] >> marker;
    for (auto& x : v) --x;
    if (marker == 307) {
      ++interface;
      bool found = false;
      for (const auto& f : ifs) found = found || vertices(d.segments()[1], f.first) == v;
      BOOST_TEST(found);
    } else {
      BOOST_TEST((marker == 700 || marker == 300));
      ++outer;
    }
  }
  BOOST_TEST(interface == ifs.size());
  BOOST_TEST(outer == boundary_facets(d.segments()[0]).size() + boundary_facets(d.segments()[1]).size() - 2 * ifs.size());
}

// Markers: two boundary facets of segment 0 marked 5 and -3 (one named), an interface facet 9: the
// .face carries them (and interface codes above face_marker_base elsewhere); read back, the
// domain has the same marked faces and names. Holds in 2D (.edge) too.
template <std::size_t D>
void markers_round_trip(const char* scratch) {
  test::scratch_dir dir(scratch);
  auto d = finalized(sample<D>());
  const auto ifs = interface_facets(d, 0, 1);
  auto face = [&](const auto& f) {
    std::array<vertex_id, D> r;
    const auto vs = vertices(d.segments()[0], f);
    std::copy(vs.begin(), vs.end(), r.begin());
    return r;
  };
  std::vector<std::array<vertex_id, D>> outer;  // on the domain's boundary, not the interface
  for (const auto& f : boundary_facets(d.segments()[0])) {
    bool shared = false;
    for (const auto& g : ifs) shared = shared || g.first == f;
    if (!shared) outer.push_back(face(f));
  }
  BOOST_TEST_REQUIRE(outer.size() >= 2u);
  BOOST_TEST_REQUIRE(!ifs.empty());
  d.marked_faces().push_back({outer[0], 5});
  d.marked_faces().push_back({outer[1], -3});
  d.marked_faces().push_back({face(ifs[0].first), 9});
  d.marker_names()[5] = "drain contact";
  io::write_node_ele(d, dir.file("mesh"));
  const auto r = io::read_node_ele<D>(dir.file("mesh"));
  auto sorted = [](auto faces) {
    std::vector<std::pair<std::array<vertex_id, D>, int>> v;
    for (auto f : faces) {
      std::sort(f.vertices.begin(), f.vertices.end());
      v.push_back({f.vertices, f.marker});
    }
    std::sort(v.begin(), v.end());
    return v;
  };
  BOOST_TEST((sorted(r.marked_faces()) == sorted(d.marked_faces())));
  BOOST_TEST(r.marked_faces().size() == 3u);
  BOOST_TEST((r.marker_names() == d.marker_names()));
}

BOOST_AUTO_TEST_CASE(node_ele_markers_3d) { markers_round_trip<3>("rt_mk3"); }
BOOST_AUTO_TEST_CASE(node_ele_markers_2d) { markers_round_trip<2>("rt_mk2"); }

// A marked face inside a segment (not a boundary or interface facet) is written once after the
// outer facets, with its marker; a face marked twice keeps its earliest marker, whatever the
// vertex order it was listed in, and is written once; a boundary facet's marker replaces its
// interface code. Read back: the earliest marker of each marked face.
template <std::size_t D>
void inner_and_repeated_markers(const char* scratch) {
  test::scratch_dir dir(scratch);
  auto d = finalized(sample<D>());
  const auto& s0 = d.segments()[0];
  std::array<vertex_id, D> inner{}, outer{};
  bool have_inner = false, have_outer = false;
  for (cell_id c : cells(s0))
    for (int i = 0; i <= static_cast<int>(D); ++i) {
      const auto v = vertices(s0, facet{c, i});
      if (!have_inner && neighbour(s0, c, i) != no_cell) inner = v, have_inner = true;
      if (!have_outer && neighbour(s0, c, i) == no_cell) outer = v, have_outer = true;
    }
  BOOST_TEST_REQUIRE((have_inner && have_outer));
  auto reversed = [](std::array<vertex_id, D> f) {
    std::reverse(f.begin(), f.end());
    return f;
  };
  d.marked_faces().push_back({inner, 11});
  d.marked_faces().push_back({reversed(outer), 4});
  d.marked_faces().push_back({reversed(inner), 12});  // the same face again: 11 stays
  d.marked_faces().push_back({outer, 6});              // 4 stays
  io::write_node_ele(d, dir.file("mesh"));
  // the .face/.edge file: each face once, the inner one last
  std::ifstream in(dir.file(D == 3 ? "mesh.face" : "mesh.edge"));
  std::string line;
  std::vector<std::pair<std::array<vertex_id, D>, long>> rows;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    long n = 0;
    ls >> n;
    std::array<vertex_id, D> f;
    long m = 0;
    bool full = true;
    for (auto& v : f) {
      long x = 0;
      full = full && static_cast<bool>(ls >> x);
      v = static_cast<vertex_id>(x - 1);
    }
    if (!full || !(ls >> m)) continue;  // the count line
    std::sort(f.begin(), f.end());
    rows.push_back({f, m});
  }
  auto key = [](std::array<vertex_id, D> f) {
    std::sort(f.begin(), f.end());
    return f;
  };
  BOOST_TEST_REQUIRE(!rows.empty());
  BOOST_TEST((rows.back() == std::pair<std::array<vertex_id, D>, long>{key(inner), 11}));
  BOOST_TEST(std::count_if(rows.begin(), rows.end(), [&](const auto& r) { return r.first == key(inner); }) == 1);
  BOOST_TEST(std::count_if(rows.begin(), rows.end(), [&](const auto& r) { return r.first == key(outer); }) == 1);
  for (const auto& r : rows)
    if (r.first == key(outer)) BOOST_TEST(r.second == 4);
  const auto back = io::read_node_ele<D>(dir.file("mesh"));
  std::vector<std::pair<std::array<vertex_id, D>, int>> got;
  for (const auto& f : back.marked_faces()) got.push_back({key(f.vertices), f.marker});
  std::sort(got.begin(), got.end());
  std::vector<std::pair<std::array<vertex_id, D>, int>> want{{key(inner), 11}, {key(outer), 4}};
  std::sort(want.begin(), want.end());
  BOOST_TEST((got == want));
}

BOOST_AUTO_TEST_CASE(node_ele_inner_and_repeated_markers_3d) { inner_and_repeated_markers<3>("rt_mki3"); }
BOOST_AUTO_TEST_CASE(node_ele_inner_and_repeated_markers_2d) { inner_and_repeated_markers<2>("rt_mki2"); }

BOOST_AUTO_TEST_CASE(node_ele_edge_2d) {
  test::scratch_dir dir("rt_ne2");
  const auto d = finalized(sample<2>());
  io::write_node_ele(d, dir.file("mesh"));
  BOOST_TEST(std::filesystem::exists(dir.file("mesh.edge")));
  require_same(d, io::read_triangle_mesh(dir.file("mesh")));
}

BOOST_AUTO_TEST_CASE(node_ele_without_sidecar_names_regions) {
  test::scratch_dir dir("rt_ne_nojson");
  const auto d = finalized(sample<3>());
  io::write_node_ele(d, dir.file("m.node"));
  std::filesystem::remove(dir.file("m.json"));
  auto r = io::read_tetgen_mesh(dir.file("m"));
  BOOST_TEST(r.segments()[0].name() == "region_7");
  BOOST_TEST(r.segments()[1].name() == "region_3");
}

BOOST_AUTO_TEST_CASE(msh_ascii_and_binary) {
  test::scratch_dir dir("rt_msh");
  for (bool binary : {false, true}) {
    const auto d3 = finalized(sample<3>());
    io::write_msh(d3, dir.file("m3.msh"), binary);
    require_same(d3, io::read_msh<3>(dir.file("m3.msh")));
    BOOST_TEST(std::holds_alternative<domain<3>>(io::read_msh_any(dir.file("m3.msh"))));
    const auto d2 = finalized(sample<2>());
    io::write_msh(d2, dir.file("m2.msh"), binary);
    require_same(d2, io::read_msh<2>(dir.file("m2.msh")));
    BOOST_TEST(std::holds_alternative<domain<2>>(io::read_msh_any(dir.file("m2.msh"))));
  }
}

BOOST_AUTO_TEST_CASE(msh_skips_lower_dimensional_elements_and_unknown_sections) {
  test::scratch_dir dir("rt_msh_extra");
  const auto p = dir.write("t.msh",
                           "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
                           "$Comments\nanything $Foo\n$EndComments\n"
                           "$PhysicalNames\n2\n3 5 \"body\"\n2 9 \"skin\"\n$EndPhysicalNames\n"
                           "$Entities\n0 0 1 1\n1 0 0 0 1 1 0 1 9 0\n1 0 0 0 1 1 1 1 5 1 1\n$EndEntities\n"
                           "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n"
                           "$Elements\n2 2 1 4\n2 1 2 1\n1 1 3 2\n3 1 4 1\n2 1 2 3 4\n$EndElements\n");
  auto d = io::read_msh<3>(p);
  BOOST_TEST_REQUIRE(d.segments().size() == 1u);
  BOOST_TEST(d.segments()[0].name() == "body");
  BOOST_TEST(d.segments()[0].number() == 5);
  BOOST_TEST(d.segments()[0].num_cells() == 1u);
}

BOOST_AUTO_TEST_CASE(msh_version_2_2_volume_mesh) {
  test::scratch_dir dir("rt_msh22");
  // element 3 repeats element 2 for a second physical group (as Gmsh writes 2.2): read once,
  // in the first group; the triangle is lower-dimensional and skipped
  const auto p = dir.write("t22.msh",
                           "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n3 5 \"body\"\n3 9 \"other\"\n"
                           "$EndPhysicalNames\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n7 0 0 1\n$EndNodes\n"
                           "$Elements\n3\n1 2 2 7 3 1 2 3\n2 4 2 5 1 1 2 3 7\n3 4 2 9 1 1 2 3 7\n$EndElements\n");
  auto d = io::read_msh<3>(p);
  BOOST_TEST_REQUIRE(d.segments().size() == 1u);
  BOOST_TEST(d.segments()[0].name() == "body");
  BOOST_TEST(d.segments()[0].number() == 5);
  BOOST_TEST(d.segments()[0].num_cells() == 1u);
  BOOST_TEST(d.points()[3][2] == 1.0);
}

BOOST_AUTO_TEST_CASE(vtu_structure) {
  test::scratch_dir dir("rt_vtu");
  auto d = finalized(sample<3>());
  auto& s0 = d.segments()[0];
  auto phi = add_quantity<double>(s0, on_vertices, "potential", 1.5);
  values(s0, phi)[0] = -2.0;
  for (auto& s : d.segments()) add_quantity<double>(s, on_cells, "volume", 0.25);
  add_quantity<int>(d.segments()[1], on_cells, "flag", 1);
  io::write_vtu(d, dir.file("m.vtu"));
  const auto text = test::slurp_file(dir.file("m.vtu"));
  for (const char* want : {"header_type=\"UInt64\"", "Name=\"segment\"", "Name=\"p doped silicon/potential\"",
                           "Name=\"volume\"", "Name=\"oxide/flag\"", "NumberOfPoints=\"36\"", "encoding=\"raw\""})
    BOOST_TEST(text.find(want) != std::string::npos, want);
  // the appended block sizes add up to the data between '_' and the closing tag
  const auto start = text.find('_', text.find("<AppendedData")) + 1;
  const auto end = text.rfind("\n  </AppendedData>");
  std::size_t at = start, blocks = 0;
  while (at < end) {
    std::uint64_t n;
    std::memcpy(&n, text.data() + at, 8);
    at += 8 + n;
    ++blocks;
  }
  BOOST_TEST(at == end);
  BOOST_TEST(blocks == 8u);  // potential, segment, volume, flag, points, connectivity, offsets, types
}

// read_vtu reads back what write_vtu writes (appended raw data, UInt64 headers): the points, every
// segment's cells in order, and a point quantity, value for value.
BOOST_AUTO_TEST_CASE(vtu_read_back) {
  test::scratch_dir dir("rt_vtu_read");
  auto d = finalized(sample<3>());
  auto& s0 = d.segments()[0];
  auto phi = add_quantity<double>(s0, on_vertices, "potential", 1.5);
  for (std::size_t v = 0; v < d.points().size(); ++v) values(s0, phi)[v] = 0.25 * static_cast<double>(v) - 3;
  io::write_vtu(d, dir.file("m.vtu"));
  const io::vtu_grid g = io::read_vtu(dir.file("m.vtu"));
  BOOST_TEST_REQUIRE(g.points.size() == d.points().size());
  for (std::size_t v = 0; v < g.points.size(); ++v)
    for (std::size_t k = 0; k < 3; ++k) BOOST_TEST(g.points[v][k] == d.points()[v][k]);
  std::size_t c = 0;
  for (const auto& s : d.segments())
    for (const auto& cell : s.cell_data()) {
      BOOST_TEST_REQUIRE(c < g.cell_types.size());
      BOOST_TEST(g.cell_types[c] == 10);
      BOOST_TEST_REQUIRE(g.cell_start[c + 1] - g.cell_start[c] == cell.size());
      for (std::size_t k = 0; k < cell.size(); ++k) BOOST_TEST(g.connectivity[g.cell_start[c] + k] == static_cast<std::size_t>(cell[k]));
      ++c;
    }
  BOOST_TEST(c == g.cell_types.size());
  const auto* a = g.point_array(s0.name() + "/potential");
  BOOST_TEST_REQUIRE(a != nullptr);
  BOOST_TEST(a->components == 1u);
  for (std::size_t v = 0; v < d.points().size(); ++v) BOOST_TEST(a->values[v] == values(s0, phi)[v]);
}

// The encodings write_vtu does not produce, built by hand: appended base64 (header and data
// encoded apart, as VTK does) with UInt32 headers in big-endian byte order, and appended raw
// zlib-compressed blocks (two blocks, the last one short) with UInt64 headers.
BOOST_AUTO_TEST_CASE(vtu_read_appended_encodings) {
  test::scratch_dir dir("rt_vtu_enc");
  const std::vector<double> coords{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::vector<std::int32_t> conn{0, 1, 2, 3}, offs{4};
  const std::vector<std::uint8_t> types{10};
  const std::vector<double> size{0.5, 0.25, 0.125, 1.0};
  auto bytes = [](const auto& v, bool big) {
    std::string b;
    for (auto x : v) {
      char c[sizeof(x)];
      std::memcpy(c, &x, sizeof(x));
      if (big) std::reverse(c, c + sizeof(x));
      b.append(c, sizeof(x));
    }
    return b;
  };
  auto b64 = [](const std::string& in) {
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string o;
    for (std::size_t i = 0; i < in.size(); i += 3) {
      const auto n = std::min<std::size_t>(3, in.size() - i);
      std::uint32_t v = 0;
      for (std::size_t k = 0; k < 3; ++k) v = (v << 8) | (k < n ? static_cast<unsigned char>(in[i + k]) : 0u);
      for (std::size_t k = 0; k < 4; ++k) o += k <= n ? t[(v >> (18 - 6 * k)) & 63] : '=';
    }
    return o;
  };
  auto file = [&](const std::string& header_attrs, const std::string& encoding, const std::vector<std::string>& blocks) {
    std::string x = "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" " + header_attrs +
                    ">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"4\" NumberOfCells=\"1\">\n";
    const char* heads[5] = {"<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\"",
                            "</Points><Cells><DataArray type=\"Int32\" Name=\"connectivity\"",
                            "<DataArray type=\"Int32\" Name=\"offsets\"", "<DataArray type=\"UInt8\" Name=\"types\"",
                            "</Cells><PointData><DataArray type=\"Float64\" Name=\"size\""};
    std::size_t at = 0;
    for (std::size_t k = 0; k < 5; ++k) {
      x += std::string(heads[k]) + " format=\"appended\" offset=\"" + std::to_string(at) + "\"/>\n";
      at += blocks[k].size();
    }
    x += "</PointData></Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"" + encoding + "\">\n_";
    for (const auto& b : blocks) x += b;
    return x + "\n</AppendedData>\n</VTKFile>\n";
  };
  auto check = [&](const std::string& path) {
    const auto g = io::read_vtu(path);
    BOOST_TEST_REQUIRE(g.points.size() == 4u, path);
    for (std::size_t i = 0; i < 12; ++i) BOOST_TEST(g.points[i / 3][i % 3] == coords[i]);
    BOOST_TEST((g.connectivity == std::vector<std::size_t>{0, 1, 2, 3}));
    BOOST_TEST(g.cell_types.size() == 1u);
    BOOST_TEST(g.cell_types[0] == 10);
    const auto* a = g.point_array("size");
    BOOST_TEST_REQUIRE(a != nullptr);
    BOOST_TEST(a->values == size);
  };
  {
    // base64, big-endian, UInt32 headers: each block is base64(header) + base64(data)
    std::vector<std::string> blocks;
    auto block = [&](const std::string& data) {
      blocks.push_back(b64(bytes(std::vector<std::uint32_t>{static_cast<std::uint32_t>(data.size())}, true)) + b64(data));
    };
    block(bytes(coords, true)), block(bytes(conn, true)), block(bytes(offs, true)), block(bytes(types, true)), block(bytes(size, true));
    check(dir.write("b64.vtu", file("byte_order=\"BigEndian\" header_type=\"UInt32\"", "base64", blocks)));
  }
  {
    // raw, zlib, UInt64 headers, blocks of 64 bytes (the points' 96 bytes make two, the last 32)
    std::vector<std::string> blocks;
    auto block = [&](const std::string& data) {
      const std::size_t bs = 64, nb = (data.size() + bs - 1) / bs;
      std::vector<std::string> parts;
      std::vector<std::uint64_t> head{nb, bs, data.size() % bs};
      for (std::size_t k = 0; k < nb; ++k) {
        const std::string piece = data.substr(k * bs, bs);
        uLongf n = compressBound(static_cast<uLong>(piece.size()));
        std::string z(n, '\0');
        BOOST_TEST_REQUIRE(compress(reinterpret_cast<Bytef*>(z.data()), &n, reinterpret_cast<const Bytef*>(piece.data()), static_cast<uLong>(piece.size())) == Z_OK);
        z.resize(n);
        parts.push_back(z);
        head.push_back(n);
      }
      std::string b = bytes(head, false);
      for (const auto& z : parts) b += z;
      blocks.push_back(b);
    };
    block(bytes(coords, false)), block(bytes(conn, false)), block(bytes(offs, false)), block(bytes(types, false)), block(bytes(size, false));
    check(dir.write("zlib.vtu", file("byte_order=\"LittleEndian\" header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\"", "raw", blocks)));
  }
}

// Every way a .vtu can be wrong gives an io_error naming the file and the line of the element at
// fault, never a crash: each case is a small hand-written file.
BOOST_AUTO_TEST_CASE(vtu_read_errors) {
  test::scratch_dir dir("rt_vtu_bad");
  const std::string head = "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n<UnstructuredGrid>\n";
  const std::string pts = "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n0 0 0 1 0 0 0 1 0 0 0 1\n</DataArray>\n</Points>\n";
  auto cells = [](const std::string& conn) {
    return "<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">" + conn +
           "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">4</DataArray>\n"
           "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10</DataArray>\n</Cells>\n";
  };
  const std::string piece = "<Piece NumberOfPoints=\"4\" NumberOfCells=\"1\">\n";
  const std::string tail = "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  // a good one first: the cases below differ from it in one place
  const auto good = dir.write("good.vtu", head + piece + pts + cells("0 1 2 3") + tail);
  const auto g = io::read_vtu(good);
  BOOST_TEST(g.points.size() == 4u);
  BOOST_TEST(g.connectivity.size() == 4u);
  const std::vector<std::pair<std::string, std::string>> cases{
      {head + piece + pts + cells("0 1 2 4") + tail, ":11: connectivity entry 3 (4) is not a point"},  // index out of range
      {head + piece + pts + cells("0 1 2") + tail, ":12: offset 4 of cell 0 is not a non-decreasing index"},
      {head + piece + pts + cells("0 1 x 3") + tail, ":11: 'x'"},
      {head + "<Piece NumberOfPoints=\"5\" NumberOfCells=\"1\">\n" + pts + cells("0 1 2 3") + tail, ":6: 12 coordinates for 5 points"},
      {head + piece + "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n0 0 0 1 0 0 0 1 0 0 0 nan\n</DataArray>\n</Points>\n" +
           cells("0 1 2 3") + tail,
       ":6: point 3 has a non-finite coordinate"},
      {"<VTKFile type=\"PolyData\">\n</VTKFile>\n", ":1: a VTK XML file of type 'PolyData'"},
      {"<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" compressor=\"vtkLZ4DataCompressor\">\n", ":2: compressor 'vtkLZ4DataCompressor'"},
      {head + piece + pts + cells("0 1 2 3"), "not closed"},
      {head + piece + "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"binary\">\nAAAA\n</DataArray>\n</Points>\n" + cells("0 1 2 3") + tail,
       ":6: the data of DataArray '' end"},
      {head + piece + "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" offset=\"0\"/>\n</Points>\n" + cells("0 1 2 3") + tail,
       ":6: an appended DataArray but no <AppendedData>"},
      {head + piece + "<Points>\n<DataArray type=\"Float128\" NumberOfComponents=\"3\" format=\"ascii\">0</DataArray>\n</Points>\n" + cells("0 1 2 3") + tail,
       ":6: DataArray type 'Float128'"},
      {"solid x\nendsolid x\n", ":1: no <VTKFile> element"},
  };
  int k = 0;
  for (const auto& [text, want] : cases) {
    const auto f = dir.write("bad" + std::to_string(k++) + ".vtu", text);
    try {
      (void)io::read_vtu(f);
      BOOST_ERROR("no error for case " << k << ", expected " << want);
    } catch (const io::io_error& e) {
      const std::string w = e.what();
      BOOST_TEST(w.find(f) == 0u, w);
      BOOST_TEST(w.find(want) != std::string::npos, "case " << k << ": '" << w << "' lacks '" << want << "'");
    }
  }
  BOOST_CHECK_THROW(io::read_vtu(dir.file("missing.vtu")), io::io_error);
}

BOOST_AUTO_TEST_CASE(tetgen_poly_with_polygons_holes_markers_regions) {
  test::scratch_dir dir("rt_poly");
  // unit cube; the bottom facet has an outer loop and an inner loop (a square hole, whose hole
  // point is listed), the top facet carries an embedded edge as a 2-vertex polygon
  const auto p = dir.write("cube.poly",
                           "# cube\n12 3 0 1\n"
                           "1 0 0 0 5\n2 1 0 0 5\n3 1 1 0\n4 0 1 0\n5 0 0 1\n6 1 0 1\n7 1 1 1\n8 0 1 1\n"
                           "9 0.25 0.25 0\n10 0.75 0.25 0\n11 0.75 0.75 0\n12 0.25 0.75 0\n"
                           "6 1\n"
                           "2 1 11\n4 1 2 3 4\n4 9 10 11 12\n1 0.5 0.5 0\n"
                           "2 0 12\n4 5 6 7 8\n2 5 7\n"
                           "1 0 13\n4 1 2 6 5\n"
                           "1 0 14\n4 2 3 7 6\n"
                           "1 0 15\n4 3 4 8 7\n"
                           "1 0 16\n4 4 1 5 8\n"
                           "1\n1 2 2 2\n"
                           "2\n1 0.5 0.5 0.5 4 0.01\n2 0.1 0.1 0.9 9\n");
  dir.write("cube.json", "{\"segments\": [\"a\", \"b\", \"c\", \"bulk\"], \"h\": 0.1}");
  auto any = io::read_plc(p);
  BOOST_TEST_REQUIRE(std::holds_alternative<plc<3>>(any));
  const auto& g = std::get<plc<3>>(any);
  BOOST_TEST(g.points.size() == 12u);
  BOOST_TEST(g.point_markers[0] == 5);
  BOOST_TEST_REQUIRE(g.facets.size() == 6u);
  BOOST_TEST(g.facets[0].polygons.size() == 2u);
  BOOST_TEST(g.facets[0].holes.size() == 1u);
  BOOST_TEST(g.facets[0].marker == 11);
  BOOST_TEST(g.facets[1].polygons.size() == 2u);
  BOOST_TEST(g.facets[1].polygons[1].size() == 2u);
  BOOST_TEST(g.facets[5].marker == 16);
  BOOST_TEST(g.facets[0].polygons[1][0] == 8u);  // 1-based in the file
  BOOST_TEST(g.holes.size() == 1u);
  BOOST_TEST_REQUIRE(g.regions.size() == 2u);
  BOOST_TEST(g.regions[0].number == 4);
  BOOST_TEST(g.regions[0].max_volume == 0.01);
  BOOST_TEST(g.regions[0].name == "bulk");
  BOOST_TEST(g.regions[1].max_volume < 0);
  BOOST_TEST(g.regions[1].name == "region_9");
}

BOOST_AUTO_TEST_CASE(smesh_and_triangle_poly_and_node) {
  test::scratch_dir dir("rt_smesh");
  dir.write("t.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n");
  const auto s = dir.write("t.smesh", "0 3 0 0\n4 1\n3 0 2 1 1\n3 0 1 3 2\n3 0 3 2 3\n3 1 2 3 4\n0\n0\n");
  auto g = io::read_tetgen_poly(s);
  // coordinates from the .node, zero-based connectivity in the file's order, the markers
  const std::vector<point3> corners{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  BOOST_TEST((g.points == corners));
  BOOST_TEST_REQUIRE(g.facets.size() == 4u);
  const std::vector<std::vector<vertex_id>> loops{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (std::size_t f = 0; f < 4; ++f) {
    BOOST_TEST_REQUIRE(g.facets[f].polygons.size() == 1u);
    BOOST_TEST((g.facets[f].polygons[0] == loops[f]));
    BOOST_TEST(g.facets[f].marker == int(f) + 1);
  }
  BOOST_TEST((io::read_node<3>(dir.file("t.node")) == corners));
  const auto t = dir.write("sq.poly", "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n4 1\n1 1 2 7\n2 2 3 7\n3 3 4 7\n4 4 1 8\n"
                                      "0\n1\n1 0.5 0.5 2 0.05\n");
  auto any = io::read_plc(t);
  BOOST_TEST_REQUIRE(std::holds_alternative<plc<2>>(any));
  const auto& q = std::get<plc<2>>(any);
  BOOST_TEST((q.points == std::vector<point2>{{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  BOOST_TEST_REQUIRE(q.edges.size() == 4u);
  for (vertex_id e = 0; e < 4; ++e) BOOST_TEST((q.edges[e] == std::array<vertex_id, 2>{e, (e + 1) % 4}));
  BOOST_TEST((q.edge_markers == std::vector<int>{7, 7, 7, 8}));
  BOOST_TEST_REQUIRE(q.regions.size() == 1u);
  BOOST_TEST((q.regions[0].at == point2{0.5, 0.5}));
  BOOST_TEST(q.regions[0].number == 2);
  BOOST_TEST(q.regions[0].max_volume == 0.05);
}

BOOST_AUTO_TEST_CASE(off_cube) {
  test::scratch_dir dir("rt_off");
  const auto p = dir.write("box.off",
                           "OFF\n# a cube\n8 6 12\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                           "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7 255 0 0\n");
  auto any = io::read_plc(p);
  const auto& g = std::get<plc<3>>(any);
  BOOST_TEST((g.points == std::vector<point3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}));
  BOOST_TEST_REQUIRE(g.facets.size() == 6u);
  const std::vector<std::vector<vertex_id>> loops{{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (std::size_t f = 0; f < 6; ++f) {
    BOOST_TEST_REQUIRE(g.facets[f].polygons.size() == 1u);
    BOOST_TEST((g.facets[f].polygons[0] == loops[f]));  // the colour after the last face is ignored
  }
  BOOST_TEST(g.regions.empty());
  BOOST_TEST(io::single_segment_name(g.source) == "box");
}

namespace {
const float tet[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const int tri[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};

// The STL's four triangles, corner by corner in the file's order (so the orientation is kept),
// by coordinates: the merged vertex ids are the reader's choice.
void same_triangles(const plc<3>& g) {
  BOOST_TEST_REQUIRE(g.facets.size() == 4u);
  for (std::size_t f = 0; f < 4; ++f) {
    BOOST_TEST_REQUIRE(g.facets[f].polygons.size() == 1u);
    const auto& loop = g.facets[f].polygons[0];
    BOOST_TEST_REQUIRE(loop.size() == 3u);
    for (std::size_t k = 0; k < 3; ++k) {
      const auto& c = tet[tri[f][k]];
      BOOST_TEST((g.points[loop[k]] == point3{c[0], c[1], c[2]}), "facet " << f << " corner " << k);
    }
  }
}
}  // namespace

BOOST_AUTO_TEST_CASE(stl_ascii_and_binary_merge_vertices) {
  test::scratch_dir dir("rt_stl");
  std::ostringstream a;
  a << "solid tet\n";
  for (auto& t : tri) {
    a << "  facet normal 0 0 0\n    outer loop\n";
    for (int v : t) a << "      vertex " << tet[v][0] << ' ' << tet[v][1] << ' ' << (v == 0 ? "-0" : std::to_string(tet[v][2])) << "\n";
    a << "    endloop\n  endfacet\n";
  }
  a << "endsolid tet\n";
  auto g = io::read_stl(dir.write("tet.stl", a.str()));
  BOOST_TEST(g.points.size() == 4u);  // 12 corners merged; -0 equals 0
  same_triangles(g);
  // binary, with a header that starts with "solid" like many exporters write
  std::string b(80, ' ');
  std::memcpy(b.data(), "solid but binary", 16);
  std::uint32_t n = 4;
  b.append(reinterpret_cast<const char*>(&n), 4);
  for (auto& t : tri) {
    float rec[12] = {};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) rec[3 + 3 * k + c] = tet[t[k]][c];
    b.append(reinterpret_cast<const char*>(rec), sizeof rec);
    b.append(2, '\0');
  }
  auto any = io::read_plc(dir.write("tetb.stl", b));
  const auto& h = std::get<plc<3>>(any);
  BOOST_TEST(h.points.size() == 4u);
  same_triangles(h);
  BOOST_TEST(h.regions.empty());
}

BOOST_AUTO_TEST_CASE(failed_write_leaves_no_file) {
  test::scratch_dir dir("rt_atomic");
  auto d = finalized(sample<3>());
  d.segments()[1].set_number(7);  // duplicate numbers cannot be written
  BOOST_CHECK_THROW(io::write_msh(d, dir.file("bad.msh")), io::io_error);
  BOOST_CHECK_THROW(io::write_node_ele(d, dir.file("bad")), io::io_error);
  BOOST_CHECK_THROW(io::write_vtu(d, dir.file("bad.vtu")), io::io_error);
  d.segments()[1].set_number(3);
  d.segments()[1].set_name("has \"quote\"");
  BOOST_CHECK_THROW(io::write_msh(d, dir.file("bad.msh")), io::io_error);
  {  // an exception while writing discards the temporary
    io::atomic_file f(dir.file("partial.txt"));
    f.stream() << "half";
  }
  BOOST_CHECK_THROW(io::write_atomically(dir.file("thrown.txt"), [](std::ostream& o) {
                      o << "x";
                      throw std::runtime_error("writer failed");
                    }), std::runtime_error);
  // an existing file is replaced only by a complete one
  io::write_atomically(dir.file("kept.txt"), [](std::ostream& o) { o << "old"; });
  BOOST_CHECK_THROW(io::write_atomically(dir.file("kept.txt"), [](std::ostream&) { throw std::runtime_error("x"); }),
                    std::runtime_error);
  BOOST_TEST(test::slurp_file(dir.file("kept.txt")) == "old");
  // ... and a complete one replaces it, leaving nothing beside it (the old file is moved aside first)
  io::write_atomically(dir.file("kept.txt"), [](std::ostream& o) { o << "new"; });
  BOOST_TEST(test::slurp_file(dir.file("kept.txt")) == "new");
  std::size_t files = 0;
  for ([[maybe_unused]] auto& e : std::filesystem::directory_iterator(dir.path)) ++files;
  BOOST_TEST(files == 1u);  // only kept.txt: no output, no temporaries
  BOOST_CHECK_THROW(io::write_vtu(finalized(sample<3>()), dir.file("no/such/dir/m.vtu")), io::io_error);
}
