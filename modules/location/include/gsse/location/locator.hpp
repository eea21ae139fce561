#pragma once
// Exact point location in a mesh of segments: which cell, and so which segment, holds a point.
// The pipeline builds one over a coarse mesh of the unsized conformed boundary (few cells, the
// same surface as the sized boundary) and asks it where the interior points go: the lattice's
// and the size field's points, and the user's cloud (modules/location/README.md).
//
// Every decision is an exact orientation (CGAL's predicates); doubles only choose which cells to
// test (a tree of the cells' boxes). Cells are positively oriented, as the front mesher makes
// them.
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "gsse/topology/simplex.hpp"
#include "gsse/geometry/point.hpp"
#include "gsse/sizing/box_tree.hpp"

namespace gsse::location {

template <std::size_t D>
using cell_t = std::array<vertex_id, D + 1>;

/// True if q lies in the closed cell c of points p (on its boundary counts: a point on an inner
/// face of the mesh is inside the domain). c positively oriented.
template <std::size_t D>
bool inside_cell(const std::vector<point<D>>& p, const cell_t<D>& c, const point<D>& q);

/// True if q lies strictly inside cell c (on none of its faces): then no other cell of a valid
/// mesh holds it. Never true of a cell of zero volume: its facets' signed volumes about q sum to
/// the cell's, 0, so they cannot all be positive.
template <std::size_t D>
bool strictly_inside_cell(const std::vector<point<D>>& p, const cell_t<D>& c, const point<D>& q);

/// The cells of a mesh, region by region, and exact look-ups in them.
///
/// | expression | result |
/// |---|---|
/// | `locator<D>(points, cells)` | over `cells[r]`, the cells of region r on `points` |
/// | `m.cell_holding(q)` | the cell of least index (regions in order) whose closed cell holds q, or `no_cell` |
/// | `m.region_of(q)` | the region of that cell, or -1 |
/// | `m.region_of(q, hint)` | the same; tries the cell `hint` first and leaves there the cell found |
/// | `m.in_segment(q)`, `m.in_segment(q, hint)` | whether any cell holds q |
/// | `m.lo()`, `m.hi()` | the points' bounding box |
/// | `m.flat_cells()` | the cells of zero volume, left out of every look-up |
///
/// A cell of zero volume holds (closed) every point of its plane within its box, so it is never
/// asked: the front mesher makes none (it turns only positive orientations into cells), and a
/// mesh from elsewhere may. The hinted look-ups give the unhinted answer: the hint is taken only
/// when q lies strictly inside it (region_of) or when any cell holding q will do (in_segment).
template <std::size_t D>
class locator {
 public:
  static constexpr std::uint32_t no_cell = std::numeric_limits<std::uint32_t>::max();

  locator() = default;
  locator(std::vector<point<D>> points, const std::vector<std::vector<cell_t<D>>>& cells_by_region);

  std::uint32_t cell_holding(const point<D>& q) const;
  int region_of(const point<D>& q) const;
  int region_of(const point<D>& q, std::uint32_t& hint) const;
  bool in_segment(const point<D>& q) const { return cell_holding(q) != no_cell; }
  bool in_segment(const point<D>& q, std::uint32_t& hint) const;

  const point<D>& lo() const { return lo_; }
  const point<D>& hi() const { return hi_; }
  std::size_t cells() const { return cells_.size(); }
  std::size_t flat_cells() const;

 private:
  std::vector<point<D>> p_;
  std::vector<cell_t<D>> cells_;
  std::vector<int> region_;  // of each cell
  std::vector<char> flat_;   // 1 for a cell of zero volume
  point<D> lo_{}, hi_{};
  sizing::box_tree<D> tree_;  // the cells' boxes
};

}  // namespace gsse::location
