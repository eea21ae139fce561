#pragma once
// Points inserted while a region is meshed (rule-driven point creation), bucketed in the cells of
// the shared read-only point_grid: each region keeps its own overlay, so regions meshed in
// parallel never see each other's insertions and the shared grid stays immutable.
#include <cstdint>
#include <vector>

#include "gsse/geometry/point_grid.hpp"

namespace gsse::front {

using geometry::point_grid;  // the candidate index (gsse/geometry/point_grid.hpp)

template <std::size_t G>
class point_overlay {
 public:
  using coord = std::array<double, G>;

  explicit point_overlay(const point_grid<G>& base) : base_(base), head_(base.cell_count(), -1) {}

  void insert(vertex_id v, const coord& c) {
    const auto cell = base_.linear(base_.cell_index(c));
    next_.push_back(head_[cell]);
    head_[cell] = static_cast<std::int32_t>(ids_.size());
    ids_.push_back(v);
    xyz_.push_back(c);
  }
  /// Same contract as point_grid::visit_box, over the inserted points only.
  template <class F>
  bool visit_box(const coord& lo, const coord& hi, F&& f) const {
    if (ids_.empty()) return true;
    return base_.visit_cells(lo, hi, [&](std::size_t cell) { return visit_list(cell, f); });
  }
  /// Same contract as point_grid::visit_ball, over the inserted points only.
  template <class F>
  bool visit_ball(const coord& c, double r, const coord& n, double d, F&& f) const {
    if (ids_.empty()) return true;
    return base_.visit_cells(c, r, n, d, [&](std::size_t cell) { return visit_list(cell, f); });
  }
  std::size_t size() const { return ids_.size(); }

 private:
  template <class F>
  bool visit_list(std::size_t cell, F& f) const {
    for (auto k = head_[cell]; k >= 0; k = next_[static_cast<std::size_t>(k)])
      if (!f(ids_[static_cast<std::size_t>(k)], xyz_[static_cast<std::size_t>(k)])) return false;
    return true;
  }
  const point_grid<G>& base_;
  std::vector<std::int32_t> head_, next_;
  std::vector<vertex_id> ids_;
  std::vector<coord> xyz_;
};

}  // namespace gsse::front
