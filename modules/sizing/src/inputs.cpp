#include "gsse/sizing/inputs.hpp"

#include <charconv>
#include <cmath>

#include <filesystem>

#include "gsse/io/node_ele.hpp"
#include "gsse/io/text_reader.hpp"
#include "gsse/io/vtu.hpp"

namespace gsse::sizing {

namespace {

// A .vtu background: its tetrahedra (2D: triangles, z ignored) and the point array "size".
template <std::size_t D>
std::shared_ptr<const typename spec<D>::background_mesh> read_background_vtu(const std::string& path) {
  const io::vtu_grid g = io::read_vtu(path);
  auto B = std::make_shared<typename spec<D>::background_mesh>();
  B->source = path;
  B->points.reserve(g.points.size());
  for (const auto& x : g.points) {
    point<D> p;
    for (std::size_t k = 0; k < D; ++k) p[k] = x[k];
    B->points.push_back(p);
  }
  // VTK cell types: the simplices used, the lower-dimensional ones skipped, other cells of the
  // mesh's dimension refused (a background must be simplicial to interpolate linearly)
  const std::uint8_t simplex = D == 3 ? 10 : 5;
  auto volume_type = [](std::uint8_t t) -> const char* {
    if constexpr (D == 3) {
      switch (t) {
        case 11: return "voxel";
        case 12: return "hexahedron";
        case 13: return "wedge";
        case 14: return "pyramid";
        case 24: return "quadratic tetrahedron";
        case 25: return "quadratic hexahedron";
        case 42: return "polyhedron";
        default: return nullptr;
      }
    } else {
      switch (t) {
        case 6: return "triangle strip";
        case 7: return "polygon";
        case 8: return "pixel";
        case 9: return "quadrilateral";
        case 22: return "quadratic triangle";
        default: return nullptr;
      }
    }
  };
  for (std::size_t c = 0; c < g.cell_types.size(); ++c) {
    const std::uint8_t t = g.cell_types[c];
    if (t == simplex) {
      if (g.cell_start[c + 1] - g.cell_start[c] != D + 1)
        throw io::io_error(path, g.cells_line, "cell " + std::to_string(c) + " has " + std::to_string(g.cell_start[c + 1] - g.cell_start[c]) + " vertices for its type");
      std::array<vertex_id, D + 1> s;
      for (std::size_t k = 0; k <= D; ++k) s[k] = static_cast<vertex_id>(g.connectivity[g.cell_start[c] + k]);
      B->cells.push_back(s);
    } else if (const char* what = volume_type(t)) {
      throw io::io_error(path, g.cells_line, "cell " + std::to_string(c) + " is a " + what + " (VTK type " + std::to_string(t) + "); a " + std::to_string(D) +
                                                 "D background mesh must be made of " + (D == 3 ? "tetrahedra" : "triangles"));
    }
  }
  if (B->cells.empty())
    throw io::io_error(path, g.cells_line ? g.cells_line : 1, std::string("no ") + (D == 3 ? "tetrahedra" : "triangles") + " in the background mesh");
  const io::vtu_grid::array* h = g.point_array("size");
  if (!h) {
    std::string names;
    for (const auto& a : g.point_data) names += (names.empty() ? "" : ", ") + a.name;
    throw io::io_error(path, 1, "no point data array 'size' (point arrays: " + (names.empty() ? std::string("none") : names) + ")");
  }
  if (h->components != 1) throw io::io_error(path, h->line, "point data 'size' has " + std::to_string(h->components) + " components (one size per point)");
  for (std::size_t i = 0; i < h->values.size(); ++i)
    if (!(h->values[i] > 0) || !std::isfinite(h->values[i]))
      throw io::io_error(path, h->line, "the size of point " + std::to_string(i) + " must be positive and finite (it is " + std::to_string(h->values[i]) + ")");
  B->size = h->values;
  return B;
}

}  // namespace

std::vector<std::string> background_files(const std::string& path) {
  if (path.size() > 4 && path.compare(path.size() - 4, 4, ".vtu") == 0) return {path};
  std::string base = path;
  for (const char* e : {".node", ".ele", ".mtr"}) {
    const std::string ext = e;
    if (base.size() > ext.size() && base.compare(base.size() - ext.size(), ext.size(), ext) == 0) {
      base.resize(base.size() - ext.size());
      break;
    }
  }
  return {base + ".node", base + ".ele", base + ".mtr"};
}

template <std::size_t D>
std::shared_ptr<const typename spec<D>::background_mesh> read_background(const std::string& path) {
  const std::vector<std::string> files = background_files(path);
  if (files.size() == 1) return read_background_vtu<D>(path);
  const std::string base = files[0].substr(0, files[0].size() - 5);  // BASE.node without .node
  const domain<D> d = io::read_node_ele<D>(base);
  auto B = std::make_shared<typename spec<D>::background_mesh>();
  B->source = base + ".mtr";
  B->points = d.points();
  for (const auto& s : d.segments())
    for (const auto& c : s.cell_data()) B->cells.push_back(c);
  io::text_reader r(base + ".mtr");
  r.require_line("size count line '<#points> <#values per point>'");
  const long n = r.integer_in("number of points", 0, 1'000'000'000);
  if (static_cast<std::size_t>(n) != B->points.size())
    r.fail(std::to_string(n) + " sizes for " + std::to_string(B->points.size()) + " nodes in " + base + ".node");
  const long per = r.optional_integer("values per point", 1);
  if (per != 1) r.fail("one size per point is supported (an isotropic size), not " + std::to_string(per));
  B->size.reserve(static_cast<std::size_t>(n));
  for (long i = 0; i < n; ++i) {
    r.require_line("size of node " + std::to_string(i + 1));
    const double h = r.real("size");
    if (!(h > 0)) r.fail("the size of node " + std::to_string(i + 1) + " must be positive");
    B->size.push_back(h);
  }
  return B;
}

template <std::size_t D>
void add_sidecar(spec<D>& s, const io::sizing_table& t, const plc<D>& p, const std::string& sidecar_path) {
  auto number = [&](const std::string& name, std::size_t line) {
    for (const auto& r : p.regions)
      if (r.name == name) return r.number;
    int n = 0;
    auto [end, ec] = std::from_chars(name.data(), name.data() + name.size(), n);
    if (ec == std::errc() && end == name.data() + name.size())
      for (const auto& r : p.regions)
        if (r.number == n) return n;
    std::string known;
    for (const auto& r : p.regions) known += (known.empty() ? "" : ", ") + (r.name.empty() ? std::to_string(r.number) : r.name);
    throw io::io_error(sidecar_path, line, "no segment '" + name + "' in " + p.source + (known.empty() ? "" : " (segments: " + known + ")"));
  };
  for (const auto& e : t.sizes) {
    const int n = number(e.segment, e.line);
    auto [it, fresh] = s.segment_size.try_emplace(n, e.size);
    if (!fresh) it->second = std::min(it->second, e.size);
  }
  for (const auto& L : t.interfaces) s.interfaces.push_back({number(L.a, L.line), number(L.b, L.line), L.size, L.grade});
  for (const auto& b : t.boxes) {
    if (b.lo.size() != D)
      throw io::io_error(sidecar_path, b.line, "a refinement box of " + std::to_string(b.lo.size()) + " coordinates for a " +
                                                   std::to_string(D) + "D input");
    typename spec<D>::box x;
    for (std::size_t k = 0; k < D; ++k) x.lo[k] = b.lo[k], x.hi[k] = b.hi[k];
    x.size = b.size;
    x.grade = b.grade;
    s.boxes.push_back(x);
  }
  if (!t.background.empty()) {
    const std::filesystem::path rel(t.background);
    s.background = read_background<D>(rel.is_absolute() ? rel.string() : (std::filesystem::path(sidecar_path).parent_path() / rel).string());
  }
  if (t.grade > 0) s.grade = t.grade;
}

template void add_sidecar<2>(spec<2>&, const io::sizing_table&, const plc<2>&, const std::string&);
template void add_sidecar<3>(spec<3>&, const io::sizing_table&, const plc<3>&, const std::string&);
template std::shared_ptr<const spec<2>::background_mesh> read_background<2>(const std::string&);
template std::shared_ptr<const spec<3>::background_mesh> read_background<3>(const std::string&);

}  // namespace gsse::sizing
