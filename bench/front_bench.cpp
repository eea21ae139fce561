// Front mesher throughput against CGAL's Delaunay_triangulation_3 on the same points.
// usage: front_bench N [gsse|gsse2|cgal|both]   (one method per process for a clean peak-memory figure;
// `both` also compares the two tetrahedrizations, cell for cell: "identical": true or false)
// gsse: one thread; gsse2: two threads, the cube halved by a DeWall wall (x = 0.5) whose two
// sides are meshed concurrently, as the pipeline splits large segments.
// Points: 8 cube corners + N uniform points in the unit cube (seed 1). Prints one JSON line.
#include <sys/resource.h>

#include <CGAL/Delaunay_triangulation_3.h>

#include <algorithm>
#include <map>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <thread>

#include "gsse/front/front_mesher.hpp"
#include "gsse/front/gift_wrap.hpp"
#include "gsse/geometry/predicates.hpp"

using namespace gsse;

namespace {
double peak_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: front_bench N [gsse|cgal|both]\n");
    return 2;
  }
  const std::size_t n = std::stoul(argv[1]);
  const std::string which = argc > 2 ? argv[2] : "both";
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<point3> p;
  for (int i = 0; i < 8; ++i) p.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  for (std::size_t i = 0; i < n; ++i) p.push_back({u(rng), u(rng), u(rng)});
  const double base_mb = peak_mb();
  std::vector<std::array<vertex_id, 4>> cells;  // GSSE's, kept for the comparison of `both`
  std::printf("{\"points\": %zu", p.size());
  if (which == "gsse" || which == "gsse2" || which == "both") {
    // the cube's boundary: each face split along its perturbed-Delaunay diagonal
    std::vector<std::array<vertex_id, 3>> boundary;
    const point3 centre{0.5, 0.5, 0.5};
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        auto at = [&](int a, int b) {
          int c[3];
          c[axis] = side;
          c[(axis + 1) % 3] = a;
          c[(axis + 2) % 3] = b;
          return vertex_id(c[0] + 2 * c[1] + 4 * c[2]);
        };
        const vertex_id q[4] = {at(0, 0), at(1, 0), at(1, 1), at(0, 1)};
        const bool d02 = geometry::in_coplanar_circle_perturbed(p[q[0]], p[q[1]], p[q[2]], p[q[3]], axis) < 0;
        const std::array<std::array<vertex_id, 3>, 2> t =
            d02 ? std::array<std::array<vertex_id, 3>, 2>{{{q[0], q[1], q[2]}, {q[0], q[2], q[3]}}}
                : std::array<std::array<vertex_id, 3>, 2>{{{q[0], q[1], q[3]}, {q[1], q[2], q[3]}}};
        for (auto f : t) {
          if (geometry::orient3d(p[f[0]], p[f[1]], p[f[2]], centre) < 0) std::swap(f[0], f[1]);
          boundary.push_back(f);
        }
      }
    const auto t0 = std::chrono::steady_clock::now();
    const auto grid = front::make_grid(p);
    front::wrap_stats st;
    if (which == "gsse2") {
      std::array<std::vector<std::array<vertex_id, 3>>, 2> sides;
      cells = front::wrap_wall(p, grid, boundary, "cube", 0, 0.5, sides);
      std::array<std::vector<std::array<vertex_id, 4>>, 2> half;
      {
        std::jthread other([&] { half[1] = front::wrap(p, grid, sides[1], "cube side 1"); });
        half[0] = front::wrap(p, grid, sides[0], "cube side 0");
      }
      for (const auto& h : half) cells.insert(cells.end(), h.begin(), h.end());
    } else {
      cells = front::wrap(p, grid, boundary, "cube", &st);
    }
    const double s = seconds_since(t0);
    std::printf(", \"%s\": {\"tets\": %zu, \"seconds\": %.3f, \"tets_per_s\": %.0f, \"peak_mb\": %.1f, "
                "\"bytes_per_tet\": %.0f, \"insphere_per_tet\": %.1f, \"orient_per_tet\": %.1f, "
                "\"visits_per_tet\": %.1f, \"max_front\": %zu}",
                which == "gsse2" ? "gsse2" : "gsse", cells.size(), s, static_cast<double>(cells.size()) / s, peak_mb(),
                (peak_mb() - base_mb) * 1048576.0 / static_cast<double>(cells.size()),
                static_cast<double>(st.candidate_tests) / static_cast<double>(cells.size()),
                static_cast<double>(st.side_tests) / static_cast<double>(cells.size()), static_cast<double>(st.visits) / static_cast<double>(cells.size()), st.max_front);
  }
  if (which == "cgal" || which == "both") {
    using K = geometry::kernel;
    std::vector<K::Point_3> cp;
    for (const auto& q : p) cp.push_back({q[0], q[1], q[2]});
    const auto t0 = std::chrono::steady_clock::now();
    CGAL::Delaunay_triangulation_3<K> dt(cp.begin(), cp.end());
    const double s = seconds_since(t0);
    std::printf(", \"cgal\": {\"tets\": %zu, \"seconds\": %.3f, \"tets_per_s\": %.0f, \"peak_mb\": %.1f}",
                static_cast<std::size_t>(dt.number_of_finite_cells()), s,
                static_cast<double>(dt.number_of_finite_cells()) / s, peak_mb());
    if (which == "both") {  // cell for cell, vertices mapped back by their (distinct) coordinates
      std::map<std::array<double, 3>, vertex_id> id;
      for (std::size_t i = 0; i < p.size(); ++i) id[p[i]] = static_cast<vertex_id>(i);
      std::vector<std::array<vertex_id, 4>> theirs, ours = cells;
      for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
        std::array<vertex_id, 4> t;
        for (int k = 0; k < 4; ++k) {
          const auto& q = c->vertex(k)->point();
          t[static_cast<std::size_t>(k)] = id.at({q.x(), q.y(), q.z()});
        }
        theirs.push_back(t);
      }
      for (auto* v : {&ours, &theirs}) {
        for (auto& t : *v) std::sort(t.begin(), t.end());
        std::sort(v->begin(), v->end());
      }
      std::printf(", \"identical\": %s", ours == theirs ? "true" : "false");
    }
  }
  std::printf("}\n");
  return 0;
}
