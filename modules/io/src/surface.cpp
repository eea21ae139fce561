#include "gsse/io/surface.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include "binary_cursor.hpp"
#include "gsse/io/poly.hpp"
#include "gsse/io/text_reader.hpp"

namespace gsse::io {

namespace detail {
std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io_error::whole(path, "cannot open file for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
}  // namespace detail

namespace {

// A surface bounds cells when every edge belongs to at least two facets: two for a single shell,
// more where shells meet (several volumes sharing faces). An edge in one facet is a hole in the
// surface, which the mesher cannot fill.
void check_closed(const std::string& file, const plc<3>& p, bool binary) {
  std::map<std::pair<vertex_id, vertex_id>, std::pair<int, std::size_t>> use;  // edge -> (count, facet)
  for (std::size_t f = 0; f < p.facets.size(); ++f) {
    const auto& poly = p.facets[f].polygons.front();
    for (std::size_t i = 0; i < poly.size(); ++i) {
      auto a = poly[i], b = poly[(i + 1) % poly.size()];
      auto& u = use[{std::min(a, b), std::max(a, b)}];
      if (u.first++ == 0) u.second = f;
    }
  }
  for (const auto& [e, u] : use)
    if (u.first < 2) {
      const std::string what = "surface is not closed: edge (" + std::to_string(e.first + 1) + ", " +
                               std::to_string(e.second + 1) + ") belongs to 1 face, a closed surface needs at least 2";
      // binary STL: facet.line is the triangle number; point at the triangle's record
      if (binary) throw io_error::at_byte(file, 84 + 50 * (p.facets[u.second].line - 1), what);
      throw io_error(file, p.facets[u.second].line, what);
    }
}

void check_polygon(text_reader& r, const std::vector<vertex_id>& poly) {
  auto s = poly;
  std::sort(s.begin(), s.end());
  if (std::adjacent_find(s.begin(), s.end()) != s.end()) r.fail("face repeats a vertex");
}

plc<3> read_stl_ascii(const std::string& path, std::string data);
plc<3> read_stl_binary(const std::string& path, const std::string& data);

struct bits_hash {
  std::size_t operator()(const std::array<std::uint64_t, 3>& k) const {
    std::size_t h = 1469598103934665603ull;
    for (auto v : k) h = (h ^ v) * 1099511628211ull;
    return h;
  }
};

// Merges vertices with bitwise-equal coordinates (STL repeats every vertex per triangle).
class vertex_merger {
 public:
  explicit vertex_merger(plc<3>& p) : p_(p) {}
  vertex_id add(point3 x) {
    std::array<std::uint64_t, 3> k;
    for (std::size_t i = 0; i < 3; ++i) {
      x[i] += 0.0;  // -0.0 -> +0.0, which compare equal and would otherwise be "duplicates"
      std::memcpy(&k[i], &x[i], sizeof(double));
    }
    auto [it, fresh] = ids_.try_emplace(k, static_cast<vertex_id>(p_.points.size()));
    if (fresh) {
      p_.points.push_back(x);
      p_.point_markers.push_back(0);
    }
    return it->second;
  }

 private:
  plc<3>& p_;
  std::unordered_map<std::array<std::uint64_t, 3>, vertex_id, bits_hash> ids_;
};

bool lower_equal(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != b[i]) return false;
  return true;
}

void keyword(text_reader& r, std::string_view kw) {
  auto t = r.token(kw);
  if (!lower_equal(t, kw)) r.fail("expected '" + std::string(kw) + "', found '" + std::string(t) + "'");
}

plc<3> read_stl_ascii(const std::string& path, std::string data) {
  text_reader r(path, std::move(data));
  plc<3> out;
  out.source = path;
  vertex_merger m(out);
  r.require_line("'solid <name>'");
  keyword(r, "solid");
  while (true) {
    r.require_line("'facet normal' or 'endsolid'");
    auto t = r.token("'facet' or 'endsolid'");
    if (lower_equal(t, "endsolid")) break;
    if (!lower_equal(t, "facet")) r.fail("expected 'facet' or 'endsolid', found '" + std::string(t) + "'");
    plc_facet f;
    f.line = r.line();
    r.require_line("'outer loop'");
    keyword(r, "outer");
    keyword(r, "loop");
    std::vector<vertex_id> tri;
    for (int k = 0; k < 3; ++k) {
      r.require_line("'vertex x y z'");
      keyword(r, "vertex");
      point3 x{r.real("vertex x"), r.real("vertex y"), r.real("vertex z")};
      tri.push_back(m.add(x));
    }
    check_polygon(r, tri);
    r.require_line("'endloop'");
    keyword(r, "endloop");
    r.require_line("'endfacet'");
    keyword(r, "endfacet");
    f.polygons.push_back(std::move(tri));
    out.facets.push_back(std::move(f));
  }
  return out;
}

plc<3> read_stl_binary(const std::string& path, const std::string& data) {
  detail::binary_cursor c(path, data);
  c.need(84, "80-byte header and triangle count");
  c.seek(80);
  const auto n = c.get<std::uint32_t>("triangle count");
  const std::uint64_t expected = 84 + 50 * static_cast<std::uint64_t>(n);
  if (expected != data.size())
    throw io_error::at_byte(path, 80,
                            "binary STL with " + std::to_string(n) + " triangles must have " + std::to_string(expected) +
                                " bytes, file has " + std::to_string(data.size()));
  plc<3> out;
  out.source = path;
  vertex_merger m(out);
  out.facets.reserve(n);
  for (std::uint32_t t = 0; t < n; ++t) {
    const std::size_t start = c.pos();
    for (int k = 0; k < 3; ++k) (void)c.get<float>("normal");
    std::vector<vertex_id> tri;
    for (int v = 0; v < 3; ++v) {
      point3 x;
      for (std::size_t k = 0; k < 3; ++k) {
        const auto at = c.pos();
        const float f = c.get<float>("vertex coordinate");
        if (!std::isfinite(f)) throw io_error::at_byte(path, at, "coordinate is not a finite number");
        x[k] = static_cast<double>(f);
      }
      tri.push_back(m.add(x));
    }
    (void)c.get<std::uint16_t>("attribute byte count");
    auto s = tri;
    std::sort(s.begin(), s.end());
    if (std::adjacent_find(s.begin(), s.end()) != s.end())
      throw io_error::at_byte(path, start, "triangle " + std::to_string(t + 1) + " repeats a vertex");
    plc_facet f;
    f.line = t + 1;  // triangle number (binary files have no lines)
    f.polygons.push_back(std::move(tri));
    out.facets.push_back(std::move(f));
  }
  return out;
}

}  // namespace

std::string single_segment_name(const std::string& source) {
  auto s = std::filesystem::path(source).stem().string();
  return s.empty() ? std::string("segment_1") : s;
}

plc<3> read_off(const std::string& path) {
  text_reader r(path);
  plc<3> out;
  out.source = path;
  r.require_line("'OFF' header");
  auto h = r.token("'OFF' header");
  if (h != "OFF") r.fail("expected 'OFF' header, found '" + std::string(h) + "'");
  if (!r.has_token()) r.require_line("'<#vertices> <#faces> <#edges>'");
  const long nv = r.integer_in("number of vertices", 0, 100'000'000);
  const long nf = r.integer_in("number of faces", 0, 100'000'000);
  (void)r.optional_integer("number of edges", 0);
  std::vector<std::size_t> lines;
  out.points.reserve(std::min(static_cast<std::size_t>(nv), r.bytes_left() / 2 + 1));
  for (long i = 0; i < nv; ++i) {
    r.require_line("vertex " + std::to_string(i + 1) + " of " + std::to_string(nv));
    out.points.push_back({r.real("vertex x"), r.real("vertex y"), r.real("vertex z")});
    out.point_markers.push_back(0);
    lines.push_back(r.line());
  }
  for (long f = 0; f < nf; ++f) {
    r.require_line("face " + std::to_string(f + 1) + " of " + std::to_string(nf));
    plc_facet facet;
    facet.line = r.line();
    const long nc = r.integer_in("number of face corners", 3, 1'000'000);
    std::vector<vertex_id> poly;
    for (long c = 0; c < nc; ++c)
      poly.push_back(static_cast<vertex_id>(r.integer_in("vertex index", 0, static_cast<long>(out.points.size()) - 1)));
    check_polygon(r, poly);  // trailing tokens (colours) are ignored
    facet.polygons.push_back(std::move(poly));
    out.facets.push_back(std::move(facet));
  }
  if (out.facets.empty()) r.fail("OFF file has no faces");
  check_points<3>(path, out.points, lines);
  check_closed(path, out, false);
  return out;
}

plc<3> read_stl(const std::string& path) {
  std::string data = detail::slurp(path);
  // A binary file may also begin with "solid"; the size its header states decides.
  bool binary = data.rfind("solid", 0) != 0;
  if (data.size() >= 84) {
    detail::binary_cursor c(path, data, 80);
    if (84 + 50 * static_cast<std::uint64_t>(c.get<std::uint32_t>("triangle count")) == data.size()) binary = true;
  }
  plc<3> out = binary ? read_stl_binary(path, data) : read_stl_ascii(path, std::move(data));
  if (out.facets.empty()) throw io_error::whole(path, "STL file has no triangles");
  check_closed(path, out, binary);
  return out;
}

}  // namespace gsse::io
