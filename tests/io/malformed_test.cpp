// A table of malformed inputs: each must fail with gsse::io::io_error whose message names the
// file, the line (text) or byte offset (binary), and says what was expected.
#define BOOST_TEST_MODULE io_malformed
#include <boost/test/data/test_case.hpp>
#include <boost/test/unit_test.hpp>

#include <cstdint>
#include <cstring>
#include <functional>
#include <iostream>

#include "gsse/io/gmsh.hpp"
#include "gsse/io/node_ele.hpp"
#include "gsse/io/poly.hpp"
#include "gsse/io/sidecar.hpp"
#include "gsse/io/surface.hpp"
#include "io_test_util.hpp"

using namespace gsse;

namespace {

struct bad_input {
  const char* name;      // file name; its extension picks the reader
  std::string content;
  const char* where;     // ":<line>:" or ": byte <n>:"
  const char* expected;  // message substring
  const char* node = nullptr;  // companion .node for .ele cases
};
std::ostream& operator<<(std::ostream& o, const bad_input& b) { return o << b.name; }

const char* good_node = "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n";
const char* msh_head = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
const char* msh_nodes = "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n";

std::string binary_stl(std::uint32_t stated, std::uint32_t written, float bad = 0.0f) {
  std::string b(80, ' ');
  b.append(reinterpret_cast<const char*>(&stated), 4);
  for (std::uint32_t t = 0; t < written; ++t) {
    float rec[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, bad};
    b.append(reinterpret_cast<const char*>(rec), sizeof rec);
    b.append(2, '\0');
  }
  return b;
}

// A binary .msh whose node section states `nodes` nodes and ends after the first node tag.
std::string binary_msh_truncated(std::uint64_t nodes) {
  std::string s = "$MeshFormat\n4.1 1 8\n";
  std::int32_t one = 1;
  s.append(reinterpret_cast<const char*>(&one), 4);
  s += "\n$EndMeshFormat\n$Nodes\n";
  std::uint64_t head[4] = {1, nodes, 1, nodes};
  s.append(reinterpret_cast<const char*>(head), sizeof head);
  std::int32_t blk[3] = {3, 1, 0};
  s.append(reinterpret_cast<const char*>(blk), sizeof blk);
  s.append(reinterpret_cast<const char*>(&nodes), 8);
  std::uint64_t tag = 1;
  s.append(reinterpret_cast<const char*>(&tag), 8);
  return s;  // the node header starts at byte 47, the first tag at 99, its coordinates (missing) at 107
}

// Version 2.2, binary: one node stated, the file ends after its tag (at byte 53).
std::string binary_msh22_truncated() {
  std::string s = "$MeshFormat\n2.2 1 8\n";
  std::int32_t one = 1;
  s.append(reinterpret_cast<const char*>(&one), 4);
  s += "\n$EndMeshFormat\n$Nodes\n1\n";
  s.append(reinterpret_cast<const char*>(&one), 4);
  return s;
}

// A surface entity 1 and a volume 1 bounded by it (5 lines), and the closed surface of the
// tetrahedron of msh_nodes in surface 1 (8 lines).
const char* entities_vol = "$Entities\n0 0 1 1\n1 0 0 0 1 1 1 0 0\n1 0 0 0 1 1 1 0 1 1\n$EndEntities\n";
const char* tet_surface = "$Elements\n1 4 1 4\n2 1 2 4\n1 1 3 2\n2 1 2 4\n3 2 3 4\n4 1 4 3\n$EndElements\n";

std::vector<bad_input> table() {
  const std::string M = msh_head;
  return {
      // ---- OFF
      {"trunc.off", "OFF\n4 4 6\n0 0 0\n1 0 0\n", ":5:", "unexpected end of file, expected vertex 3 of 4"},
      {"header.off", "OFX\n4 4 6\n", ":1:", "expected 'OFF' header, found 'OFX'"},
      {"range.off", "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 7\n", ":8:", "vertex index 7 out of range [0, 3]"},
      {"nan.off", "OFF\n1 0 0\n0 nan 0\n", ":3:", "'nan' is not a finite number, expected vertex y"},
      {"inf.off", "OFF\n1 0 0\n0 0 -inf\n", ":3:", "'-inf' is not a finite number, expected vertex z"},
      {"text.off", "OFF\n1 0 0\n0 zero 0\n", ":3:", "'zero' is not a number, expected vertex y"},
      {"count.off", "OFF\nfour 4 6\n", ":2:", "'four' is not an integer, expected number of vertices"},
      {"dup.off", "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n1 0 0\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n", ":6:",
       "duplicate point: point 4 repeats point 2 (line 4)"},
      {"open.off", "OFF\n4 3 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n", ":7:", "surface is not closed"},
      {"repeat.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n", ":6:", "face repeats a vertex"},
      // ---- STL
      {"loop.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendfacet\n", ":7:",
       "expected 'endloop', found 'endfacet'"},
      {"noend.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", ":5:", "unexpected end of file, expected 'vertex x y z'"},
      {"short.stl", binary_stl(12, 1), ": byte 80:", "binary STL with 12 triangles must have 684 bytes, file has 134"},
      {"nanb.stl", binary_stl(1, 1, std::numeric_limits<float>::quiet_NaN()), ": byte 128:", "coordinate is not a finite number"},
      {"tiny.stl", std::string("\x01\x02", 2), ": byte 0:", "unexpected end of file, expected 80-byte header and triangle count"},
      // ---- TetGen / Triangle PLC
      {"version.poly", "8 4 0 0\n", ":1:", "dimension must be 2 or 3, got 4"},
      {"corner.poly", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n1 0\n1\n3 1 2 9\n", ":8:", "corner 9 out of range [1, 4]"},
      {"seq.poly", "3 3 0 0\n1 0 0 0\n3 1 0 0\n", ":3:", "point number 3 out of sequence, expected 2"},
      {"facets.poly", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n2 0\n1\n3 1 2 3\n", ":9:",
       "unexpected end of file, expected facet 2"},
      {"edge.poly", "2 2 0 0\n1 0 0\n2 1 0\n1 0\n1 2 2\n", ":5:", "segment 1 has equal endpoints"},
      {"region.poly", "2 2 0 0\n1 0 0\n2 1 0\n0 0\n0\n1\n1 0.5 0.5 x\n", ":7:", "'x' is not an integer, expected region attribute"},
      {"huge.node", "100000000 3 0 0\n1 0 0 0\n", ":3:", "unexpected end of file, expected point 2 of 100000000"},
      // ---- TetGen mesh
      {"range.ele", "1 4 1\n1 1 2 3 5 1\n", ":2:", "corner 5 out of range [1, 4]", good_node},
      {"quad.ele", "1 10 0\n", ":1:", "only linear elements are supported: 10 nodes per tetrahedron, expected 4", good_node},
      {"count.ele", "3 4 1\n1 1 2 3 4 1\n", ":3:", "unexpected end of file, expected tetrahedron 2 of 3", good_node},
      {"attr.ele", "1 4 1\n1 1 2 3 4 1.5\n", ":2:", "region attribute must be an integer", good_node},
      {"degenerate.ele", "1 4 0\n1 1 2 2 4\n", ":2:", "tetrahedron repeats a vertex", good_node},
      {"twice.ele", "2 4 0\n1 1 2 3 4\n2 4 3 2 1\n", ":3:", "tetrahedron 2 repeats tetrahedron 1", good_node},
      {"fan.ele", "3 4 0\n1 1 2 3 4\n2 1 3 2 5\n3 1 2 3 6\n", ": ", "segment 'region_1' is not a valid mesh",
       "6 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 0 0 -1\n6 1 1 1\n"},
      // ---- Gmsh
      {"v30.msh", "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n", ":2:", "unsupported .msh version '3.0', expected 4.1 or 2.2"},
      {"size.msh", "$MeshFormat\n4.1 0 4\n$EndMeshFormat\n", ":2:", "data size 4 unsupported, expected 8"},
      {"missing.msh", M + msh_nodes + "$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 99\n$EndElements\n", ":19:",
       "element refers to node tag 99, which is not defined"},
      {"count.msh", M + "$Nodes\n1 1000000000 1 1000000000\n", ":5:", "number of nodes 1000000000 exceeds what the remaining"},
      {"end.msh", M + "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$Elements\n", ":15:",
       "expected '$EndNodes', found '$Elements'"},
      {"coord.msh", M + "$Nodes\n1 1 1 1\n3 1 0 1\n1\n0 0 nan\n$EndNodes\n", ":8:", "'nan' is not a finite number, expected node z"},
      {"order.msh", M + "$Elements\n0 0 0 0\n$EndElements\n", ":4:", "$Elements before $Nodes"},
      {"twice_el.msh", M + msh_nodes + "$Elements\n1 2 1 2\n3 1 4 2\n1 1 2 3 4\n2 4 2 3 1\n$EndElements\n", ":20:",
       "element 2 (volume 1) has the same nodes as element 1 (volume 1)"},
      {"overlap.msh", M + msh_nodes + "$Elements\n2 2 1 2\n2 1 2 1\n1 1 2 3\n2 2 2 1\n2 1 3 2\n$EndElements\n", ":21:",
       "element 2 (surface 2) has the same nodes as element 1 (surface 1): the two entities overlap there"},
      {"type.msh", M + msh_nodes + "$Elements\n1 1 1 1\n3 1 99 1\n1 1 2 3 4\n$EndElements\n", ":18:", "unsupported element type 99"},
      {"twice.msh", M + "$Nodes\n1 2 1 2\n3 1 0 2\n1\n1\n0 0 0\n1 0 0\n$EndNodes\n", ":8:", "node tag 1 defined twice"},
      {"flat.msh", M + "$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 1\n$EndNodes\n$Elements\n1 1 1 1\n2 1 2 1\n1 1 2 3\n$EndElements\n",
       ":12:", "node has z = 1; a 2D mesh needs z = 0"},
      {"dup.msh", M + "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n1 0 0\n$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n",
       ":14:", "duplicate point: node 4 (in file order) repeats node 2"},
      {"bin.msh", binary_msh_truncated(1), ": byte 107:", "unexpected end of file, expected node x (8 bytes, 0 left)"},
      {"binc.msh", binary_msh_truncated(4), ": byte 55:", "number of nodes 4 exceeds what the remaining 44 bytes can hold"},
      {"v22b.msh", binary_msh22_truncated(), ": byte 53:", "unexpected end of file, expected node x (8 bytes, 0 left)"},
      // ---- Gmsh surface meshes read as PLCs (read_plc; names start with surf_)
      {"surf_open.msh", M + msh_nodes + "$Elements\n1 1 1 1\n2 1 2 1\n1 1 2 3\n$EndElements\n", ":19:",
       "surface is not closed: edge (nodes 1, 2) belongs to 1 face"},
      {"surf_vol_open.msh", M + entities_vol + msh_nodes + "$Elements\n1 3 1 3\n2 1 2 3\n1 1 3 2\n2 1 2 4\n3 2 3 4\n$EndElements\n",
       ":24:", "volume 1 is not closed: edge (nodes 1, 3) lies in 1 of its boundary faces"},
      {"surf_order2.msh", M + msh_nodes + "$Elements\n1 1 1 1\n2 1 9 1\n1 1 2 3 4 1 2\n$EndElements\n", ":18:",
       "second-order triangles (type 9) cannot be surface facets"},
      {"surf_unknown.msh", M + msh_nodes + "$Elements\n1 1 1 1\n2 1 77 1\n1 1 2 3\n$EndElements\n", ":18:",
       "unsupported element type 77"},
      {"surf_tets.msh", M + msh_nodes + "$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n", ":18:",
       "tetrahedra (type 4): a volume mesh, not a surface mesh"},
      {"surf_nosurf.msh", M + "$Entities\n0 0 0 1\n1 0 0 0 1 1 1 0 1 5\n$EndEntities\n" + msh_nodes + tet_surface, ":6:",
       "volume 1 is bounded by surface 5, which has no triangles or quadrangles"},
      {"surf_phys.msh",
       M + "$Entities\n0 0 1 2\n1 0 0 0 1 1 1 0 0\n1 0 0 0 1 1 1 0 1 1\n2 0 0 0 1 1 1 1 1 1 1\n$EndEntities\n" + msh_nodes + tet_surface,
       ":7:", "volume 1 has no physical group, and its tag 1 is the physical group of volume 2"},
      {"surf_dup.msh", M + "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n1 0 0\n$EndNodes\n" + tet_surface, ":14:",
       "duplicate point: node 4 repeats node 2"},
      {"surf_v22_open.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n"
                            "$Elements\n1\n1 2 2 0 1 1 2 3\n$EndElements\n", ":12:", "surface is not closed: edge (nodes 1, 2)"},
      // ---- sidecar
      {"side.json", "{\"segments\": [\"a\", \"b\"], \"numbers\": [1]}", ":1:", "\"numbers\" has 1 entries, \"segments\" has 2"},
  };
}

void read_any(const std::string& path) {
  const auto ext = std::filesystem::path(path).extension().string();
  if (ext == ".msh" && std::filesystem::path(path).filename().string().rfind("surf_", 0) == 0) (void)io::read_plc(path);
  else if (ext == ".msh") (void)io::read_msh_any(path);
  else if (ext == ".ele") (void)io::read_tetgen_mesh(path);
  else if (ext == ".node") (void)io::read_node<3>(path);
  else if (ext == ".json") (void)io::read_sidecar(path);
  else (void)io::read_plc(path);
}

}  // namespace

BOOST_DATA_TEST_CASE(malformed_input_is_reported, boost::unit_test::data::make(table()), c) {
  test::scratch_dir dir(std::string("bad_") + c.name);
  const auto path = dir.write(c.name, c.content);
  if (c.node) dir.write(std::filesystem::path(c.name).stem().string() + ".node", c.node);
  try {
    read_any(path);
    BOOST_ERROR(c.name << ": no error");
  } catch (const io::io_error& e) {
    const std::string m = e.what();
    BOOST_TEST(m.find(path + c.where) == 0, c.name << ": location: " << m);
    BOOST_TEST(m.find(c.expected) != std::string::npos, c.name << ": message: " << m);
  }
}

BOOST_AUTO_TEST_CASE(missing_file_is_reported) {
  try {
    (void)io::read_msh_any("/nonexistent/x.msh");
    BOOST_ERROR("no error");
  } catch (const io::io_error& e) {
    BOOST_TEST(std::string(e.what()).find("/nonexistent/x.msh: cannot open file") == 0);
  }
}
