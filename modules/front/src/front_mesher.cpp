#include "gsse/front/front_mesher.hpp"

#include "gsse/front/gift_wrap.hpp"
#include "gsse/front/kernels.hpp"

namespace gsse::front {

point_grid<3> make_grid(std::span<const point3> pts) { return point_grid<3>(pts); }
point_grid<2> make_grid(std::span<const point2> pts) { return point_grid<2>(pts); }

namespace {
template <class K, class Face>
auto run(const K& k, const point_grid<K::grid_dim>& grid, const std::vector<Face>& boundary, const std::string& label,
         wrap_stats* stats, std::size_t max_cells) {
  gift_wrapper<K> w(k, grid);
  auto cells = w.run(boundary, label, max_cells);
  if (stats) *stats += w.stats();
  return cells;
}

}  // namespace

point_grid<2> make_grid(std::span<const point3> pts, int axis, std::span<const vertex_id> subset) {
  std::vector<std::array<double, 2>> c;
  c.reserve(subset.size());
  for (vertex_id v : subset) c.push_back(geometry::project(pts[v], axis));
  return point_grid<2>(c, subset);
}

std::vector<std::array<vertex_id, 4>> wrap(std::span<const point3> pts, const point_grid<3>& grid,
                                           const std::vector<std::array<vertex_id, 3>>& boundary,
                                           const std::string& label, wrap_stats* stats, std::size_t max_cells) {
  return run(volume_kernel{pts}, grid, boundary, label, stats, max_cells);
}
std::vector<std::array<vertex_id, 3>> wrap(std::span<const point2> pts, const point_grid<2>& grid,
                                           const std::vector<std::array<vertex_id, 2>>& boundary,
                                           const std::string& label, wrap_stats* stats, std::size_t max_cells) {
  return run(plane_kernel{pts}, grid, boundary, label, stats, max_cells);
}
std::vector<std::array<vertex_id, 3>> wrap_facet(std::span<const point3> pts, int axis, const point_grid<2>& grid,
                                                 const std::vector<std::array<vertex_id, 2>>& boundary,
                                                 const std::string& label, wrap_stats* stats, std::size_t max_cells) {
  return run(facet_kernel{pts, axis}, grid, boundary, label, stats, max_cells);
}

}  // namespace gsse::front
