#include "gsse/io/gmsh.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>

#include "binary_cursor.hpp"
#include "facets.hpp"
#include "gsse/io/atomic_file.hpp"
#include "number_format.hpp"

namespace gsse::io {
namespace {

// Nodes per element and dimension of the Gmsh element types we may meet (linear and
// quadratic ones, points). Others are rejected: in binary files their size would be unknown.
struct element_kind {
  int nodes;
  int dim;
};
element_kind kind_of(int type) {
  switch (type) {
    case 1: return {2, 1};
    case 2: return {3, 2};
    case 3: return {4, 2};
    case 4: return {4, 3};
    case 5: return {8, 3};
    case 6: return {6, 3};
    case 7: return {5, 3};
    case 8: return {3, 1};
    case 9: return {6, 2};
    case 10: return {9, 2};
    case 11: return {10, 3};
    case 12: return {27, 3};
    case 13: return {18, 3};
    case 14: return {14, 3};
    case 15: return {1, 0};
    case 16: return {8, 2};
    case 17: return {20, 3};
    case 18: return {15, 3};
    case 19: return {13, 3};
    default: return {0, -1};
  }
}

// Reads a .msh file that mixes ASCII lines and (in binary mode) raw blocks. Text errors name the
// line, binary errors the byte offset.
class msh_cursor {
 public:
  msh_cursor(const std::string& file, const std::string& data) : file_(file), data_(data) {}

  std::size_t pos() const { return pos_; }
  /// Position of the next item (after whitespace in text), for messages about it.
  std::size_t mark() {
    if (!in_binary_block) skip_ws();
    return pos_;
  }
  std::size_t left() const { return data_.size() - pos_; }
  std::size_t line_at(std::size_t p) const {
    return 1 + static_cast<std::size_t>(std::count(data_.begin(), data_.begin() + static_cast<long>(std::min(p, data_.size())), '\n'));
  }
  [[noreturn]] void fail_at(std::size_t p, const std::string& what) const {
    if (in_binary_block) throw io_error::at_byte(file_, p, what);
    throw io_error(file_, line_at(p), what);
  }
  [[noreturn]] void fail(const std::string& what) const { fail_at(last_, what); }
  bool in_binary_block = false;

  void skip_ws() {
    while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
  }
  bool at_end() {
    skip_ws();
    return pos_ >= data_.size();
  }
  std::string_view token(const std::string& expected) {
    skip_ws();
    last_ = pos_;
    if (pos_ >= data_.size()) fail("unexpected end of file, expected " + expected);
    const std::size_t b = pos_;
    while (pos_ < data_.size() && !std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    return std::string_view(data_).substr(b, pos_ - b);
  }
  void expect(const std::string& word) {
    auto t = token("'" + word + "'");
    if (t != word) fail("expected '" + word + "', found '" + std::string(t.substr(0, 40)) + "'");
  }
  long long integer(const std::string& expected, long long lo, long long hi) {
    auto t = token(expected);
    long long v = 0;
    auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || p != t.data() + t.size())
      fail("'" + std::string(t.substr(0, 40)) + "' is not an integer, expected " + expected);
    if (v < lo || v > hi)
      fail(expected + " " + std::to_string(v) + " out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return v;
  }
  double real(const std::string& expected) {
    auto t = token(expected);
    double v = 0;
    auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || p != t.data() + t.size() || !std::isfinite(v))
      fail("'" + std::string(t.substr(0, 40)) + "' is not a finite number, expected " + expected);
    return v;
  }
  std::string quoted(const std::string& expected) {
    skip_ws();
    last_ = pos_;
    if (pos_ >= data_.size() || data_[pos_] != '"') fail("expected a quoted " + expected);
    const auto e = data_.find('"', pos_ + 1);
    if (e == std::string::npos || data_.find('\n', pos_) < e) fail("unterminated quoted " + expected);
    std::string r = data_.substr(pos_ + 1, e - pos_ - 1);
    pos_ = e + 1;
    return r;
  }
  // binary mode: one newline after the section header line, then raw data
  void begin_binary() {
    while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
    if (pos_ < data_.size()) ++pos_;
    in_binary_block = true;
  }
  void end_binary() { in_binary_block = false; }
  template <class T>
  T get(const std::string& expected) {
    last_ = pos_;
    detail::binary_cursor c(file_, data_, pos_);
    T v = c.get<T>(expected);
    pos_ = c.pos();
    return v;
  }
  // A count is trusted only as far as the rest of the file can hold that many items.
  void check_count(std::uint64_t n, std::size_t min_bytes, const std::string& what) {
    if (min_bytes && n > left() / min_bytes + 1)
      fail(what + " " + std::to_string(n) + " exceeds what the remaining " + std::to_string(left()) +
           " bytes can hold");
  }
  // Generic readers for ints and size_t that work in both modes.
  long long read_int(const std::string& expected, long long lo, long long hi) {
    if (!in_binary_block) return integer(expected, lo, hi);
    const auto v = get<std::int32_t>(expected);
    if (v < lo || v > hi)
      fail(expected + " " + std::to_string(v) + " out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return v;
  }
  std::uint64_t read_size(const std::string& expected, std::uint64_t hi) {
    if (!in_binary_block) return static_cast<std::uint64_t>(integer(expected, 0, static_cast<long long>(std::min<std::uint64_t>(hi, std::numeric_limits<long long>::max()))));
    const auto v = get<std::uint64_t>(expected);
    if (v > hi) fail(expected + " " + std::to_string(v) + " out of range [0, " + std::to_string(hi) + "]");
    return v;
  }
  double read_real(const std::string& expected) {
    if (!in_binary_block) return real(expected);
    const auto v = get<double>(expected);
    if (!std::isfinite(v)) fail("coordinate is not a finite number, expected " + expected);
    return v;
  }
  std::size_t skip_to(const std::string& word) {
    const auto e = data_.find(word, pos_);
    if (e == std::string::npos) fail("missing '" + word + "'");
    pos_ = e;
    return e;
  }

 private:
  const std::string& file_;
  const std::string& data_;
  std::size_t pos_ = 0;
  std::size_t last_ = 0;
};

struct msh_block {
  int dim, entity, type;
  std::vector<vertex_id> conn;
  std::size_t where;  // position of the block header, for messages
};

struct msh_content {
  std::map<std::pair<int, int>, std::string> names;
  std::map<std::pair<int, int>, std::vector<int>> physicals;
  std::vector<point3> nodes;
  std::vector<std::size_t> node_at;  // position of each node's coordinates, for messages
  std::vector<msh_block> blocks;     // triangle and tetrahedron blocks
  bool binary = false;
};

constexpr long long int_max = std::numeric_limits<std::int32_t>::max();

void read_entities(msh_cursor& c, msh_content& m) {
  if (m.binary) c.begin_binary();
  std::uint64_t count[4];
  for (int d = 0; d < 4; ++d) count[d] = c.read_size("number of entities", int_max);
  for (int d = 0; d < 4; ++d) {
    c.check_count(count[d], 8, "number of entities");
    for (std::uint64_t e = 0; e < count[d]; ++e) {
      const int tag = static_cast<int>(c.read_int("entity tag", -int_max, int_max));
      for (int k = 0; k < (d == 0 ? 3 : 6); ++k) (void)c.read_real("entity coordinate");
      const auto np = c.read_size("number of physical tags", int_max);
      c.check_count(np, 2, "number of physical tags");
      auto& ph = m.physicals[{d, tag}];
      for (std::uint64_t k = 0; k < np; ++k) ph.push_back(static_cast<int>(c.read_int("physical tag", -int_max, int_max)));
      if (d > 0) {
        const auto nb = c.read_size("number of bounding entities", int_max);
        c.check_count(nb, 2, "number of bounding entities");
        for (std::uint64_t k = 0; k < nb; ++k) (void)c.read_int("bounding entity tag", -int_max, int_max);
      }
    }
  }
  c.end_binary();
  c.expect("$EndEntities");
}

void read_nodes(msh_cursor& c, msh_content& m, std::unordered_map<std::uint64_t, vertex_id>& ids) {
  if (m.binary) c.begin_binary();
  const auto blocks = c.read_size("number of node blocks", int_max);
  const auto total = c.read_size("number of nodes", std::numeric_limits<vertex_id>::max() - 1);
  c.check_count(total, m.binary ? 32 : 8, "number of nodes");
  (void)c.read_size("minimum node tag", std::numeric_limits<std::uint64_t>::max());
  (void)c.read_size("maximum node tag", std::numeric_limits<std::uint64_t>::max());
  m.nodes.reserve(total);
  ids.reserve(total);
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const int dim = static_cast<int>(c.read_int("entity dimension", 0, 3));
    (void)c.read_int("entity tag", -int_max, int_max);
    const bool parametric = c.read_int("parametric flag (0 or 1)", 0, 1) == 1;
    const auto n = c.read_size("number of nodes in block", total - m.nodes.size());
    std::vector<std::size_t> at;
    for (std::uint64_t k = 0; k < n; ++k) {
      const auto where = c.mark();
      const auto tag = c.read_size("node tag", std::numeric_limits<std::uint64_t>::max());
      if (!ids.emplace(tag, static_cast<vertex_id>(m.nodes.size() + k)).second)
        c.fail_at(where, "node tag " + std::to_string(tag) + " defined twice");
    }
    for (std::uint64_t k = 0; k < n; ++k) {
      at.push_back(c.mark());
      point3 p{c.read_real("node x"), c.read_real("node y"), c.read_real("node z")};
      if (parametric)
        for (int u = 0; u < dim; ++u) (void)c.read_real("parametric coordinate");
      m.nodes.push_back(p);
    }
    m.node_at.insert(m.node_at.end(), at.begin(), at.end());
  }
  if (m.nodes.size() != total) c.fail("node blocks hold " + std::to_string(m.nodes.size()) + " nodes, header says " + std::to_string(total));
  c.end_binary();
  c.expect("$EndNodes");
}

void read_elements(msh_cursor& c, msh_content& m, const std::unordered_map<std::uint64_t, vertex_id>& ids) {
  // sorted corners of every triangle/tetrahedron (triangles padded), to reject repeated elements
  std::unordered_map<std::array<vertex_id, 4>, std::uint64_t, detail::key_hash> seen_elements;
  if (m.binary) c.begin_binary();
  const auto blocks = c.read_size("number of element blocks", int_max);
  const auto total = c.read_size("number of elements", std::numeric_limits<std::uint32_t>::max());
  c.check_count(total, m.binary ? 16 : 4, "number of elements");
  (void)c.read_size("minimum element tag", std::numeric_limits<std::uint64_t>::max());
  (void)c.read_size("maximum element tag", std::numeric_limits<std::uint64_t>::max());
  std::uint64_t seen = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const auto where = c.mark();
    msh_block blk{};
    blk.where = where;
    blk.dim = static_cast<int>(c.read_int("entity dimension", 0, 3));
    blk.entity = static_cast<int>(c.read_int("entity tag", -int_max, int_max));
    blk.type = static_cast<int>(c.read_int("element type", 1, int_max));
    const auto kind = kind_of(blk.type);
    if (kind.dim < 0) c.fail("unsupported element type " + std::to_string(blk.type));
    if (kind.dim != blk.dim)
      c.fail("element type " + std::to_string(blk.type) + " has dimension " + std::to_string(kind.dim) +
             ", block says " + std::to_string(blk.dim));
    const auto n = c.read_size("number of elements in block", total - seen);
    seen += n;
    const bool keep = blk.type == 2 || blk.type == 4;
    if (keep) blk.conn.reserve(n * static_cast<std::uint64_t>(kind.nodes));
    for (std::uint64_t e = 0; e < n; ++e) {
      const auto etag = c.read_size("element tag", std::numeric_limits<std::uint64_t>::max());
      for (int k = 0; k < kind.nodes; ++k) {
        const auto at = c.mark();
        const auto tag = c.read_size("node tag of element", std::numeric_limits<std::uint64_t>::max());
        const auto it = ids.find(tag);
        if (it == ids.end()) c.fail_at(at, "element refers to node tag " + std::to_string(tag) + ", which is not defined");
        if (keep) blk.conn.push_back(it->second);
      }
      if (keep) {
        auto b0 = blk.conn.end() - kind.nodes;
        std::vector<vertex_id> s(b0, blk.conn.end());
        std::sort(s.begin(), s.end());
        if (std::adjacent_find(s.begin(), s.end()) != s.end()) c.fail("element repeats a node");
        std::array<vertex_id, 4> key;
        key.fill(no_vertex);
        std::copy(s.begin(), s.end(), key.begin());
        if (auto [it, fresh] = seen_elements.try_emplace(key, etag); !fresh)
          c.fail("element " + std::to_string(etag) + " has the same nodes as element " + std::to_string(it->second));
      }
    }
    if (keep) m.blocks.push_back(std::move(blk));
  }
  if (seen != total) c.fail("element blocks hold " + std::to_string(seen) + " elements, header says " + std::to_string(total));
  c.end_binary();
  c.expect("$EndElements");
}

msh_content parse_msh(const std::string& path) {
  const std::string data = detail::slurp(path);
  msh_cursor c(path, data);
  msh_content m;
  c.expect("$MeshFormat");
  const auto version = c.token("version");
  if (version != "4.1") c.fail("unsupported .msh version '" + std::string(version.substr(0, 20)) + "', expected 4.1");
  m.binary = c.integer("file type (0 ASCII, 1 binary)", 0, 1) == 1;
  const auto size = c.integer("data size", 0, 64);
  if (size != 8) c.fail("data size " + std::to_string(size) + " unsupported, expected 8");
  if (m.binary) {
    c.begin_binary();
    if (c.get<std::int32_t>("endianness marker 1") != 1) c.fail("endianness marker is not 1: byte order differs from this machine");
    c.end_binary();
  }
  c.expect("$EndMeshFormat");
  std::unordered_map<std::uint64_t, vertex_id> ids;
  bool have_nodes = false;
  while (!c.at_end()) {
    const auto head = c.token("section header");
    if (head == "$PhysicalNames") {
      const auto n = c.integer("number of physical names", 0, int_max);
      c.check_count(static_cast<std::uint64_t>(n), 6, "number of physical names");
      for (long long k = 0; k < n; ++k) {
        const int dim = static_cast<int>(c.integer("physical dimension", 0, 3));
        const int tag = static_cast<int>(c.integer("physical tag", -int_max, int_max));
        m.names[{dim, tag}] = c.quoted("physical name");
      }
      c.expect("$EndPhysicalNames");
    } else if (head == "$Entities") {
      read_entities(c, m);
    } else if (head == "$Nodes") {
      read_nodes(c, m, ids);
      have_nodes = true;
    } else if (head == "$Elements") {
      if (!have_nodes) c.fail("$Elements before $Nodes");
      read_elements(c, m, ids);
    } else if (head.size() > 1 && head[0] == '$') {
      c.skip_to("$End" + std::string(head.substr(1)));  // sections we do not use
      (void)c.token("section end");
    } else {
      c.fail("expected a section header ($Name), found '" + std::string(head.substr(0, 40)) + "'");
    }
  }
  return m;
}

template <std::size_t D>
domain<D> build(const std::string& path, msh_content& m) {
  constexpr int type = D == 3 ? 4 : 2;
  // positions are line numbers or byte offsets, as the file is text or binary
  auto fail_at = [&](std::size_t pos, const std::string& what) -> void {
    if (m.binary) throw io_error::at_byte(path, pos, what);
    std::string data = detail::slurp(path);
    throw io_error(path, 1 + static_cast<std::size_t>(std::count(data.begin(), data.begin() + static_cast<long>(pos), '\n')), what);
  };
  domain<D> d;
  auto& pts = d.mutable_points();
  pts.reserve(m.nodes.size());
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    point<D> p;
    for (std::size_t k = 0; k < D; ++k) p[k] = m.nodes[i][k];
    if (D == 2 && m.nodes[i][2] != 0.0) {
      std::string z;
      detail::append_real(z, m.nodes[i][2]);
      fail_at(m.node_at[i], "node has z = " + z + "; a 2D mesh needs z = 0");
    }
    pts.push_back(p);
  }
  {  // duplicate coordinates are an error, as for every other reader
    std::vector<std::size_t> order(pts.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return lex_less(pts[a], pts[b]) || (pts[a] == pts[b] && a < b); });
    for (std::size_t k = 1; k < order.size(); ++k)
      if (pts[order[k]] == pts[order[k - 1]]) {
        const auto a = std::min(order[k], order[k - 1]), b = std::max(order[k], order[k - 1]);
        fail_at(m.node_at[b], "duplicate point: node " + std::to_string(b + 1) + " (in file order) repeats node " + std::to_string(a + 1));
      }
  }
  std::map<int, segment<D>*> seg_of;
  for (auto& blk : m.blocks) {
    if (blk.dim != static_cast<int>(D)) continue;
    if (blk.type != type) fail_at(blk.where, "unsupported element type " + std::to_string(blk.type) + " in a " + std::to_string(D) + "D mesh");
    int number = blk.entity;
    std::string name;
    if (auto it = m.physicals.find({blk.dim, blk.entity}); it != m.physicals.end() && !it->second.empty()) {
      number = it->second.front();
      if (auto n = m.names.find({blk.dim, number}); n != m.names.end()) name = n->second;
    }
    if (name.empty()) name = "region_" + std::to_string(number);
    auto [it, fresh] = seg_of.try_emplace(number, nullptr);
    if (fresh) {
      if (d.find(name)) fail_at(blk.where, "physical name '" + name + "' is used by two physical groups");
      it->second = &d.add_segment(name, number);
    }
    auto& s = *it->second;
    for (std::size_t k = 0; k + D < blk.conn.size(); k += D + 1) {
      std::array<vertex_id, D + 1> cell;
      for (std::size_t j = 0; j <= D; ++j) cell[j] = blk.conn[k + j];
      s.add_cell(cell);
    }
  }
  if (d.segments().empty()) throw io_error::whole(path, std::string("no ") + (D == 3 ? "tetrahedra" : "triangles") + " in the mesh");
  detail::finalize_all(d, path);
  d.sync_slots();
  return d;
}

// Writes the same layout as text or as binary (Gmsh's binary 4.1 keeps the ASCII structure and
// writes ints as int32, counts and tags as size_t, coordinates as double).
class msh_writer {
 public:
  msh_writer(std::ostream& o, bool binary) : o_(o), binary_(binary) {}
  void line(const std::string& s) { o_ << s << '\n'; }
  void i32(long long v) { bin_or_text<std::int32_t>(v); }
  void size(std::uint64_t v) { bin_or_text<std::uint64_t>(v); }
  void real(double v) {
    if (binary_) {
      put(v);
    } else {
      std::string s;
      detail::append_real(s, v);
      o_ << sep() << s;
    }
  }
  void end_record() {
    if (!binary_) o_ << '\n';
    first_ = true;
  }
  void end_section(const char* name) {
    if (binary_) o_ << '\n';
    o_ << name << '\n';
  }

 private:
  const char* sep() {
    const char* s = first_ ? "" : " ";
    first_ = false;
    return s;
  }
  template <class T>
  void put(T v) {
    if constexpr (std::endian::native == std::endian::big) {
      unsigned char b[sizeof(T)];
      std::memcpy(b, &v, sizeof(T));
      std::reverse(b, b + sizeof(T));
      o_.write(reinterpret_cast<const char*>(b), sizeof(T));
    } else {
      o_.write(reinterpret_cast<const char*>(&v), sizeof(T));
    }
  }
  template <class T, class V>
  void bin_or_text(V v) {
    if (binary_)
      put(static_cast<T>(v));
    else
      o_ << sep() << v;
  }
  std::ostream& o_;
  bool binary_;
  bool first_ = true;
};

}  // namespace

template <std::size_t D>
domain<D> read_msh(const std::string& path) {
  auto m = parse_msh(path);
  return build<D>(path, m);
}
template domain<2> read_msh<2>(const std::string&);
template domain<3> read_msh<3>(const std::string&);

std::variant<domain<2>, domain<3>> read_msh_any(const std::string& path) {
  auto m = parse_msh(path);
  const bool tets = std::any_of(m.blocks.begin(), m.blocks.end(), [](const msh_block& b) { return b.type == 4; });
  if (tets) return build<3>(path, m);
  return build<2>(path, m);
}

template <std::size_t D>
void write_msh(const domain<D>& d, const std::string& path, bool binary) {
  detail::check_domain(d, path);
  for (const auto& s : d.segments())
    if (s.name().find_first_of("\"\n\r") != std::string::npos)
      throw io_error::whole(path, "segment name '" + s.name() + "' contains a quote or newline, which .msh cannot hold");
  const auto& pts = d.points();
  const auto& segs = d.segments();
  atomic_file f(path);
  auto& o = f.stream();
  msh_writer w(o, binary);
  o << "$MeshFormat\n4.1 " << (binary ? 1 : 0) << " 8\n";
  if (binary) {
    w.i32(1);
    o << '\n';
  }
  o << "$EndMeshFormat\n$PhysicalNames\n" << segs.size() << '\n';
  for (const auto& s : segs) o << D << ' ' << s.number() << " \"" << s.name() << "\"\n";
  o << "$EndPhysicalNames\n$Entities\n";
  for (std::size_t k = 0; k < 4; ++k) w.size(k == D ? segs.size() : 0);
  w.end_record();
  for (std::size_t k = 0; k < segs.size(); ++k) {
    point3 lo{0, 0, 0}, hi{0, 0, 0};
    if (segs[k].num_cells() > 0) {
      const auto& p0 = pts[segs[k].cell(0)[0]];
      for (std::size_t a = 0; a < D; ++a) lo[a] = hi[a] = p0[a];
    }
    for (const auto& c : segs[k].cell_data())
      for (auto v : c)
        for (std::size_t a = 0; a < D; ++a) {
          lo[a] = std::min(lo[a], pts[v][a]);
          hi[a] = std::max(hi[a], pts[v][a]);
        }
    w.i32(static_cast<long long>(k + 1));
    for (double x : lo) w.real(x);
    for (double x : hi) w.real(x);
    w.size(1);
    w.i32(segs[k].number());
    w.size(0);
    w.end_record();
  }
  w.end_section("$EndEntities");
  o << "$Nodes\n";
  const bool any = !pts.empty() && !segs.empty();
  w.size(any ? 1 : 0);
  w.size(any ? pts.size() : 0);
  w.size(any ? 1 : 0);
  w.size(any ? pts.size() : 0);
  w.end_record();
  if (any) {
    // all nodes in the first segment's entity; elements of every entity may refer to them
    w.i32(D);
    w.i32(1);
    w.i32(0);
    w.size(pts.size());
    w.end_record();
    for (std::size_t i = 0; i < pts.size(); ++i) {
      w.size(i + 1);
      w.end_record();
    }
    for (const auto& p : pts) {
      for (std::size_t a = 0; a < 3; ++a) w.real(a < D ? p[a] : 0.0);
      w.end_record();
    }
  }
  w.end_section("$EndNodes");
  o << "$Elements\n";
  std::size_t blocks = 0, total = 0;
  for (const auto& s : segs) {
    blocks += s.num_cells() > 0;
    total += s.num_cells();
  }
  w.size(blocks);
  w.size(total);
  w.size(total ? 1 : 0);
  w.size(total);
  w.end_record();
  std::size_t tag = 0;
  for (std::size_t k = 0; k < segs.size(); ++k) {
    if (segs[k].num_cells() == 0) continue;
    w.i32(D);
    w.i32(static_cast<long long>(k + 1));
    w.i32(D == 3 ? 4 : 2);
    w.size(segs[k].num_cells());
    w.end_record();
    for (const auto& c : segs[k].cell_data()) {
      w.size(++tag);
      for (auto v : c) w.size(std::uint64_t{v} + 1);
      w.end_record();
    }
  }
  w.end_section("$EndElements");
  f.commit();
}
template void write_msh<2>(const domain<2>&, const std::string&, bool);
template void write_msh<3>(const domain<3>&, const std::string&, bool);

}  // namespace gsse::io
