// Python module `gsse` (pybind11): mesh a file or numpy arrays with the CLI's options as keywords,
// get numpy arrays and a meshio.Mesh back, write any output format. See python/README.md.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "gsse/io/boundary.hpp"
#include "gsse/io/gmsh.hpp"
#include "gsse/io/node_ele.hpp"
#include "gsse/io/poly.hpp"
#include "gsse/io/vtu.hpp"
#include "gsse/pipeline/pipeline.hpp"
#include "gsse/plc/region_points.hpp"

namespace py = pybind11;

namespace {

/// The CLI's options, as keywords.
struct mesh_options {
  double size = 0;
  unsigned threads = 1;
  bool verify = false;
  std::size_t max_steiner = gsse::conformer::options{}.max_steiner;
  std::string fill = "lattice";
  bool merge = true;
  bool gabriel = false;
};

gsse::pipeline::options pipeline_options(const mesh_options& m) {
  if (m.threads < 1 || m.threads > 4096) throw py::value_error("threads must be from 1 to 4096");
  if (m.size < 0) throw py::value_error("size must not be negative");
  if (m.fill != "lattice" && m.fill != "rules") throw py::value_error("fill must be 'lattice' or 'rules'");
  if (m.fill == "rules" && !(m.size > 0)) throw py::value_error("fill='rules' needs a size");
  gsse::pipeline::options o;
  o.size = m.size;
  o.threads = m.threads;
  o.verify = m.verify;
  o.conform.max_steiner = m.max_steiner;
  o.conform.merge_coplanar = m.merge;
  o.gabriel = m.gabriel;
  o.interior = m.fill == "rules" ? gsse::pipeline::fill::rules : gsse::pipeline::fill::lattice;
  return o;
}

/// A mesh: the library's domain, with the figures of the run that made it.
class mesh_result {
 public:
  std::variant<gsse::domain<2>, gsse::domain<3>> d;
  std::size_t steiner = 0, volume_points = 0, dropped_points = 0;
  std::map<std::string, double> times;

  int dimension() const { return d.index() == 0 ? 2 : 3; }

  py::array_t<double> points() const {
    return std::visit([](const auto& m) {
      constexpr std::size_t D = std::decay_t<decltype(m)>::dimension;
      py::array_t<double> a({m.points().size(), D});
      auto r = a.mutable_unchecked<2>();
      for (std::size_t i = 0; i < m.points().size(); ++i)
        for (std::size_t k = 0; k < D; ++k) r(i, k) = m.points()[i][k];
      return a;
    }, d);
  }
  py::array_t<std::int64_t> cells() const {
    return std::visit([](const auto& m) {
      constexpr std::size_t D = std::decay_t<decltype(m)>::dimension;
      std::size_t n = 0;
      for (const auto& s : m.segments()) n += s.num_cells();
      py::array_t<std::int64_t> a({n, D + 1});
      auto r = a.mutable_unchecked<2>();
      std::size_t i = 0;
      for (const auto& s : m.segments())
        for (const auto& c : s.cell_data()) {
          for (std::size_t k = 0; k <= D; ++k) r(i, k) = c[k];
          ++i;
        }
      return a;
    }, d);
  }
  py::array_t<std::int32_t> cell_segments() const {
    return std::visit([](const auto& m) {
      std::vector<std::int32_t> v;
      for (const auto& s : m.segments()) v.insert(v.end(), s.num_cells(), s.number());
      return py::array_t<std::int32_t>(v.size(), v.data());
    }, d);
  }
  std::vector<std::pair<int, std::string>> segments() const {
    return std::visit([](const auto& m) {
      std::vector<std::pair<int, std::string>> v;
      for (const auto& s : m.segments()) v.push_back({s.number(), s.name()});
      return v;
    }, d);
  }
  /// Boundary and interface faces once (oriented into the segment listed first, of lower number at
  /// an interface), then marked faces inside a segment: (faces, markers, segment pairs), as
  /// gsse::io::boundary_faces gives them (and BASE.boundary.vtu holds them).
  py::tuple faces() const {
    return std::visit([](const auto& m) {
      constexpr std::size_t D = std::decay_t<decltype(m)>::dimension;
      const auto bf = gsse::io::boundary_faces(m);
      py::array_t<std::int64_t> fa({bf.size(), D});
      py::array_t<std::int32_t> ma(bf.size()), sa({bf.size(), std::size_t{2}});
      auto F = fa.template mutable_unchecked<2>();
      auto M = ma.template mutable_unchecked<1>();
      auto S = sa.template mutable_unchecked<2>();
      for (std::size_t i = 0; i < bf.size(); ++i) {
        for (std::size_t k = 0; k < D; ++k) F(i, k) = bf[i].vertices[k];
        M(i) = bf[i].marker;
        S(i, 0) = bf[i].segment;
        S(i, 1) = bf[i].other;
      }
      return py::make_tuple(fa, ma, sa);
    }, d);
  }
  std::map<int, std::string> marker_names() const {
    return std::visit([](const auto& m) { return m.marker_names(); }, d);
  }
  void write(const std::string& path, const std::string& msh, unsigned threads) const {
    std::visit([&](const auto& m) {
      auto ends = [&](const std::string& e) { return path.size() >= e.size() && path.compare(path.size() - e.size(), e.size(), e) == 0; };
      if (ends(".vtu")) {
        gsse::io::write_vtu(m, path);
      } else if (ends(".msh")) {
        if (msh != "4.1" && msh != "2.2") throw py::value_error("msh must be '4.1' or '2.2'");
        gsse::io::write_msh(m, path, false, msh == "2.2" ? gsse::io::msh_version::v22 : gsse::io::msh_version::v41);
      } else if (ends(".node")) {
        gsse::io::write_node_ele(m, path.substr(0, path.size() - 5), threads);
      } else {
        throw py::value_error(path + ": unknown output format (use .vtu, .msh or .node)");
      }
    }, d);
  }
};

template <std::size_t D>
mesh_result run(const gsse::plc<D>& p, const std::vector<gsse::point<D>>& cloud, const mesh_options& m) {
  const auto o = pipeline_options(m);
  mesh_result r;
  gsse::pipeline::report rep;
  {
    py::gil_scoped_release unlocked;  // other Python threads run while the mesh is made
    r.d = gsse::pipeline::mesh(p, cloud, o, rep);
  }
  if (!rep.problems.empty()) {
    std::string all = "the library verifier rejected the mesh:";
    for (const auto& s : rep.problems) all += "\n  " + s;
    throw std::runtime_error(all);
  }
  r.steiner = rep.steiner;
  r.volume_points = rep.volume_points;
  r.dropped_points = rep.dropped_points;
  for (const auto& t : rep.times) r.times[t.stage] = t.seconds;
  return r;
}

mesh_result mesh_file(const std::string& path, const mesh_options& m, std::optional<py::array_t<double>> cloud) {
  std::vector<gsse::io::plc_volume> volumes;
  auto input = gsse::io::read_plc(path, &volumes);
  if (!volumes.empty()) {  // a Gmsh model: its volumes get region points, as gsse-mesh does
    auto& p3 = std::get<gsse::plc<3>>(input);
    gsse::plc_tools::drop_stray_facets(p3, volumes, m.threads);
    gsse::plc_tools::add_region_points(p3, volumes, m.threads);
  }
  return std::visit([&](const auto& p) {
    constexpr std::size_t D = std::decay_t<decltype(p)>::dimension;
    std::vector<gsse::point<D>> c;
    if (cloud) {
      const auto a = cloud->unchecked<2>();
      if (a.shape(1) != static_cast<py::ssize_t>(D)) throw py::value_error("cloud must have one column per dimension");
      for (py::ssize_t i = 0; i < a.shape(0); ++i) {
        gsse::point<D> q;
        for (std::size_t k = 0; k < D; ++k) q[k] = a(i, static_cast<py::ssize_t>(k));
        c.push_back(q);
      }
    }
    return run(p, c, m);
  }, input);
}

/// A PLC from arrays: points (n x 2 or n x 3); facets: 3D a list of polygons (each a list of
/// point indices, from 0) or a (k x 3) array of triangles, 2D a (k x 2) array of segments;
/// markers per facet; regions as (x, y[, z], number[, name]); holes as points.
template <std::size_t D>
gsse::plc<D> plc_from(py::array_t<double> points, py::object facets, std::optional<std::vector<int>> markers,
                      std::optional<std::vector<py::tuple>> regions, std::optional<py::array_t<double>> holes,
                      std::optional<std::map<int, std::string>> names) {
  gsse::plc<D> p;
  p.source = "<arrays>";
  const auto P = points.unchecked<2>();
  for (py::ssize_t i = 0; i < P.shape(0); ++i) {
    gsse::point<D> q;
    for (std::size_t k = 0; k < D; ++k) q[k] = P(i, static_cast<py::ssize_t>(k));
    p.points.push_back(q);
  }
  p.point_markers.assign(p.points.size(), 0);
  auto index = [&](py::handle h) {
    const long v = py::cast<long>(h);
    if (v < 0 || static_cast<std::size_t>(v) >= p.points.size())
      throw py::value_error("facet refers to point " + std::to_string(v) + " of " + std::to_string(p.points.size()));
    return static_cast<gsse::vertex_id>(v);
  };
  std::size_t k = 0;
  for (py::handle f : facets) {
    std::vector<gsse::vertex_id> poly;
    for (py::handle v : f) poly.push_back(index(v));
    const int mk = markers ? (k < markers->size() ? (*markers)[k] : throw py::value_error("fewer markers than facets")) : 0;
    if constexpr (D == 3) {
      if (poly.size() < 3) throw py::value_error("facet " + std::to_string(k) + " has fewer than 3 points");
      gsse::plc_facet pf;
      pf.polygons.push_back(std::move(poly));
      pf.marker = mk;
      pf.line = k + 1;
      p.facets.push_back(std::move(pf));
    } else {
      if (poly.size() != 2) throw py::value_error("segment " + std::to_string(k) + " must have 2 points");
      p.edges.push_back({poly[0], poly[1]});
      p.edge_markers.push_back(mk);
    }
    ++k;
  }
  if (markers && markers->size() != k) throw py::value_error("more markers than facets");
  if (regions)
    for (const auto& t : *regions) {
      if (t.size() < D + 1) throw py::value_error("a region is (x, y[, z], number[, name])");
      gsse::plc_region<D> g;
      for (std::size_t a = 0; a < D; ++a) g.at[a] = py::cast<double>(t[a]);
      g.number = py::cast<int>(t[D]);
      g.name = t.size() > D + 1 ? py::cast<std::string>(t[D + 1]) : "region_" + std::to_string(g.number);
      p.regions.push_back(g);
    }
  if (holes) {
    const auto H = holes->unchecked<2>();
    for (py::ssize_t i = 0; i < H.shape(0); ++i) {
      gsse::point<D> q;
      for (std::size_t a = 0; a < D; ++a) q[a] = H(i, static_cast<py::ssize_t>(a));
      p.holes.push_back(q);
    }
  }
  if (names) p.marker_names = *names;
  return p;
}

mesh_result mesh_arrays(py::array_t<double, py::array::c_style | py::array::forcecast> points, py::object facets,
                        std::optional<std::vector<int>> markers, std::optional<std::vector<py::tuple>> regions,
                        std::optional<py::array_t<double>> holes, std::optional<std::map<int, std::string>> names,
                        const mesh_options& m) {
  if (points.ndim() != 2 || (points.shape(1) != 2 && points.shape(1) != 3))
    throw py::value_error("points must be an (n, 2) or (n, 3) array");
  if (points.shape(1) == 2) return run(plc_from<2>(points, facets, markers, regions, holes, names), {}, m);
  return run(plc_from<3>(points, facets, markers, regions, holes, names), {}, m);
}

}  // namespace

PYBIND11_MODULE(gsse, mod) {
  mod.doc() = "GSSE: conforming Delaunay meshes of multi-segment structures (TCAD). See python/README.md.";
  py::class_<mesh_result>(mod, "Mesh", "A conforming Delaunay mesh: points, cells per segment, boundary faces with markers.")
      .def_property_readonly("dimension", &mesh_result::dimension)
      .def_property_readonly("points", &mesh_result::points, "(n, D) float64")
      .def_property_readonly("cells", &mesh_result::cells, "(m, D+1) int64 vertex ids, segment after segment")
      .def_property_readonly("cell_segments", &mesh_result::cell_segments, "(m,) int32 segment number per cell")
      .def_property_readonly("segments", &mesh_result::segments, "[(number, name)] in the cells' order")
      .def_property_readonly("faces", &mesh_result::faces,
                             "(faces (k, D) int64, markers (k,) int32, segments (k, 2) int32): boundary and interface "
                             "faces once, then marked faces inside a segment; marker 0 = none, segment 0 = outside")
      .def_property_readonly("marker_names", &mesh_result::marker_names)
      .def_readonly("steiner", &mesh_result::steiner, "boundary Steiner points")
      .def_readonly("volume_points", &mesh_result::volume_points)
      .def_readonly("dropped_points", &mesh_result::dropped_points)
      .def_readonly("times", &mesh_result::times, "seconds per stage")
      .def("write", &mesh_result::write, py::arg("path"), py::arg("msh") = "4.1", py::arg("threads") = 1,
           "writes .vtu (+ .boundary.vtu), .msh (msh='4.1' or '2.2') or .node (+ .ele, .face/.edge, .json)")
      .def("to_meshio", [](const mesh_result& r) {
        const py::module_ meshio = py::module_::import("meshio");
        const int D = r.dimension();
        const py::tuple f = r.faces();
        const auto sides = py::cast<py::array_t<std::int32_t>>(f[2]).unchecked<2>();
        py::array_t<std::int32_t> first(sides.shape(0)), none(py::len(r.cell_segments()));
        for (py::ssize_t i = 0; i < sides.shape(0); ++i) first.mutable_at(i) = sides(i, 0);
        std::fill(none.mutable_data(), none.mutable_data() + none.size(), 0);
        py::list cells;
        cells.append(py::make_tuple(D == 3 ? "tetra" : "triangle", r.cells()));
        cells.append(py::make_tuple(D == 3 ? "triangle" : "line", f[0]));
        py::dict data;
        py::list segment, marker;
        segment.append(r.cell_segments());
        segment.append(first);
        marker.append(none);
        marker.append(f[1]);
        data["segment"] = segment;
        data["marker"] = marker;
        return meshio.attr("Mesh")(r.points(), cells, py::arg("cell_data") = data);
      }, "a meshio.Mesh: the cells, then the faces; cell data 'segment' (for a face: the segment it is oriented "
         "into) and 'marker' (0 on cells)");
  mod.def("mesh_file", [](const std::string& path, double size, unsigned threads, bool verify, std::size_t max_steiner,
                          const std::string& fill, bool merge, bool gabriel, std::optional<py::array_t<double>> cloud) {
    return mesh_file(path, {size, threads, verify, max_steiner, fill, merge, gabriel}, cloud);
  }, py::arg("path"), py::kw_only(), py::arg("size") = 0.0, py::arg("threads") = 1u, py::arg("verify") = false,
     py::arg("max_steiner") = gsse::conformer::options{}.max_steiner, py::arg("fill") = "lattice", py::arg("merge") = true,
     py::arg("gabriel") = false, py::arg("cloud") = py::none(),
     "Meshes a .poly, .smesh, .off, .stl or Gmsh surface .msh with gsse-mesh's options; raises on bad input "
     "(message names the file and line) and when verify=True finds a problem.");
  mod.def("mesh", [](py::array_t<double, py::array::c_style | py::array::forcecast> points, py::object facets,
                     std::optional<std::vector<int>> markers, std::optional<std::vector<py::tuple>> regions,
                     std::optional<py::array_t<double>> holes, std::optional<std::map<int, std::string>> names, double size,
                     unsigned threads, bool verify, std::size_t max_steiner, const std::string& fill, bool merge, bool gabriel) {
    return mesh_arrays(points, facets, markers, regions, holes, names, {size, threads, verify, max_steiner, fill, merge, gabriel});
  }, py::arg("points"), py::arg("facets"), py::kw_only(), py::arg("markers") = py::none(), py::arg("regions") = py::none(),
     py::arg("holes") = py::none(), py::arg("marker_names") = py::none(), py::arg("size") = 0.0, py::arg("threads") = 1u,
     py::arg("verify") = false, py::arg("max_steiner") = gsse::conformer::options{}.max_steiner, py::arg("fill") = "lattice",
     py::arg("merge") = true, py::arg("gabriel") = false,
     "Meshes a PLC given as arrays: points (n, 2|3); facets: 3D polygons (lists of point indices from 0) or a (k, 3) "
     "array, 2D a (k, 2) array of segments; markers per facet; regions [(x, y[, z], number[, name])]; holes (h, D).");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
}
