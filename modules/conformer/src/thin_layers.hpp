#pragma once
// Thin layers: pairs of parallel facets facing each other across a gap thinner than the size
// (an oxide, a liner). The conformer seeds such a facet, and splits its PLC edges, at a spacing
// proportional to the gap when the refinement will ask for a radius-edge bound (options::
// thin_layer): the layer is then filled with right prisms over the walls' common lattice, whose
// tetrahedra meet the bound from the first mesh on, instead of the rounds refining the walls in
// steps of the square root of 3 (docs/design-decisions.md, "Thin layers are seeded at the gap's
// scale under --quality").
//
// Sizing only: doubles throughout, no topology is decided here. What is a thin layer:
// - two facets whose unit normals are parallel or opposite within 1e-9 radians (the walls of an
//   axis-aligned layer exactly, a turned layer's within rounding; walls that are only
//   approximately parallel, as CAD may give, are not found: the rounds refine those as before);
// - whose planes lie t apart, with 2e-8 of the model's size < t <= max_gap (closer planes count
//   as one plane: coplanar facets are not a layer);
// - that share no corner (a fold between nearly coplanar neighbours is not a layer);
// - and face each other: the centroid of each one's corners, projected into the other's plane,
//   lies inside the other facet (crossing test against its boundary edges, holes included). Both
//   ways round: with either way, OpenCASCADE's chair (corpus, --size at the diagonal / 20,
//   --quality 1.414) took its faces 0.11 and 0.3 apart, of 8 and 37 corners, facing in part only,
//   for layers, and its rounds ran to the cap of 250 (97,927 points against 83,103 in 30).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "gsse/geometry/point.hpp"

namespace gsse::conformer::thin {

struct facet {
  point3 unit{};                                  // unit normal
  point3 e1{}, e2{};                              // an orthonormal frame of the plane
  std::vector<point3> corners;                    // its PLC vertices
  std::vector<std::array<point3, 2>> sides;       // its boundary edges (outer loop and holes)
  std::vector<std::uint32_t> corner_ids;          // sorted ids of the corners (shared-corner test)
};

/// Whether x, projected into f's plane, lies inside f (even-odd crossing over its sides).
inline bool covers(const facet& f, const point3& x) {
  const double px = dot(x, f.e1), py = dot(x, f.e2);
  bool in = false;
  for (const auto& s : f.sides) {
    const double ax = dot(s[0], f.e1), ay = dot(s[0], f.e2), bx = dot(s[1], f.e1), by = dot(s[1], f.e2);
    if ((ay > py) != (by > py) && px < ax + (py - ay) * (bx - ax) / (by - ay)) in = !in;
  }
  return in;
}

inline point3 centroid(const facet& f) {
  point3 c{};
  for (const auto& q : f.corners) c = c + q;
  return (1.0 / static_cast<double>(std::max<std::size_t>(f.corners.size(), 1))) * c;
}

/// Per facet, the least gap t to a facet it faces as a thin layer's other wall (above), or
/// +infinity. `model` is the model's size (bounding-box diagonal), `max_gap` the largest gap of
/// interest. O(n log n) plus the pairs of parallel facets within max_gap of each other.
inline std::vector<double> layer_gaps(const std::vector<facet>& fs, double model, double max_gap) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<double> gap(fs.size(), inf);
  if (!(max_gap > 0) || fs.empty()) return gap;
  const double min_gap = 2e-8 * model;
  // the normals in cells of 1e-9 along each axis: a parallel facet's normal lies in the same
  // cell or a neighbour of it, an opposite one's in a neighbour of the negated normal's cell
  constexpr double q = 1e-9;
  using key = std::array<long long, 3>;
  struct key_hash {
    std::size_t operator()(const key& k) const {
      return static_cast<std::size_t>(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL);
    }
  };
  auto cell_of = [](const point3& n) {
    return key{static_cast<long long>(std::floor(n[0] / q)), static_cast<long long>(std::floor(n[1] / q)),
               static_cast<long long>(std::floor(n[2] / q))};
  };
  // each cell's facets sorted by their plane's offset along the cell's first facet's normal
  struct cell {
    point3 dir{};
    std::vector<std::pair<double, std::uint32_t>> by_offset;
  };
  std::unordered_map<key, cell, key_hash> cells;
  // centres from the corners' least corner, so that offsets are of the model's size, not its
  // coordinates'
  point3 origin{inf, inf, inf};
  for (const auto& f : fs)
    for (const auto& x : f.corners)
      for (std::size_t k = 0; k < 3; ++k) origin[k] = std::min(origin[k], x[k]);
  std::vector<point3> centre(fs.size());
  for (std::uint32_t i = 0; i < fs.size(); ++i) {
    if (fs[i].sides.empty() || fs[i].corners.empty()) continue;
    centre[i] = centroid(fs[i]) - origin;
    auto& c = cells[cell_of(fs[i].unit)];
    if (c.by_offset.empty()) c.dir = fs[i].unit;
    c.by_offset.push_back({dot(centre[i], c.dir), i});
  }
  for (auto& [k, c] : cells) std::sort(c.by_offset.begin(), c.by_offset.end());
  // normals within 2 cells' diagonal of each other differ by about 3.5e-9: offsets along the
  // cell's direction are off by at most that times the distance from the origin
  double far = 0;
  for (std::uint32_t i = 0; i < fs.size(); ++i) far = std::max(far, std::sqrt(dot(centre[i], centre[i])));
  const double slack = 8 * q * far;  // at most 8e-9 of the model's size: below min_gap
  // the cells a facet's parallel and opposite normals may lie in
  auto neighbours = [&](const point3& n) {
    std::vector<const cell*> found;
    for (const double sign : {1.0, -1.0}) {
      const key k0 = cell_of(sign * n);
      for (long long dx = -1; dx <= 1; ++dx)
        for (long long dy = -1; dy <= 1; ++dy)
          for (long long dz = -1; dz <= 1; ++dz)
            if (const auto it = cells.find(key{k0[0] + dx, k0[1] + dy, k0[2] + dz}); it != cells.end()) found.push_back(&it->second);
    }
    return found;
  };
  auto share_corner = [](const facet& F, const facet& G) {
    for (auto a = F.corner_ids.begin(), b = G.corner_ids.begin(); a != F.corner_ids.end() && b != G.corner_ids.end();) {
      if (*a == *b) return true;
      *a < *b ? ++a : ++b;
    }
    return false;
  };
  // the band of planes closer than min_gap (coplanar facets, possibly thousands of an STL's) is
  // skipped: the facets below it and above it, each range found by bisection
  const double band = min_gap - slack;
  for (std::uint32_t i = 0; i < fs.size(); ++i) {
    const auto& F = fs[i];
    if (F.sides.empty() || F.corners.empty()) continue;
    for (const cell* c : neighbours(F.unit)) {
      const double d = dot(centre[i], c->dir);
      for (auto [lo, hi] : {std::pair{d - max_gap - slack, d - band}, std::pair{d + band, d + max_gap + slack}}) {
        auto at = std::lower_bound(c->by_offset.begin(), c->by_offset.end(), std::make_pair(lo, std::uint32_t{0}));
        for (; at != c->by_offset.end() && at->first <= hi; ++at) {
          const std::uint32_t j = at->second;
          const auto& G = fs[j];
          const point3 x = cross(F.unit, G.unit);
          if (j == i || dot(x, x) > 1e-18) continue;  // itself, or more than 1e-9 radians apart
          const double t = std::abs(dot(centre[j] - centre[i], F.unit));
          if (!(t > min_gap) || t > max_gap || t >= gap[i] || share_corner(F, G)) continue;
          if (covers(F, centre[j] + origin) && covers(G, centre[i] + origin)) gap[i] = t;
        }
      }
    }
  }
  return gap;
}

}  // namespace gsse::conformer::thin
