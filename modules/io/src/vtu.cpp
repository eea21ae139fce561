#include "gsse/io/vtu.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <typeinfo>

#include "facets.hpp"
#include "gsse/io/boundary.hpp"
#include "gsse/io/atomic_file.hpp"

namespace gsse::io {
namespace {

struct data_array {
  bool on_cells;
  std::string name;
  const char* type;  // VTK type name
  int components;
  std::string bytes;
};

template <class T>
void append(std::string& b, T v) {
  if constexpr (std::endian::native == std::endian::big) {
    // VTK reads the file's declared byte order; we declare the native one, so no swap is needed
  }
  char c[sizeof(T)];
  std::memcpy(c, &v, sizeof(T));
  b.append(c, sizeof(T));
}

std::string xml_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      default: r += c;
    }
  }
  return r;
}

// One column written over `n` entries: stored values first, zero-padded or truncated to n.
template <class T>
std::string column_bytes(const std::vector<T>& col, std::size_t n) {
  std::string b;
  b.reserve(n * sizeof(T));
  for (std::size_t i = 0; i < n; ++i) append(b, i < col.size() ? col[i] : T{});
  return b;
}

void write_grid(std::ostream& o, const std::string& points, std::size_t npoints, std::size_t ncells,
                const std::vector<data_array>& arrays, const std::string& conn, const std::string& offsets,
                const std::string& types) {
  std::uint64_t at = 0;
  std::vector<const std::string*> order;
  auto decl = [&](const std::string& attrs, const std::string& bytes) {
    o << "      <DataArray " << attrs << " format=\"appended\" offset=\"" << at << "\"/>\n";
    at += 8 + bytes.size();
    order.push_back(&bytes);
  };
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\""
    << (std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian")
    << "\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" << npoints
    << "\" NumberOfCells=\"" << ncells << "\">\n";
  for (bool cells : {false, true}) {
    o << (cells ? "     <CellData Scalars=\"segment\">\n" : "     <PointData>\n");
    for (const auto& a : arrays)
      if (a.on_cells == cells) decl("type=\"" + std::string(a.type) + "\" Name=\"" + xml_escape(a.name) + "\"", a.bytes);
    o << (cells ? "     </CellData>\n" : "     </PointData>\n");
  }
  o << "     <Points>\n";
  decl("type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"", points);
  o << "     </Points>\n     <Cells>\n";
  decl("type=\"Int64\" Name=\"connectivity\"", conn);
  decl("type=\"Int64\" Name=\"offsets\"", offsets);
  decl("type=\"UInt8\" Name=\"types\"", types);
  o << "     </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";
  for (const auto* b : order) {
    std::string h;
    append(h, static_cast<std::uint64_t>(b->size()));
    o << h << *b;
  }
  o << "\n  </AppendedData>\n</VTKFile>\n";
}

}  // namespace

template <std::size_t D>
void write_vtu(const domain<D>& d, const std::string& path) {
  detail::check_domain(d, path);
  const auto& pts = d.points();
  const auto& segs = d.segments();
  std::size_t ncells = 0;
  for (const auto& s : segs) ncells += s.num_cells();
  std::vector<data_array> arrays;

  // point data: per segment vertex quantities
  for (const auto& s : segs) {
    const auto& q = s.quantities();
    for (std::size_t k = 0; k < q.size(); ++k) {
      const auto& m = q.meta(k);
      if (m.on_cells) continue;
      if (auto c = q.template typed<double>(k)) arrays.push_back({false, s.name() + "/" + m.name, "Float64", 1, column_bytes(*c, pts.size())});
      else if (auto i = q.template typed<int>(k)) arrays.push_back({false, s.name() + "/" + m.name, "Int32", 1, column_bytes(*i, pts.size())});
    }
  }
  // cell data: segment numbers, then cell quantities
  {
    std::string b;
    for (const auto& s : segs)
      for (std::size_t c = 0; c < s.num_cells(); ++c) append(b, static_cast<std::int32_t>(s.number()));
    arrays.push_back({true, "segment", "Int32", 1, std::move(b)});
  }
  std::vector<std::pair<std::string, bool>> names;  // (name, is double), in order of first appearance
  std::map<std::pair<std::string, bool>, std::size_t> holders;
  for (const auto& s : segs) {
    const auto& q = s.quantities();
    for (std::size_t k = 0; k < q.size(); ++k) {
      const auto& m = q.meta(k);
      if (!m.on_cells || !(q.template typed<double>(k) || q.template typed<int>(k))) continue;
      std::pair<std::string, bool> key{m.name, q.template typed<double>(k) != nullptr};
      if (holders[key]++ == 0) names.push_back(key);
    }
  }
  std::size_t with_cells = 0;
  for (const auto& s : segs) with_cells += s.num_cells() > 0;
  for (const auto& key : names) {
    const bool is_double = key.second;
    auto fill = [&](const segment<D>* only) {
      std::string b;
      for (const auto& s : segs) {
        const auto& q = s.quantities();
        std::optional<std::size_t> slot;
        for (std::size_t k = 0; k < q.size(); ++k)
          if (q.meta(k).on_cells && q.meta(k).name == key.first && (is_double ? q.template typed<double>(k) != nullptr : q.template typed<int>(k) != nullptr))
            slot = k;
        const bool use = slot && (!only || only == &s);
        if (is_double) {
          static const std::vector<double> none;
          b += column_bytes(use ? *q.template typed<double>(*slot) : none, s.num_cells());
        } else {
          static const std::vector<int> none;
          b += column_bytes(use ? *q.template typed<int>(*slot) : none, s.num_cells());
        }
      }
      return b;
    };
    std::size_t present = 0;
    for (const auto& s : segs)
      if (s.num_cells() > 0 && (is_double ? s.quantities().template find<double, on_cells_t>(key.first).has_value()
                                           : s.quantities().template find<int, on_cells_t>(key.first).has_value()))
        ++present;
    const char* type = is_double ? "Float64" : "Int32";
    if (present == with_cells) {
      arrays.push_back({true, key.first, type, 1, fill(nullptr)});
    } else {
      for (const auto& s : segs)
        if (is_double ? s.quantities().template find<double, on_cells_t>(key.first).has_value()
                      : s.quantities().template find<int, on_cells_t>(key.first).has_value())
          arrays.push_back({true, s.name() + "/" + key.first, type, 1, fill(&s)});
    }
  }

  std::string points, conn, offsets, types;
  for (const auto& p : pts)
    for (std::size_t a = 0; a < 3; ++a) append(points, a < D ? p[a] : 0.0);
  std::int64_t off = 0;
  for (const auto& s : segs)
    for (const auto& c : s.cell_data()) {
      for (auto v : c) append(conn, static_cast<std::int64_t>(v));
      append(offsets, off += static_cast<std::int64_t>(D + 1));
      append(types, static_cast<std::uint8_t>(D == 3 ? 10 : 5));  // VTK_TETRA, VTK_TRIANGLE
    }

  // the companion: boundary, interface and marked faces
  const auto bfaces = boundary_faces(d, path);
  std::string fconn, foffsets, ftypes, fmarker, fseg, fother;
  off = 0;
  for (const auto& f : bfaces) {
    for (auto v : f.vertices) append(fconn, static_cast<std::int64_t>(v));
    append(foffsets, off += static_cast<std::int64_t>(D));
    append(ftypes, static_cast<std::uint8_t>(D == 3 ? 5 : 3));  // VTK_TRIANGLE, VTK_LINE
    append(fmarker, static_cast<std::int32_t>(f.marker));
    append(fseg, static_cast<std::int32_t>(f.segment));
    append(fother, static_cast<std::int32_t>(f.other));
  }
  const std::vector<data_array> farrays{{true, "marker", "Int32", 1, fmarker},
                                        {true, "segment", "Int32", 1, fseg},
                                        {true, "other_segment", "Int32", 1, fother}};

  atomic_file f(path), fb(boundary_vtu_path(path));
  write_grid(f.stream(), points, pts.size(), ncells, arrays, conn, offsets, types);
  write_grid(fb.stream(), points, pts.size(), bfaces.size(), farrays, fconn, foffsets, ftypes);
  f.commit();
  fb.commit();
}

std::string boundary_vtu_path(const std::string& path) {
  const std::string e = ".vtu";
  const bool has = path.size() >= e.size() && path.compare(path.size() - e.size(), e.size(), e) == 0;
  return (has ? path.substr(0, path.size() - e.size()) : path) + ".boundary.vtu";
}

template void write_vtu<2>(const domain<2>&, const std::string&);
template void write_vtu<3>(const domain<3>&, const std::string&);

}  // namespace gsse::io
