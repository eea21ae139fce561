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
#include <tuple>
#include <unordered_map>

#include "binary_cursor.hpp"
#include "facets.hpp"
#include "gsse/io/atomic_file.hpp"
#include "number_format.hpp"
#include "parallel_text.hpp"

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
  std::vector<vertex_id> conn;    // kept types (triangles, quadrangles, tetrahedra) only
  std::vector<std::size_t> at;    // position of each kept surface element, for messages
  std::size_t where;              // position of the block header (2.2: of its first element)
};

struct msh_content {
  std::map<std::pair<int, int>, std::string> names;
  std::map<std::pair<int, int>, std::vector<int>> physicals;
  std::vector<point3> nodes;
  std::vector<std::size_t> node_at;      // position of each node's coordinates, for messages
  std::vector<std::uint64_t> node_tags;  // the file's tag of each node, for messages
  std::vector<msh_block> blocks;         // triangle, quadrangle and tetrahedron blocks
  std::vector<msh_block> others;         // headers of the other 2D and 3D element blocks
  std::vector<int> volumes;              // volume entity tags in file order (4.1 $Entities)
  std::map<int, std::vector<int>> bounds;     // volume tag -> its bounding surface tags (signed)
  std::map<int, std::size_t> volume_at;       // volume tag -> position of its $Entities record
  bool binary = false;
  bool v2 = false;  // version 2.2
};

constexpr long long int_max = std::numeric_limits<std::int32_t>::max();

void read_entities(msh_cursor& c, msh_content& m) {
  if (m.binary) c.begin_binary();
  std::uint64_t count[4];
  for (int d = 0; d < 4; ++d) count[d] = c.read_size("number of entities", int_max);
  for (int d = 0; d < 4; ++d) {
    c.check_count(count[d], 8, "number of entities");
    for (std::uint64_t e = 0; e < count[d]; ++e) {
      const auto where = c.mark();
      const int tag = static_cast<int>(c.read_int("entity tag", -int_max, int_max));
      for (int k = 0; k < (d == 0 ? 3 : 6); ++k) (void)c.read_real("entity coordinate");
      const auto np = c.read_size("number of physical tags", int_max);
      c.check_count(np, 2, "number of physical tags");
      auto& ph = m.physicals[{d, tag}];
      for (std::uint64_t k = 0; k < np; ++k) ph.push_back(static_cast<int>(c.read_int("physical tag", -int_max, int_max)));
      if (d > 0) {
        const auto nb = c.read_size("number of bounding entities", int_max);
        c.check_count(nb, 2, "number of bounding entities");
        std::vector<int> b;
        for (std::uint64_t k = 0; k < nb; ++k) b.push_back(static_cast<int>(c.read_int("bounding entity tag", -int_max, int_max)));
        if (d == 3) {
          if (!m.bounds.emplace(tag, std::move(b)).second) c.fail_at(where, "volume " + std::to_string(tag) + " listed twice");
          m.volumes.push_back(tag);
          m.volume_at[tag] = where;
        }
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
      m.node_tags.push_back(tag);
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

// Version 2.2: a count line, then 'tag x y z' per node (binary: int32 tag, three doubles).
void read_nodes_v2(msh_cursor& c, msh_content& m, std::unordered_map<std::uint64_t, vertex_id>& ids) {
  const auto total = static_cast<std::uint64_t>(c.integer("number of nodes", 0, std::numeric_limits<vertex_id>::max() - 1));
  if (m.binary) c.begin_binary();
  c.check_count(total, m.binary ? 28 : 8, "number of nodes");
  m.nodes.reserve(total);
  ids.reserve(total);
  for (std::uint64_t k = 0; k < total; ++k) {
    const auto where = c.mark();
    const auto tag = static_cast<std::uint64_t>(c.read_int("node tag", 1, int_max));
    if (!ids.emplace(tag, static_cast<vertex_id>(m.nodes.size())).second)
      c.fail_at(where, "node tag " + std::to_string(tag) + " defined twice");
    m.node_tags.push_back(tag);
    m.node_at.push_back(c.mark());
    m.nodes.push_back({c.read_real("node x"), c.read_real("node y"), c.read_real("node z")});
  }
  c.end_binary();
  c.expect("$EndNodes");
}

// Collects the element blocks of both versions: keeps the connectivity of triangles,
// quadrangles and tetrahedra, rejects elements that repeat a node or another element's nodes.
class element_store {
 public:
  element_store(msh_cursor& c, msh_content& m) : c_(c), m_(m) {}
  /// Starts a block; returns the number of nodes per element.
  int begin(int dim, int entity, int type, std::size_t where) {
    const auto kind = kind_of(type);
    if (kind.dim < 0) c_.fail_at(where, "unsupported element type " + std::to_string(type));
    if (kind.dim != dim)
      c_.fail_at(where, "element type " + std::to_string(type) + " has dimension " + std::to_string(kind.dim) +
                            ", block says " + std::to_string(dim));
    msh_block blk{};
    blk.dim = dim;
    blk.entity = entity;
    blk.type = type;
    blk.where = where;
    keep_ = type == 2 || type == 3 || type == 4;
    nodes_ = kind.nodes;
    if (keep_) {
      m_.blocks.push_back(std::move(blk));
    } else {
      if (dim >= 2) m_.others.push_back(std::move(blk));
      cur_ = nullptr;
      return nodes_;
    }
    cur_ = &m_.blocks.back();
    return nodes_;
  }
  /// One element of the current block. `repeats_ok`: an element with the nodes of an earlier
  /// one of the same entity is dropped (2.2 writes an element once per physical group).
  void add(std::uint64_t etag, std::size_t where, const vertex_id* nodes, bool repeats_ok) {
    if (!keep_) return;
    std::array<vertex_id, 4> key;  // kept elements have at most 4 nodes; the rest is padding
    key.fill(no_vertex);
    for (std::size_t k = 0; k < key.size() && k < static_cast<std::size_t>(nodes_); ++k) key[k] = nodes[k];
    std::sort(key.begin(), key.end());
    for (std::size_t k = 1; k < key.size() && k < static_cast<std::size_t>(nodes_); ++k)
      if (key[k] == key[k - 1]) c_.fail_at(where, "element repeats a node");
    const auto [it, fresh] = seen_.try_emplace(key, seen{etag, cur_->dim, cur_->entity});
    if (!fresh) {
      if (repeats_ok && it->second.dim == cur_->dim && it->second.entity == cur_->entity) return;
      // which entities: two surfaces of a model that share a triangle (Gmsh meshes a surface
      // cut at a tangent plane so) are named as Gmsh names them
      auto entity = [](int dim, int tag) {
        return std::string(dim == 3 ? "volume " : dim == 2 ? "surface " : dim == 1 ? "curve " : "point ") + std::to_string(tag);
      };
      c_.fail_at(where, "element " + std::to_string(etag) + " (" + entity(cur_->dim, cur_->entity) + ") has the same nodes as element " +
                            std::to_string(it->second.tag) + " (" + entity(it->second.dim, it->second.entity) + ")" +
                            (it->second.entity != cur_->entity || it->second.dim != cur_->dim ? ": the two entities overlap there" : ""));
    }
    cur_->conn.insert(cur_->conn.end(), nodes, nodes + nodes_);
    if (cur_->dim == 2) cur_->at.push_back(where);
  }

 private:
  struct seen {
    std::uint64_t tag;
    int dim, entity;
  };
  msh_cursor& c_;
  msh_content& m_;
  msh_block* cur_ = nullptr;
  bool keep_ = false;
  int nodes_ = 0;
  std::unordered_map<std::array<vertex_id, 4>, seen, detail::key_hash> seen_;
};

vertex_id node_id(msh_cursor& c, const std::unordered_map<std::uint64_t, vertex_id>& ids, std::uint64_t tag, std::size_t at) {
  const auto it = ids.find(tag);
  if (it == ids.end()) c.fail_at(at, "element refers to node tag " + std::to_string(tag) + ", which is not defined");
  return it->second;
}

void read_elements(msh_cursor& c, msh_content& m, const std::unordered_map<std::uint64_t, vertex_id>& ids) {
  element_store store(c, m);
  if (m.binary) c.begin_binary();
  const auto blocks = c.read_size("number of element blocks", int_max);
  const auto total = c.read_size("number of elements", std::numeric_limits<std::uint32_t>::max());
  c.check_count(total, m.binary ? 16 : 4, "number of elements");
  (void)c.read_size("minimum element tag", std::numeric_limits<std::uint64_t>::max());
  (void)c.read_size("maximum element tag", std::numeric_limits<std::uint64_t>::max());
  std::uint64_t seen = 0;
  std::vector<vertex_id> nodes;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const auto where = c.mark();
    const int dim = static_cast<int>(c.read_int("entity dimension", 0, 3));
    const int entity = static_cast<int>(c.read_int("entity tag", -int_max, int_max));
    const int type = static_cast<int>(c.read_int("element type", 1, int_max));
    const int per = store.begin(dim, entity, type, where);
    const auto n = c.read_size("number of elements in block", total - seen);
    seen += n;
    nodes.resize(static_cast<std::size_t>(per));
    for (std::uint64_t e = 0; e < n; ++e) {
      const auto at = c.mark();
      const auto etag = c.read_size("element tag", std::numeric_limits<std::uint64_t>::max());
      for (int k = 0; k < per; ++k) {
        const auto nat = c.mark();
        nodes[static_cast<std::size_t>(k)] = node_id(c, ids, c.read_size("node tag of element", std::numeric_limits<std::uint64_t>::max()), nat);
      }
      store.add(etag, at, nodes.data(), false);
    }
  }
  if (seen != total) c.fail("element blocks hold " + std::to_string(seen) + " elements, header says " + std::to_string(total));
  c.end_binary();
  c.expect("$EndElements");
}

// Version 2.2: 'tag type #tags tags... nodes...' per element; tag 1 is the physical group, tag 2
// the elementary entity. Binary: headers (type, count, #tags) each followed by `count` elements
// of int32s. Consecutive elements of one entity and type form a block.
void read_elements_v2(msh_cursor& c, msh_content& m, const std::unordered_map<std::uint64_t, vertex_id>& ids) {
  element_store store(c, m);
  const auto total = static_cast<std::uint64_t>(c.integer("number of elements", 0, std::numeric_limits<std::uint32_t>::max()));
  if (m.binary) c.begin_binary();
  c.check_count(total, m.binary ? 16 : 8, "number of elements");
  int cur_dim = -1, cur_entity = 0, cur_type = -1, per = 0;
  std::uint64_t group_left = 0;  // binary: elements left under the current header
  int group_type = 0, group_tags = 0;
  std::vector<vertex_id> nodes;
  for (std::uint64_t e = 0; e < total; ++e) {
    if (m.binary && group_left == 0) {
      group_type = static_cast<int>(c.read_int("element type", 1, int_max));
      group_left = static_cast<std::uint64_t>(c.read_int("number of elements following", 1, static_cast<long long>(total - e)));
      group_tags = static_cast<int>(c.read_int("number of tags", 0, 1000));
    }
    const auto at = c.mark();
    const auto etag = static_cast<std::uint64_t>(c.read_int("element tag", 1, int_max));
    int type = group_type, ntags = group_tags;
    if (!m.binary) {
      type = static_cast<int>(c.read_int("element type", 1, int_max));
      ntags = static_cast<int>(c.read_int("number of tags", 0, 1000));
    }
    int physical = 0, entity = 0;
    for (int k = 0; k < ntags; ++k) {
      const int t = static_cast<int>(c.read_int("element tag value", -int_max, int_max));
      if (k == 0) physical = t;
      if (k == 1) entity = t;
    }
    const auto kind = kind_of(type);
    if (kind.dim < 0) c.fail_at(at, "unsupported element type " + std::to_string(type));
    if (kind.dim != cur_dim || entity != cur_entity || type != cur_type) {
      per = store.begin(kind.dim, entity, type, at);
      cur_dim = kind.dim, cur_entity = entity, cur_type = type;
    }
    if (physical != 0) {
      auto& ph = m.physicals[{kind.dim, entity}];
      if (std::find(ph.begin(), ph.end(), physical) == ph.end()) ph.push_back(physical);
    }
    nodes.resize(static_cast<std::size_t>(per));
    for (int k = 0; k < per; ++k) {
      const auto nat = c.mark();
      nodes[static_cast<std::size_t>(k)] = node_id(c, ids, static_cast<std::uint64_t>(c.read_int("node tag of element", 1, int_max)), nat);
    }
    store.add(etag, at, nodes.data(), true);
    if (m.binary) --group_left;
  }
  c.end_binary();
  c.expect("$EndElements");
}

// `data` is the whole file; it must outlive the cursor only, not the result.
msh_content parse_msh(const std::string& path, const std::string& data) {
  msh_cursor c(path, data);
  msh_content m;
  c.expect("$MeshFormat");
  const auto version = c.token("version");
  if (version == "2.2")
    m.v2 = true;
  else if (version != "4.1")
    c.fail("unsupported .msh version '" + std::string(version.substr(0, 20)) + "', expected 4.1 or 2.2");
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
    } else if (head == "$Entities" && !m.v2) {
      read_entities(c, m);
    } else if (head == "$Nodes") {
      if (m.v2)
        read_nodes_v2(c, m, ids);
      else
        read_nodes(c, m, ids);
      have_nodes = true;
    } else if (head == "$Elements") {
      if (!have_nodes) c.fail("$Elements before $Nodes");
      if (m.v2)
        read_elements_v2(c, m, ids);
      else
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

// Duplicate coordinates are an error, as for every other reader: `fail(a, b)` (a < b, the point
// that repeats a) for the first pair in coordinate order.
template <std::size_t D, class Fail>
void check_distinct(const std::vector<point<D>>& pts, Fail&& fail) {
  std::vector<std::size_t> order(pts.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return lex_less(pts[a], pts[b]) || (pts[a] == pts[b] && a < b); });
  for (std::size_t k = 1; k < order.size(); ++k)
    if (pts[order[k]] == pts[order[k - 1]]) fail(std::min(order[k], order[k - 1]), std::max(order[k], order[k - 1]));
}

// Error at a position of the file: its line (text) or byte offset (binary).
[[noreturn]] void fail_in_file(const std::string& path, const std::string& data, bool binary, std::size_t pos, const std::string& what) {
  if (binary) throw io_error::at_byte(path, pos, what);
  throw io_error(path, 1 + static_cast<std::size_t>(std::count(data.begin(), data.begin() + static_cast<long>(std::min(pos, data.size())), '\n')), what);
}

template <std::size_t D>
domain<D> build(const std::string& path, const std::string& data, msh_content& m) {
  constexpr int type = D == 3 ? 4 : 2;
  // positions are line numbers or byte offsets, as the file is text or binary
  auto fail_at = [&](std::size_t pos, const std::string& what) { fail_in_file(path, data, m.binary, pos, what); };
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
  check_distinct(pts, [&](std::size_t a, std::size_t b) {
    fail_at(m.node_at[b], "duplicate point: node " + std::to_string(b + 1) + " (in file order) repeats node " + std::to_string(a + 1));
  });
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
  const std::string data = detail::slurp(path);
  auto m = parse_msh(path, data);
  return build<D>(path, data, m);
}
template domain<2> read_msh<2>(const std::string&);
template domain<3> read_msh<3>(const std::string&);

std::variant<domain<2>, domain<3>> read_msh_any(const std::string& path) {
  const std::string data = detail::slurp(path);
  auto m = parse_msh(path, data);
  const bool tets = std::any_of(m.blocks.begin(), m.blocks.end(), [](const msh_block& b) { return b.type == 4; });
  if (tets) return build<3>(path, data, m);
  return build<2>(path, data, m);
}

namespace {

std::string element_name(int type) {
  switch (type) {
    case 4: return "tetrahedra (type 4)";
    case 5: return "hexahedra (type 5)";
    case 6: return "prisms (type 6)";
    case 7: return "pyramids (type 7)";
    case 9: return "second-order triangles (type 9)";
    case 10: return "second-order quadrangles (type 10)";
    case 16: return "second-order quadrangles (type 16)";
    default: return "elements of type " + std::to_string(type);
  }
}

// Line numbers of increasing positions of a text, in one pass.
std::vector<std::size_t> lines_of(const std::string& data, const std::vector<std::size_t>& pos) {
  std::vector<std::size_t> out;
  out.reserve(pos.size());
  std::size_t line = 1, at = 0;
  for (const auto p : pos) {
    const auto end = std::min(p, data.size());
    if (end > at) line += static_cast<std::size_t>(std::count(data.begin() + static_cast<long>(at), data.begin() + static_cast<long>(end), '\n'));
    at = std::max(at, end);
    out.push_back(line);
  }
  return out;
}

struct edge_use {
  vertex_id a, b;
  std::size_t facet;
  auto operator<=>(const edge_use&) const = default;
};

// The edges of the given facets' polygons, sorted: each edge's uses form one run.
std::vector<edge_use> edge_uses(const plc<3>& p, const std::vector<std::size_t>& facets) {
  std::vector<edge_use> e;
  for (const auto f : facets)
    for (const auto& poly : p.facets[f].polygons)
      for (std::size_t i = 0; i < poly.size(); ++i) {
        const auto [a, b] = std::minmax(poly[i], poly[(i + 1) % poly.size()]);
        e.push_back({a, b, f});
      }
  std::sort(e.begin(), e.end());
  return e;
}

}  // namespace

plc<3> read_msh_plc(const std::string& path, std::vector<plc_volume>* volumes) {
  if (volumes) volumes->clear();
  const std::string data = detail::slurp(path);
  auto m = parse_msh(path, data);
  auto fail_at = [&](std::size_t pos, const std::string& what) { fail_in_file(path, data, m.binary, pos, what); };
  for (const auto* list : {&m.blocks, &m.others})
    for (const auto& b : *list) {
      if (b.dim == 3)
        fail_at(b.where, element_name(b.type) + ": a volume mesh, not a surface mesh (mesh the surfaces only, gmsh -2, "
                         "or read the volume mesh with read_msh)");
      if (b.type != 2 && b.type != 3)
        fail_at(b.where, element_name(b.type) + " cannot be surface facets: linear triangles (type 2) and quadrangles "
                         "(type 3) only (gmsh -order 1)");
    }
  std::vector<char> used(m.nodes.size(), 0);
  std::vector<std::size_t> element_at;  // increasing positions of all surface elements
  for (const auto& b : m.blocks) {
    for (const auto v : b.conn) used[v] = 1;
    element_at.insert(element_at.end(), b.at.begin(), b.at.end());
  }
  if (element_at.empty()) throw io_error::whole(path, "no triangles or quadrangles: nothing to read as a surface");
  plc<3> out;
  out.source = path;
  for (const auto& [dt, name] : m.names)  // surface groups name the facet markers they give
    if (dt.first == 2) out.marker_names[dt.second] = name;
  std::vector<vertex_id> id(m.nodes.size(), no_vertex);
  std::vector<std::size_t> node_of;  // node index of each point
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (used[i]) {
      id[i] = static_cast<vertex_id>(out.points.size());
      out.points.push_back(m.nodes[i]);
      out.point_markers.push_back(0);
      node_of.push_back(i);
    }
  auto tag = [&](vertex_id v) { return std::to_string(m.node_tags[node_of[v]]); };
  check_distinct(out.points, [&](std::size_t a, std::size_t b) {
    fail_at(m.node_at[node_of[b]], "duplicate point: node " + tag(static_cast<vertex_id>(b)) + " repeats node " +
                                       tag(static_cast<vertex_id>(a)));
  });
  const auto lines = m.binary ? std::vector<std::size_t>(element_at.size(), 0) : lines_of(data, element_at);
  std::map<int, std::vector<std::size_t>> facets_of;  // surface entity -> its facets
  // a surface without a physical group is marked by its entity tag, negated where the file has
  // surface groups: a group's tag (a contact, say) must not collide with another surface's tag
  bool grouped = false;
  for (const auto& b : m.blocks)
    if (auto it = m.physicals.find({2, b.entity}); it != m.physicals.end() && !it->second.empty()) grouped = true;
  for (const auto& b : m.blocks) {
    const std::size_t per = b.type == 2 ? 3 : 4;
    int marker = grouped ? -b.entity : b.entity;
    if (auto it = m.physicals.find({2, b.entity}); it != m.physicals.end() && !it->second.empty()) marker = it->second.front();
    auto& mine = facets_of[b.entity];
    for (std::size_t k = 0; k + per <= b.conn.size(); k += per) {
      plc_facet f;
      f.marker = marker;
      f.line = lines[out.facets.size()];
      f.polygons.emplace_back();
      for (std::size_t j = 0; j < per; ++j) f.polygons.back().push_back(id[b.conn[k + j]]);
      mine.push_back(out.facets.size());
      out.facets.push_back(std::move(f));
    }
  }
  auto edge_text = [&](const edge_use& e) { return "edge (nodes " + tag(e.a) + ", " + tag(e.b) + ")"; };
  if (m.volumes.empty()) {  // like OFF and STL: every edge must be shared
    std::vector<std::size_t> all(out.facets.size());
    std::iota(all.begin(), all.end(), 0);
    const auto e = edge_uses(out, all);
    for (std::size_t i = 0; i < e.size();) {
      std::size_t j = i;
      while (j < e.size() && e[j].a == e[i].a && e[j].b == e[i].b) ++j;
      if (j - i == 1)
        fail_at(element_at[e[i].facet], "surface is not closed: " + edge_text(e[i]) +
                                            " belongs to 1 face; without volume entities every face must bound a cell");
      i = j;
    }
    return out;
  }
  // volumes: numbers and names from physical groups; an entity tag must not pose as a group
  std::map<int, int> physical_of;  // volume -> its first physical tag
  for (const int v : m.volumes)
    if (auto it = m.physicals.find({3, v}); it != m.physicals.end() && !it->second.empty()) physical_of[v] = it->second.front();
  std::vector<plc_volume> list;
  for (const int v : m.volumes) {
    plc_volume pv;
    pv.entity = v;
    const auto ph = physical_of.find(v);
    pv.number = ph != physical_of.end() ? ph->second : v;
    if (ph == physical_of.end())
      for (const auto& [w, p] : physical_of)
        if (p == v)
          fail_at(m.volume_at[v], "volume " + std::to_string(v) + " has no physical group, and its tag " + std::to_string(v) +
                                      " is the physical group of volume " + std::to_string(w) + ": give it a physical group");
    if (auto n = m.names.find({3, pv.number}); ph != physical_of.end() && n != m.names.end()) pv.name = n->second;
    if (pv.name.empty()) pv.name = "region_" + std::to_string(pv.number);
    std::vector<int> surfaces;
    for (const int s : m.bounds[v]) surfaces.push_back(std::abs(s));
    std::sort(surfaces.begin(), surfaces.end());
    surfaces.erase(std::unique(surfaces.begin(), surfaces.end()), surfaces.end());
    if (surfaces.empty()) fail_at(m.volume_at[v], "volume " + std::to_string(v) + " has no bounding surfaces");
    for (const int s : surfaces) {
      const auto it = facets_of.find(s);
      if (it == facets_of.end())
        fail_at(m.volume_at[v], "volume " + std::to_string(v) + " is bounded by surface " + std::to_string(s) +
                                    ", which has no triangles or quadrangles in the file (save every element: gmsh -save_all)");
      pv.facets.insert(pv.facets.end(), it->second.begin(), it->second.end());
    }
    std::sort(pv.facets.begin(), pv.facets.end());
    // a closed boundary has every edge in an even number of its faces (2, or 4 where it pinches)
    const auto e = edge_uses(out, pv.facets);
    for (std::size_t i = 0; i < e.size();) {
      std::size_t j = i;
      while (j < e.size() && e[j].a == e[i].a && e[j].b == e[i].b) ++j;
      if ((j - i) % 2)
        fail_at(element_at[e[i].facet], "volume " + std::to_string(v) + " is not closed: " + edge_text(e[i]) + " lies in " +
                                            std::to_string(j - i) + " of its boundary faces, a closed boundary needs an even number");
      i = j;
    }
    list.push_back(std::move(pv));
  }
  if (volumes) *volumes = std::move(list);
  return out;
}

namespace {

/// The boundary groups of a mesh for Gmsh: one entity of dimension D-1 per (marker, first
/// segment, second segment) of its boundary, interface and marked faces; a physical group per
/// nonzero marker (tag = the marker when positive, name from the sidecar, else "facet_<m>") and
/// per interface between two segments (name "<first>:<second>", first of lower number).
template <std::size_t D>
struct boundary_groups {
  struct entity {
    int marker;
    long a, b;                              // segment indices; b < 0: outside (-1) or inside a (-2)
    std::vector<std::array<vertex_id, D>> faces;
    std::vector<int> physicals;
  };
  struct group {
    int tag;
    std::string name;
  };
  std::vector<entity> entities;
  std::vector<group> groups;  // dimension D-1

  boundary_groups(const domain<D>& d, const std::string& path) {
    const auto outer = detail::outer_facets(d, path);
    const auto marks = detail::mark_facets(d, outer);
    std::map<std::tuple<int, long, long>, std::size_t> at;
    auto add = [&](int m, long a, long b, const std::array<vertex_id, D>& f) {
      auto [it, fresh] = at.try_emplace({m, a, b}, entities.size());
      if (fresh) entities.push_back({m, a, b, {}, {}});
      entities[it->second].faces.push_back(f);
    };
    for (std::size_t i = 0; i < outer.size(); ++i) add(marks.outer[i], static_cast<long>(outer[i].first), outer[i].second, outer[i].vertices);
    for (const auto& [f, m] : marks.inner) add(m, -2, -2, f);
    // groups: positive markers keep their number as tag; interfaces and other markers after them
    std::map<int, int> marker_tag;
    int next = 1;
    for (const auto& e : entities)
      if (e.marker > 0) marker_tag[e.marker] = e.marker, next = std::max(next, e.marker + 1);
    for (const auto& e : entities)
      if (e.marker < 0 && !marker_tag.count(e.marker)) marker_tag[e.marker] = 0;
    std::map<std::pair<long, long>, int> interface_tag;
    for (const auto& e : entities)
      if (e.b >= 0) interface_tag[{e.a, e.b}] = 0;
    for (auto& [ab, t] : interface_tag) t = next++;
    for (auto& [m, t] : marker_tag)
      if (t == 0) t = next++;
    const auto& segs = d.segments();
    for (const auto& [m, t] : marker_tag) {
      const auto n = d.marker_names().find(m);
      groups.push_back({t, n != d.marker_names().end() ? n->second : "facet_" + std::to_string(m)});
    }
    for (const auto& [ab, t] : interface_tag)
      groups.push_back({t, segs[static_cast<std::size_t>(ab.first)].name() + ":" + segs[static_cast<std::size_t>(ab.second)].name()});
    std::sort(groups.begin(), groups.end(), [](const group& x, const group& y) { return x.tag < y.tag; });
    for (auto& e : entities) {
      if (e.marker != 0) e.physicals.push_back(marker_tag.at(e.marker));
      if (e.b >= 0) e.physicals.push_back(interface_tag.at({e.a, e.b}));
    }
    // faces in no group (unmarked outer boundary) are left out, as Gmsh leaves out elements of
    // entities without a physical group (meshio cannot read a file that mixes both)
    std::erase_if(entities, [](const entity& e) { return e.physicals.empty(); });
    for (const auto& g : groups)
      if (g.name.find_first_of("\"\n\r") != std::string::npos)
        throw io_error::whole(path, "group name '" + g.name + "' contains a quote or newline, which .msh cannot hold");
  }
};

template <std::size_t D>
void write_msh22(const domain<D>& d, const boundary_groups<D>& g, atomic_file& f) {
  const auto& pts = d.points();
  const auto& segs = d.segments();
  auto& o = f.stream();
  o << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n" << segs.size() + g.groups.size() << '\n';
  for (const auto& x : g.groups) o << D - 1 << ' ' << x.tag << " \"" << x.name << "\"\n";
  for (const auto& s : segs) o << D << ' ' << s.number() << " \"" << s.name() << "\"\n";
  o << "$EndPhysicalNames\n$Nodes\n" << pts.size() << '\n';
  std::string line;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    line.clear();
    detail::append_int(line, static_cast<long long>(i + 1));
    for (std::size_t a = 0; a < 3; ++a) detail::append_real(line += ' ', a < D ? pts[i][a] : 0.0);
    o << line << '\n';
  }
  // every element once per physical group of its entity (as Gmsh writes 2.2)
  std::size_t total = 0;
  for (const auto& s : segs) total += s.num_cells();
  for (const auto& e : g.entities) total += e.faces.size() * e.physicals.size();
  o << "$EndNodes\n$Elements\n" << total << '\n';  // lines, not distinct numbers
  std::size_t tag = 0;
  auto element = [&](std::size_t id, int type, int physical, long entity, const auto& vs) {
    line.clear();
    detail::append_int(line, static_cast<long long>(id));
    detail::append_int(line += ' ', type);
    line += " 2";
    detail::append_int(line += ' ', physical);
    detail::append_int(line += ' ', entity);
    for (auto v : vs) detail::append_int(line += ' ', static_cast<long long>(v) + 1);
    o << line << '\n';
  };
  for (std::size_t k = 0; k < segs.size(); ++k)
    for (const auto& c : segs[k].cell_data()) element(++tag, D == 3 ? 4 : 2, segs[k].number(), static_cast<long>(k + 1), c);
  // a face in two groups is written twice with the same element number, as Gmsh does: its
  // reader then keeps one element in both groups
  for (std::size_t k = 0; k < g.entities.size(); ++k) {
    const std::size_t first = tag;
    for (int ph : g.entities[k].physicals) {
      std::size_t id = first;
      for (const auto& fc : g.entities[k].faces) element(++id, D == 3 ? 2 : 1, ph, static_cast<long>(k + 1), fc);
    }
    tag = first + g.entities[k].faces.size();
  }
  o << "$EndElements\n";
}

}  // namespace

template <std::size_t D>
void write_msh(const domain<D>& d, const std::string& path, bool binary, msh_version version) {
  detail::check_domain(d, path);
  for (const auto& s : d.segments())
    if (s.name().find_first_of("\"\n\r") != std::string::npos)
      throw io_error::whole(path, "segment name '" + s.name() + "' contains a quote or newline, which .msh cannot hold");
  if (binary && version == msh_version::v22) throw io_error::whole(path, "Gmsh 2.2 output is ASCII only");
  const boundary_groups<D> g(d, path);
  const auto& pts = d.points();
  const auto& segs = d.segments();
  atomic_file f(path);
  if (version == msh_version::v22) {
    write_msh22(d, g, f);
    f.commit();
    return;
  }
  auto& o = f.stream();
  msh_writer w(o, binary);
  o << "$MeshFormat\n4.1 " << (binary ? 1 : 0) << " 8\n";
  if (binary) {
    w.i32(1);
    o << '\n';
  }
  o << "$EndMeshFormat\n$PhysicalNames\n" << segs.size() + g.groups.size() << '\n';
  for (const auto& x : g.groups) o << D - 1 << ' ' << x.tag << " \"" << x.name << "\"\n";
  for (const auto& s : segs) o << D << ' ' << s.number() << " \"" << s.name() << "\"\n";
  o << "$EndPhysicalNames\n$Entities\n";
  for (std::size_t k = 0; k < 4; ++k) w.size(k == D ? segs.size() : k + 1 == D ? g.entities.size() : 0);
  w.end_record();
  auto bounds = [&](const auto& cells) {
    point3 lo{0, 0, 0}, hi{0, 0, 0};
    bool first = true;
    for (const auto& c : cells)
      for (auto v : c)
        for (std::size_t a = 0; a < D; ++a) {
          lo[a] = first ? pts[v][a] : std::min(lo[a], pts[v][a]);
          hi[a] = first ? pts[v][a] : std::max(hi[a], pts[v][a]);
          first = first && a + 1 < D;
        }
    for (double x : lo) w.real(x);
    for (double x : hi) w.real(x);
  };
  for (std::size_t k = 0; k < g.entities.size(); ++k) {  // curves (2D) or surfaces (3D)
    w.i32(static_cast<long long>(k + 1));
    bounds(g.entities[k].faces);
    w.size(g.entities[k].physicals.size());
    for (int ph : g.entities[k].physicals) w.i32(ph);
    w.size(0);
    w.end_record();
  }
  for (std::size_t k = 0; k < segs.size(); ++k) {
    w.i32(static_cast<long long>(k + 1));
    bounds(segs[k].cell_data());
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
  for (const auto& e : g.entities) {
    blocks += !e.faces.empty();
    total += e.faces.size();
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
  for (std::size_t k = 0; k < g.entities.size(); ++k) {
    w.i32(D - 1);
    w.i32(static_cast<long long>(k + 1));
    w.i32(D == 3 ? 2 : 1);
    w.size(g.entities[k].faces.size());
    w.end_record();
    for (const auto& c : g.entities[k].faces) {
      w.size(++tag);
      for (auto v : c) w.size(std::uint64_t{v} + 1);
      w.end_record();
    }
  }
  w.end_section("$EndElements");
  f.commit();
}
template void write_msh<2>(const domain<2>&, const std::string&, bool, msh_version);
template void write_msh<3>(const domain<3>&, const std::string&, bool, msh_version);

}  // namespace gsse::io
