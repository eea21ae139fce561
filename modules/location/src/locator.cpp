#include "gsse/location/locator.hpp"

#include <algorithm>

#include "gsse/geometry/predicates.hpp"

namespace gsse::location {

namespace {
/// No facet of c has q on its outer side (Strict: nor on its plane). Each reference facet (2D: the
/// edges in turn) faces into the positively oriented cell.
template <bool Strict, std::size_t D>
bool on_inner_sides(const std::vector<point<D>>& p, const cell_t<D>& c, const point<D>& q) {
  auto inner = [](int o) { return Strict ? o > 0 : o >= 0; };
  if constexpr (D == 2) {
    return inner(geometry::orient2d(p[c[0]], p[c[1]], q)) && inner(geometry::orient2d(p[c[1]], p[c[2]], q)) &&
           inner(geometry::orient2d(p[c[2]], p[c[0]], q));
  } else {
    for (const auto& f : reference_simplex<3>::facet_vertices)
      if (!inner(geometry::orient3d(p[c[static_cast<std::size_t>(f[0])]], p[c[static_cast<std::size_t>(f[1])]],
                                    p[c[static_cast<std::size_t>(f[2])]], q)))
        return false;
    return true;
  }
}
}  // namespace

template <std::size_t D>
bool inside_cell(const std::vector<point<D>>& p, const cell_t<D>& c, const point<D>& q) {
  return on_inner_sides<false, D>(p, c, q);
}

template <std::size_t D>
bool strictly_inside_cell(const std::vector<point<D>>& p, const cell_t<D>& c, const point<D>& q) {
  return on_inner_sides<true, D>(p, c, q);
}

template <std::size_t D>
locator<D>::locator(std::vector<point<D>> points, const std::vector<std::vector<cell_t<D>>>& cells_by_region)
    : p_(std::move(points)) {
  for (std::size_t r = 0; r < cells_by_region.size(); ++r) {
    cells_.insert(cells_.end(), cells_by_region[r].begin(), cells_by_region[r].end());
    region_.insert(region_.end(), cells_by_region[r].size(), static_cast<int>(r));
  }
  if (!p_.empty()) lo_ = hi_ = p_[0];
  for (const auto& q : p_)
    for (std::size_t k = 0; k < D; ++k) lo_[k] = std::min(lo_[k], q[k]), hi_[k] = std::max(hi_[k], q[k]);
  // a hierarchy of the cells' boxes: a query tests the cells whose boxes hold the point. (A
  // uniform grid of buckets, filed by box, made occ_hammer's points each test about 10,000 of
  // its 45,563 long, slanted coarse tetrahedra, 300 of whose boxes held the point.)
  std::vector<sizing::aabb<D>> boxes(cells_.size());
  for (std::size_t c = 0; c < cells_.size(); ++c) {
    boxes[c] = sizing::aabb<D>::empty();
    for (auto v : cells_[c]) boxes[c].add(p_[v]);
  }
  tree_ = sizing::box_tree<D>(std::move(boxes), std::vector<double>(cells_.size(), 0.0));
  flat_.assign(cells_.size(), 0);
  for (std::size_t c = 0; c < cells_.size(); ++c) {
    const auto& t = cells_[c];
    if constexpr (D == 2)
      flat_[c] = geometry::orient2d(p_[t[0]], p_[t[1]], p_[t[2]]) == 0;
    else
      flat_[c] = geometry::orient3d(p_[t[0]], p_[t[1]], p_[t[2]], p_[t[3]]) == 0;
  }
}

template <std::size_t D>
std::uint32_t locator<D>::cell_holding(const point<D>& q) const {
  std::uint32_t found = no_cell;
  tree_.visit([&](const sizing::aabb<D>& x) { return x.contains(q); }, [&](std::uint32_t c) {
    if (c < found && !flat_[c] && inside_cell<D>(p_, cells_[c], q)) found = c;
    return true;
  });
  return found;
}

template <std::size_t D>
int locator<D>::region_of(const point<D>& q) const {
  const std::uint32_t c = cell_holding(q);
  return c == no_cell ? -1 : region_[c];
}

// q strictly inside the hinted cell: no other cell holds it, so the answer is the one without the
// hint (a point on a face between cells of two regions is looked up in full). Points asked in a
// row, as the size field's placement asks them, mostly share a cell.
template <std::size_t D>
int locator<D>::region_of(const point<D>& q, std::uint32_t& hint) const {
  if (hint < cells_.size() && strictly_inside_cell<D>(p_, cells_[hint], q)) return region_[hint];
  const std::uint32_t c = cell_holding(q);
  if (c == no_cell) return -1;
  hint = c;
  return region_[c];
}

// any cell holding q answers "in a segment" (points asked in a row, as a lattice's, mostly share a
// cell; a slanted cell's box holds many points, each then with many boxes to test)
template <std::size_t D>
bool locator<D>::in_segment(const point<D>& q, std::uint32_t& hint) const {
  if (hint < cells_.size() && !flat_[hint] && inside_cell<D>(p_, cells_[hint], q)) return true;
  const std::uint32_t c = cell_holding(q);
  if (c != no_cell) hint = c;
  return c != no_cell;
}

template <std::size_t D>
std::size_t locator<D>::flat_cells() const {
  return static_cast<std::size_t>(std::count(flat_.begin(), flat_.end(), 1));
}

template bool inside_cell<2>(const std::vector<point<2>>&, const cell_t<2>&, const point<2>&);
template bool inside_cell<3>(const std::vector<point<3>>&, const cell_t<3>&, const point<3>&);
template bool strictly_inside_cell<2>(const std::vector<point<2>>&, const cell_t<2>&, const point<2>&);
template bool strictly_inside_cell<3>(const std::vector<point<3>>&, const cell_t<3>&, const point<3>&);
template class locator<2>;
template class locator<3>;

}  // namespace gsse::location
