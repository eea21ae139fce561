#include "gsse/io/node_ele.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <exception>
#include <memory>
#include <thread>
#include <unordered_map>

#include "facets.hpp"
#include "gsse/io/atomic_file.hpp"
#include "gsse/io/poly.hpp"
#include "gsse/io/sidecar.hpp"
#include "gsse/io/text_reader.hpp"
#include "node_block.hpp"
#include "number_format.hpp"
#include "parallel_text.hpp"

namespace gsse::io {
namespace {

std::string strip_mesh_extension(const std::string& path) {
  const auto e = std::filesystem::path(path).extension().string();
  if (e == ".node" || e == ".ele" || e == ".face" || e == ".edge" || e == ".json") return base_of(path);
  return path;
}


// .face/.edge files are optional; when present they must refer to existing points. Returns the
// faces with a nonzero marker below `base` (0: any nonzero marker): the input facets' markers
// (write_node_ele writes interface codes first * base + second above them).
template <std::size_t D>
std::vector<typename domain<D>::marked_face> read_facet_file(const std::string& file, long ibase, std::size_t npoints, int base) {
  std::vector<typename domain<D>::marked_face> r;
  if (!std::filesystem::exists(file)) return r;
  text_reader t(file);
  t.require_line(D == 3 ? "face count line '<#faces> <#markers>'" : "edge count line '<#edges> <#markers>'");
  const long n = t.integer_in(D == 3 ? "number of faces" : "number of edges", 0, 1'000'000'000);
  const long markers = t.optional_integer("number of boundary markers", 0);
  if (markers < 0 || markers > 1) t.fail("invalid marker count " + std::to_string(markers));
  for (long i = 0; i < n; ++i) {
    t.require_line((D == 3 ? "face " : "edge ") + std::to_string(i + 1) + " of " + std::to_string(n));
    (void)t.integer(D == 3 ? "face number" : "edge number");
    std::array<vertex_id, D> f;
    for (auto& v : f) v = detail::vertex_ref(t, ibase, npoints, "corner");
    const long m = markers ? t.optional_integer("boundary marker", 0) : 0;
    if (m != 0 && (base == 0 || std::labs(m) < base)) r.push_back({f, static_cast<int>(m)});
  }
  return r;
}

}  // namespace

template <std::size_t D>
domain<D> read_node_ele(const std::string& path) {
  const std::string base = strip_mesh_extension(path);
  const char* cell_word = D == 3 ? "tetrahedron" : "triangle";
  domain<D> d;
  long ibase = 0;
  {
    text_reader r(base + ".node");
    r.require_line("point count line '<#points> <dimension> <#attributes> <#markers>'");
    const long n = r.integer_in("number of points", 0, 1'000'000'000);
    const long dim = r.integer("dimension");
    if (dim != static_cast<long>(D))
      r.fail("dimension " + std::to_string(dim) + " where " + std::to_string(D) + " was expected");
    const long attributes = r.optional_integer("number of attributes", 0);
    const long markers = r.optional_integer("number of boundary markers", 0);
    if (attributes < 0 || attributes > 1000 || markers < 0 || markers > 1) r.fail("invalid attribute or marker count");
    std::vector<int> pm;
    std::vector<std::size_t> lines;
    ibase = detail::read_node_block<D>(r, n, attributes, markers, d.mutable_points(), pm, lines);
    check_points<D>(r.name(), d.points(), lines);
  }
  const std::size_t np = d.points().size();
  const segment_table names = read_sidecar(base + ".json");
  {
    text_reader r(base + ".ele");
    r.require_line(std::string("element count line '<#elements> <nodes per ") + cell_word + "> <#attributes>'");
    const long n = r.integer_in("number of elements", 0, 1'000'000'000);
    const long per = r.integer("nodes per element");
    if (per != static_cast<long>(D + 1))
      r.fail("only linear elements are supported: " + std::to_string(per) + " nodes per " + cell_word + ", expected " +
             std::to_string(D + 1));
    const long attributes = r.optional_integer("number of attributes", 0);
    if (attributes < 0 || attributes > 1000) r.fail("invalid number of attributes " + std::to_string(attributes));
    std::unordered_map<long, segment<D>*> seg_of;
    std::unordered_map<std::array<vertex_id, D + 1>, long, detail::key_hash> seen;  // sorted corners -> element
    for (long i = 0; i < n; ++i) {
      r.require_line(std::string(cell_word) + " " + std::to_string(i + 1) + " of " + std::to_string(n));
      (void)r.integer("element number");
      std::array<vertex_id, D + 1> c;
      for (auto& v : c) v = detail::vertex_ref(r, ibase, np, "corner");
      auto s = c;
      std::sort(s.begin(), s.end());
      if (std::adjacent_find(s.begin(), s.end()) != s.end()) r.fail(std::string(cell_word) + " repeats a vertex");
      if (auto [it, fresh] = seen.try_emplace(s, i + 1); !fresh)
        r.fail(std::string(cell_word) + " " + std::to_string(i + 1) + " repeats " + cell_word + " " + std::to_string(it->second));
      long number = 1;
      if (attributes > 0) {
        const double a = r.real("region attribute");
        if (a != std::floor(a) || std::fabs(a) > 1e9) r.fail("region attribute must be an integer, got " + std::to_string(a));
        number = static_cast<long>(a);
        for (long k = 1; k < attributes; ++k) (void)r.real("element attribute");
      }
      auto [it, fresh] = seg_of.try_emplace(number, nullptr);
      if (fresh) {
        std::string name = names.name_of(static_cast<int>(number));
        if (name.empty()) name = "region_" + std::to_string(number);
        if (d.find(name)) r.fail("segment name '" + name + "' given to two region attributes");
        it->second = &d.add_segment(name, static_cast<int>(number));
      }
      it->second->add_cell(c);
    }
  }
  d.marked_faces() = read_facet_file<D>(base + (D == 3 ? ".face" : ".edge"), ibase, np, names.face_marker_base);
  d.marker_names() = names.facet_names;
  detail::finalize_all(d, base + ".ele");
  d.sync_slots();
  return d;
}
template domain<2> read_node_ele<2>(const std::string&);
template domain<3> read_node_ele<3>(const std::string&);

template <std::size_t D>
void write_node_ele(const domain<D>& d, const std::string& path, unsigned threads) {
  const std::string base = strip_mesh_extension(path);
  const auto& pts = d.points();
  detail::check_domain(d, base + ".ele");
  const auto faces = detail::outer_facets(d, base + (D == 3 ? ".face" : ".edge"), threads);
  const auto marks = detail::mark_facets(d, faces, threads);
  const auto& inner = marks.inner;
  // the interface code first * m + second lies above every segment number and every marker
  int largest = 0;
  for (const auto& s : d.segments()) largest = std::max(largest, std::abs(s.number()));
  for (const auto& f : d.marked_faces()) largest = std::max(largest, std::abs(f.marker));
  int m = 100;
  while (m <= largest) m *= 10;

  atomic_file node(base + ".node"), ele(base + ".ele"), face(base + (D == 3 ? ".face" : ".edge"));
  {
    auto& o = node.stream();
    o << "# written by gsse::io\n" << pts.size() << ' ' << D << " 0 0\n";
    detail::write_lines(o, pts.size(), threads, [&](std::size_t i, std::string& line) {
      detail::append_int(line, static_cast<long long>(i + 1));
      for (double x : pts[i]) detail::append_real(line += ' ', x);
      line += '\n';
    });
  }
  {
    auto& o = ele.stream();
    // one run over the elements of all segments (segment after segment): the small segments are
    // formatted alongside the large ones instead of one after another
    std::vector<std::size_t> first{0};  // first element id of each segment, then the total
    for (const auto& s : d.segments()) first.push_back(first.back() + s.num_cells());
    const std::size_t n = first.back();
    o << "# written by gsse::io; attribute = segment number\n" << n << ' ' << D + 1 << " 1\n";
    detail::write_lines(o, n, threads, [&](std::size_t i, std::string& line) {
      const auto k = static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), i) - first.begin()) - 1;
      const auto& s = d.segments()[k];
      detail::append_int(line, static_cast<long long>(i + 1));
      for (auto v : s.cell(static_cast<cell_id>(i - first[k]))) detail::append_int(line += ' ', static_cast<long long>(v) + 1);
      detail::append_int(line += ' ', s.number());
      line += '\n';
    });
  }
  {
    auto& o = face.stream();
    o << "# written by gsse::io; boundary and interface faces oriented into the first segment, then marked faces inside "
         "a segment; marker = the input facet's marker, or where it has none first*" << m << " + second (0: outside)\n"
      << faces.size() + inner.size() << " 1\n";
    detail::write_lines(o, faces.size() + inner.size(), threads, [&](std::size_t i, std::string& line) {
      detail::append_int(line, static_cast<long long>(i + 1));
      if (i >= faces.size()) {
        const auto& [f, mk] = inner[i - faces.size()];
        for (auto v : f) detail::append_int(line += ' ', static_cast<long long>(v) + 1);
        detail::append_int(line += ' ', mk);
        line += '\n';
        return;
      }
      const auto& f = faces[i];
      for (auto v : f.vertices) detail::append_int(line += ' ', static_cast<long long>(v) + 1);
      const int a = d.segments()[f.first].number();
      const int b = f.second < 0 ? 0 : d.segments()[static_cast<std::size_t>(f.second)].number();
      const int mk = marks.outer[i];
      detail::append_int(line += ' ', mk != 0 ? static_cast<long long>(mk) : static_cast<long long>(a) * m + b);
      line += '\n';
    });
  }
  segment_table t;
  for (const auto& s : d.segments()) {
    t.names.push_back(s.name());
    t.numbers.push_back(s.number());
  }
  t.face_marker_base = m;
  t.facet_names = d.marker_names();
  // each commit removes the file it replaces (freeing its blocks, a few ms for the .ele of 6e5
  // tetrahedra): with threads, the three overlap (the library's one pool, for_each)
  const std::array<atomic_file*, 3> files{&node, &ele, &face};
  for_each(execution::par(threads), files, [](atomic_file* f) { f->commit(); });
  write_sidecar(base + ".json", t);
}
template void write_node_ele<2>(const domain<2>&, const std::string&, unsigned);
template void write_node_ele<3>(const domain<3>&, const std::string&, unsigned);

}  // namespace gsse::io
