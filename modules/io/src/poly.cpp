#include "gsse/io/poly.hpp"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <numeric>

#include "gsse/io/atomic_file.hpp"
#include "gsse/io/gmsh.hpp"
#include "gsse/io/sidecar.hpp"
#include "gsse/io/surface.hpp"
#include "gsse/io/text_reader.hpp"
#include "node_block.hpp"
#include "number_format.hpp"

namespace gsse::io {
namespace {

std::string extension_of(const std::string& path) {
  auto e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

template <std::size_t D>
long read_points(text_reader& r, const std::string& path, plc<D>& out, std::vector<std::size_t>& lines) {
  r.require_line("point count line '<#points> <dimension> <#attributes> <#markers>'");
  const long n = r.integer_in("number of points", 0, 100'000'000);
  const long dim = r.integer("dimension");
  if (dim != static_cast<long>(D))
    r.fail("dimension " + std::to_string(dim) + " where " + std::to_string(D) + " was expected");
  const long attributes = r.optional_integer("number of attributes", 0);
  const long markers = r.optional_integer("number of boundary markers", 0);
  if (attributes < 0 || markers < 0 || markers > 1) r.fail("invalid attribute or marker count");
  if (n > 0) return detail::read_node_block<D>(r, n, attributes, markers, out.points, out.point_markers, lines);
  // points in BASE.node
  const std::string node = base_of(path) + ".node";
  text_reader nr(node);
  nr.require_line("point count line");
  const long m = nr.integer_in("number of points", 1, 100'000'000);
  const long d2 = nr.integer("dimension");
  if (d2 != static_cast<long>(D)) nr.fail("dimension " + std::to_string(d2) + " where " + std::to_string(D) + " was expected");
  const long a2 = nr.optional_integer("number of attributes", 0);
  const long m2 = nr.optional_integer("number of boundary markers", 0);
  return detail::read_node_block<D>(nr, m, a2, m2, out.points, out.point_markers, lines);
}


template <std::size_t D>
void read_holes_and_regions(text_reader& r, plc<D>& out, bool triangle) {
  if (!r.next_line()) return;  // hole and region sections are optional at end of file
  const long nh = r.integer_in("number of holes", 0, 100'000'000);
  for (long i = 0; i < nh; ++i) {
    r.require_line("hole " + std::to_string(i + 1));
    (void)r.integer("hole number");
    point<D> p;
    for (std::size_t k = 0; k < D; ++k) p[k] = r.real(std::string("hole ") + "xyz"[k]);
    out.holes.push_back(p);
  }
  if (!r.next_line()) return;
  const long nr = r.integer_in("number of regions", 0, 100'000'000);
  for (long i = 0; i < nr; ++i) {
    r.require_line("region " + std::to_string(i + 1));
    (void)r.integer("region number");
    plc_region<D> g;
    for (std::size_t k = 0; k < D; ++k) g.at[k] = r.real(std::string("region ") + "xyz"[k]);
    g.number = static_cast<int>(r.integer_in("region attribute", -1'000'000'000, 1'000'000'000));
    g.max_volume = r.optional_real(triangle ? "maximum area" : "maximum volume", -1);
    (void)triangle;
    out.regions.push_back(g);
  }
}

}  // namespace

namespace detail {
template <std::size_t D>
long read_node_block(text_reader& r, long count, long attributes, long markers, std::vector<point<D>>& pts,
                     std::vector<int>& point_markers, std::vector<std::size_t>& lines) {
  long base = 0;
  // a point takes at least one line of a few bytes: never reserve more than the file can hold
  pts.reserve(std::min(static_cast<std::size_t>(count), r.bytes_left() / 2 + 1));
  for (long i = 0; i < count; ++i) {
    r.require_line("point " + std::to_string(i + 1) + " of " + std::to_string(count));
    const long id = r.integer("point number");
    if (i == 0) {
      if (id != 0 && id != 1) r.fail("first point number must be 0 or 1, got " + std::to_string(id));
      base = id;
    } else if (id != base + i) {
      r.fail("point number " + std::to_string(id) + " out of sequence, expected " + std::to_string(base + i));
    }
    point<D> p;
    for (std::size_t k = 0; k < D; ++k) p[k] = r.real(std::string(1, "xyz"[k]) + " coordinate");
    for (long a = 0; a < attributes; ++a) (void)r.real("point attribute");
    point_markers.push_back(markers ? static_cast<int>(r.optional_integer("boundary marker", 0)) : 0);
    pts.push_back(p);
    lines.push_back(r.line());
  }
  return base;
}
template long read_node_block<2>(text_reader&, long, long, long, std::vector<point<2>>&, std::vector<int>&,
                                 std::vector<std::size_t>&);
template long read_node_block<3>(text_reader&, long, long, long, std::vector<point<3>>&, std::vector<int>&,
                                 std::vector<std::size_t>&);
}  // namespace detail

template <std::size_t D>
void check_points(const std::string& file, const std::vector<point<D>>& pts, const std::vector<std::size_t>& lines) {
  std::vector<std::size_t> order(pts.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) {
    return lex_less(pts[a], pts[b]) || (pts[a] == pts[b] && a < b);
  });
  for (std::size_t k = 1; k < order.size(); ++k)
    if (pts[order[k]] == pts[order[k - 1]]) {
      const auto a = std::min(order[k], order[k - 1]), b = std::max(order[k], order[k - 1]);
      throw io_error(file, lines.empty() ? 0 : lines[b],
                     "duplicate point: point " + std::to_string(b + 1) + " repeats point " + std::to_string(a + 1) +
                         (lines.empty() ? std::string() : " (line " + std::to_string(lines[a]) + ")"));
    }
}
template void check_points<2>(const std::string&, const std::vector<point<2>>&, const std::vector<std::size_t>&);
template void check_points<3>(const std::string&, const std::vector<point<3>>&, const std::vector<std::size_t>&);

plc<3> read_tetgen_poly(const std::string& path) {
  text_reader r(path);
  plc<3> out;
  out.source = path;
  std::vector<std::size_t> lines;
  const long base = read_points<3>(r, path, out, lines);
  const bool smesh = extension_of(path) == ".smesh";
  r.require_line("facet count line '<#facets> <#markers>'");
  const long nf = r.integer_in("number of facets", 0, 100'000'000);
  const long fmark = r.optional_integer("number of boundary markers", 0);
  for (long f = 0; f < nf; ++f) {
    plc_facet facet;
    r.require_line("facet " + std::to_string(f + 1));
    facet.line = r.line();
    if (smesh) {
      const long nc = r.integer_in("number of corners", 1, 1'000'000);
      std::vector<vertex_id> poly;
      for (long c = 0; c < nc; ++c) poly.push_back(detail::vertex_ref(r, base, out.points.size(), "corner"));
      facet.marker = fmark ? static_cast<int>(r.optional_integer("facet marker", 0)) : 0;
      facet.polygons.push_back(std::move(poly));
    } else {
      const long np = r.integer_in("number of polygons", 1, 1'000'000);
      const long nh = r.optional_integer("number of facet holes", 0);
      if (nh < 0) r.fail("negative number of facet holes");
      facet.marker = fmark ? static_cast<int>(r.optional_integer("facet marker", 0)) : 0;
      for (long p = 0; p < np; ++p) {
        r.require_line("polygon " + std::to_string(p + 1) + " of facet " + std::to_string(f + 1));
        const long nc = r.integer_in("number of corners", 1, 1'000'000);
        std::vector<vertex_id> poly;
        for (long c = 0; c < nc; ++c) poly.push_back(detail::vertex_ref(r, base, out.points.size(), "corner"));
        facet.polygons.push_back(std::move(poly));
      }
      for (long h = 0; h < nh; ++h) {
        r.require_line("hole " + std::to_string(h + 1) + " of facet " + std::to_string(f + 1));
        (void)r.integer("hole number");
        point3 p{r.real("hole x"), r.real("hole y"), r.real("hole z")};
        facet.holes.push_back(p);
      }
    }
    out.facets.push_back(std::move(facet));
  }
  read_holes_and_regions(r, out, false);
  check_points<3>(path, out.points, lines);
  assign_region_names(out, path);
  return out;
}

plc<2> read_triangle_poly(const std::string& path) {
  text_reader r(path);
  plc<2> out;
  out.source = path;
  std::vector<std::size_t> lines;
  const long base = read_points<2>(r, path, out, lines);
  r.require_line("segment count line '<#segments> <#markers>'");
  const long ns = r.integer_in("number of segments", 0, 100'000'000);
  const long smark = r.optional_integer("number of boundary markers", 0);
  for (long s = 0; s < ns; ++s) {
    r.require_line("segment " + std::to_string(s + 1));
    (void)r.integer("segment number");
    const vertex_id a = detail::vertex_ref(r, base, out.points.size(), "endpoint");
    const vertex_id b = detail::vertex_ref(r, base, out.points.size(), "endpoint");
    if (a == b) r.fail("segment " + std::to_string(s + 1) + " has equal endpoints");
    out.edges.push_back({a, b});
    out.edge_markers.push_back(smark ? static_cast<int>(r.optional_integer("segment marker", 0)) : 0);
  }
  read_holes_and_regions(r, out, true);
  check_points<2>(path, out.points, lines);
  assign_region_names(out, path);
  return out;
}

template <std::size_t D>
std::vector<point<D>> read_node(const std::string& path) {
  text_reader r(path);
  plc<D> tmp;
  std::vector<std::size_t> lines;
  r.require_line("point count line '<#points> <dimension> <#attributes> <#markers>'");
  const long n = r.integer_in("number of points", 0, 100'000'000);
  const long dim = r.integer("dimension");
  if (dim != static_cast<long>(D)) r.fail("dimension " + std::to_string(dim) + " where " + std::to_string(D) + " was expected");
  const long attributes = r.optional_integer("number of attributes", 0);
  const long markers = r.optional_integer("number of boundary markers", 0);
  if (attributes < 0 || markers < 0 || markers > 1) r.fail("invalid attribute or marker count");
  detail::read_node_block<D>(r, n, attributes, markers, tmp.points, tmp.point_markers, lines);
  check_points<D>(path, tmp.points, lines);
  return tmp.points;
}
template std::vector<point<2>> read_node<2>(const std::string&);
template std::vector<point<3>> read_node<3>(const std::string&);

int poly_dimension(const std::string& path) {
  text_reader r(path);
  r.require_line("point count line '<#points> <dimension> ...'");
  (void)r.integer("number of points");
  const long d = r.integer("dimension");
  if (d != 2 && d != 3) r.fail("dimension must be 2 or 3, got " + std::to_string(d));
  if (d == 3 || r.line() == 0) return static_cast<int>(d);
  return 2;
}

template <std::size_t D>
void assign_region_names(plc<D>& p, const std::string& path) {
  const segment_table t = read_sidecar(base_of(path) + ".json");
  for (const auto& [m, n] : t.facet_names) p.marker_names.try_emplace(m, n);
  for (auto& g : p.regions) {
    if (!g.name.empty()) continue;
    g.name = t.name_of(g.number);
    if (g.name.empty()) g.name = "region_" + std::to_string(g.number);
  }
}
template void assign_region_names<2>(plc<2>&, const std::string&);
template void assign_region_names<3>(plc<3>&, const std::string&);

any_plc read_plc(const std::string& path, std::vector<plc_volume>* volumes) {
  if (volumes) volumes->clear();
  const auto ext = extension_of(path);
  if (ext == ".smesh") return read_tetgen_poly(path);
  if (ext == ".poly") {
    if (poly_dimension(path) == 2) return read_triangle_poly(path);
    return read_tetgen_poly(path);
  }
  if (ext == ".off") return read_off(path);
  if (ext == ".stl") return read_stl(path);
  if (ext == ".msh") return read_msh_plc(path, volumes);
  throw io_error::whole(path, "unsupported input format '" + ext + "' (expected .poly, .smesh, .off, .stl or .msh)");
}

namespace {

void put_real(std::string& line, double x) {
  line += ' ';
  detail::append_real(line, x);
}

template <std::size_t D>
void put_point(std::string& line, const point<D>& p) {
  for (std::size_t k = 0; k < D; ++k) put_real(line, p[k]);
}

// Points (from 1, with markers), then `body` (facets or segments), then holes and regions.
template <std::size_t D>
void write_poly(const plc<D>& p, const std::string& path, const std::function<void(std::ostream&)>& body) {
  write_atomically(path, [&](std::ostream& o) {
    std::string line;
    o << "# " << (D == 3 ? "TetGen" : "Triangle") << " .poly written by gsse" << (p.source.empty() ? "" : " from " + p.source)
      << "\n" << p.points.size() << ' ' << D << " 0 1\n";
    for (std::size_t i = 0; i < p.points.size(); ++i) {
      line = std::to_string(i + 1);
      put_point(line, p.points[i]);
      line += ' ' + std::to_string(i < p.point_markers.size() ? p.point_markers[i] : 0) + '\n';
      o << line;
    }
    body(o);
    o << p.holes.size() << '\n';
    for (std::size_t i = 0; i < p.holes.size(); ++i) {
      line = std::to_string(i + 1);
      put_point(line, p.holes[i]);
      o << line << '\n';
    }
    o << p.regions.size() << '\n';
    for (std::size_t i = 0; i < p.regions.size(); ++i) {
      const auto& g = p.regions[i];
      line = std::to_string(i + 1);
      put_point(line, g.at);
      line += ' ' + std::to_string(g.number);
      put_real(line, g.max_volume);
      o << line << '\n';
    }
  });
  if (p.regions.empty()) return;
  segment_table t;  // names by number, in order of first appearance
  for (const auto& g : p.regions)
    if (std::find(t.numbers.begin(), t.numbers.end(), g.number) == t.numbers.end()) {
      t.numbers.push_back(g.number);
      t.names.push_back(g.name.empty() ? "region_" + std::to_string(g.number) : g.name);
    }
  write_sidecar(base_of(path) + ".json", t);
}

}  // namespace

void write_tetgen_poly(const plc<3>& p, const std::string& path) {
  write_poly<3>(p, path, [&](std::ostream& o) {
    o << p.facets.size() << " 1\n";
    std::string line;
    for (const auto& f : p.facets) {
      o << f.polygons.size() << ' ' << f.holes.size() << ' ' << f.marker << '\n';
      for (const auto& poly : f.polygons) {
        line = std::to_string(poly.size());
        for (const auto v : poly) line += ' ' + std::to_string(std::uint64_t{v} + 1);
        o << line << '\n';
      }
      for (std::size_t h = 0; h < f.holes.size(); ++h) {
        line = std::to_string(h + 1);
        put_point(line, f.holes[h]);
        o << line << '\n';
      }
    }
  });
}

void write_triangle_poly(const plc<2>& p, const std::string& path) {
  write_poly<2>(p, path, [&](std::ostream& o) {
    o << p.edges.size() << " 1\n";
    for (std::size_t i = 0; i < p.edges.size(); ++i)
      o << i + 1 << ' ' << std::uint64_t{p.edges[i][0]} + 1 << ' ' << std::uint64_t{p.edges[i][1]} + 1 << ' '
        << (i < p.edge_markers.size() ? p.edge_markers[i] : 0) << '\n';
  });
}

}  // namespace gsse::io
