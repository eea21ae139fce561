#include "gsse/refinement/refinement.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <optional>
#include <set>
#include <span>
#include <stdexcept>
#include <tuple>
#include <type_traits>
#include <utility>

#include "gsse/container/key_set.hpp"
#include "gsse/container/union_find.hpp"
#include "gsse/front/front_mesher.hpp"
#include "gsse/geometry/circumcentre.hpp"
#include "gsse/geometry/dihedral.hpp"
#include "gsse/geometry/exact_ball.hpp"
#include "gsse/geometry/hash_grid.hpp"
#include "gsse/geometry/point_grid.hpp"
#include "gsse/geometry/predicates.hpp"
#include "gsse/sizing/box_tree.hpp"
#include "gsse/traversal/for_each.hpp"
#include "gsse/traversal/parallel_sort.hpp"
#include "cavity_insertion.hpp"

namespace gsse::refinement {

double ratio_bound(std::size_t dimension, double bound) {
  if (std::isinf(bound) && bound > 0) return bound;  // size alone (the size rounds): no shape bound
  if (dimension == 2) {
    const double angle = bound > 0 ? bound : default_angle2;
    if (!(angle > 0 && angle <= max_angle2))
      throw std::invalid_argument("quality: the 2D bound is a smallest angle in degrees, in (0, " +
                                  std::to_string(max_angle2) + "]");
    return 1 / (2 * std::sin(angle * std::numbers::pi / 180));
  }
  const double ratio = bound > 0 ? bound : default_ratio3;
  if (!(ratio >= min_ratio3))
    throw std::invalid_argument("quality: the 3D bound is a radius-edge ratio of at least " + std::to_string(min_ratio3));
  return ratio;
}

namespace {

/// 3D without small input angles, an encroaching element asks for the split of its largest
/// encroached face below this radius-edge bound, of the nearest one at it and above (plan_round)
constexpr double largest_face_below = 1.3;

/// Refinement for size alone (the pipeline's size rounds): no radius-edge bound, no sliver rule.
inline bool size_only(double bound, double sliver) { return !std::isfinite(bound) && !(sliver > 0); }

template <std::size_t D>
using cell_t = std::array<vertex_id, D + 1>;

/// Sorts (key, index) pairs by key, stably (least significant digit first, 11 bits a pass; a
/// digit every key shares is skipped): the order std::stable_sort gives, at a few linear passes.
/// The cells' order before the rounds sorted 1e5 keys in about 5 ms with a comparison sort.
void radix_sort(std::vector<std::pair<std::uint64_t, std::uint32_t>>& a) {
  constexpr int bits = 11;
  constexpr std::size_t buckets = std::size_t{1} << bits;
  std::uint64_t any = 0, every = ~std::uint64_t{0};
  for (const auto& x : a) any |= x.first, every &= x.first;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> out(a.size());
  std::vector<std::size_t> at(buckets);
  for (int shift = 0; shift < 64; shift += bits) {
    if ((((any ^ every) >> shift) & (buckets - 1)) == 0) continue;  // the same digit in every key
    std::fill(at.begin(), at.end(), 0);
    for (const auto& x : a) ++at[(x.first >> shift) & (buckets - 1)];
    std::size_t sum = 0;
    for (auto& c : at) {
      const std::size_t n = c;
      c = sum, sum += n;
    }
    for (const auto& x : a) out[at[(x.first >> shift) & (buckets - 1)]++] = x;
    a.swap(out);
  }
}

template <std::size_t D>
struct candidate {
  point<D> c;
  double r;
  std::uint32_t first, count;  // its encroached faces, in the chunk's face list
  bool shape;                  // above the shape bound (else only too large for the size field)
  // the centroid of its cell, and whether the segment from there to c may meet the boundary (or
  // the centroid is not strictly inside the cell): only then can c lie outside the cell's segment
  point<D> from;
  bool may_leave = false;
};

/// Whether the closed segment xy and the closed boundary face F share a point, or might: coplanar
/// (2D: collinear) cases count as meeting. Exact.
inline bool may_meet(const std::vector<point2>& p, const std::array<vertex_id, 2>& F, const point2& x, const point2& y) {
  const int a = geometry::orient2d(p[F[0]], p[F[1]], x), b = geometry::orient2d(p[F[0]], p[F[1]], y);
  if (a == b && a != 0) return false;
  const int c = geometry::orient2d(x, y, p[F[0]]), d = geometry::orient2d(x, y, p[F[1]]);
  return !(c == d && c != 0);
}
inline bool may_meet(const std::vector<point3>& p, const std::array<vertex_id, 3>& F, const point3& x, const point3& y) {
  const point3 &a = p[F[0]], &b = p[F[1]], &c = p[F[2]];
  const int s = geometry::orient3d(a, b, c, x), t = geometry::orient3d(a, b, c, y);
  if (s == t && s != 0) return false;
  if (s == 0 && t == 0) return true;
  const int e0 = geometry::orient3d(x, y, a, b), e1 = geometry::orient3d(x, y, b, c), e2 = geometry::orient3d(x, y, c, a);
  const bool pos = e0 > 0 || e1 > 0 || e2 > 0, neg = e0 < 0 || e1 < 0 || e2 < 0;
  return !(pos && neg);
}

/// Whether g lies strictly inside cell c (exact).
template <std::size_t D>
bool strictly_inside(const std::vector<point<D>>& p, const std::array<vertex_id, D + 1>& c, const point<D>& g) {
  auto orient = [&](std::size_t skip) {
    std::array<point<D>, D + 1> q;
    for (std::size_t i = 0; i <= D; ++i) q[i] = i == skip ? g : p[c[i]];
    if constexpr (D == 2)
      return geometry::orient2d(q[0], q[1], q[2]);
    else
      return geometry::orient3d(q[0], q[1], q[2], q[3]);
  };
  const int o = orient(D + 1);
  if (o == 0) return false;
  for (std::size_t i = 0; i <= D; ++i)
    if (orient(i) != o) return false;
  return true;
}

/// Circumcentre and circumradius of a cell, within a relative 1e-8 of the longest edge: the
/// double construction when the cell is far from flat, else the exact one rounded outwards (a
/// nearly flat sliver's double centre can be anywhere). False only for an exactly flat cell.
template <std::size_t D>
bool circumball(const std::vector<point<D>>& p, const cell_t<D>& c, point<D>& at, double& r) {
  double longest = 0;
  for (std::size_t i = 0; i <= D; ++i)
    for (std::size_t j = i + 1; j <= D; ++j) longest = std::max(longest, squared_distance(p[c[i]], p[c[j]]));
  double det;
  if constexpr (D == 2) {
    const point2 off = geometry::plane_circumcentre_offset(p[c[1]] - p[c[0]], p[c[2]] - p[c[0]], det);
    if (std::abs(det) > 1e-6 * longest) {
      at = p[c[0]] + off;
      r = std::sqrt(dot(off, off));
      return std::isfinite(r);
    }
    if (geometry::orient2d(p[c[0]], p[c[1]], p[c[2]]) == 0) return false;
    geometry::exact_circumball(p[c[0]], p[c[1]], p[c[2]], at, r);
  } else {
    const point3 off = geometry::tetrahedron_circumcentre_offset(p[c[1]] - p[c[0]], p[c[2]] - p[c[0]], p[c[3]] - p[c[0]], det);
    if (std::abs(det) > 1e-6 * longest * std::sqrt(longest)) {
      at = p[c[0]] + off;
      r = std::sqrt(dot(off, off));
      return std::isfinite(r);
    }
    if (geometry::orient3d(p[c[0]], p[c[1]], p[c[2]], p[c[3]]) == 0) return false;
    geometry::exact_circumball(p[c[0]], p[c[1]], p[c[2]], p[c[3]], at, r);
  }
  return std::isfinite(r);
}

/// The ball the cavity search keeps for a cell (cell_ball) from circumball's result: its radius
/// padded by its rounding, or flat when circumball failed.
template <std::size_t D>
cell_ball<D> ball_of_cell(bool round, const point<D>& at, double rad) {
  cell_ball<D> ball;
  if (!round) {
    ball.pad = cell_ball<D>::flat;
    return ball;
  }
  ball.at = at;
  double m = 0;
  for (double x : at) m = std::max(m, std::abs(x));
  ball.pad = rad * (1 + 1e-8) + 64 * std::numeric_limits<double>::epsilon() * (m + rad) + 1e-300;
  return ball;
}

/// Boxes in a uniform grid of cells about as large as the boxes (each filed in every cell it
/// meets, counted and filled in box order): the plan's candidates, asked once by every boundary
/// face a round. A query box reads a few cells where a tree over the boxes descended from its root
/// (6% of a rotated trench run in that pass). Doubles select; the caller's exact tests decide.
/// Where the boxes crowd into few cells (candidates clustered about small input angles, in a grid
/// of at most 8 cells per box over the whole model), the tree instead: the boxes filed into a
/// cell, squared and summed over the cells, over all the filings (the cell mates a box has on
/// average) is 2-14 on the rotated trench and 230-7,100 on occ_hammer at --quality 1.414, where the
/// queries read 723 boxes a cell and this pass took 46% of the run. Above `crowded` the tree. Both
/// visit the same boxes; the callers sort what they find
template <std::size_t D>
class box_grid {
 public:
  explicit box_grid(const std::vector<sizing::aabb<D>>& boxes) : boxes_(boxes) {
    const std::size_t n = boxes.size();
    lo_ = hi_ = point<D>{};
    if (n == 0) return;
    auto all = sizing::aabb<D>::empty();
    double ext = 0;
    for (const auto& x : boxes) {
      all.add(x);
      for (std::size_t k = 0; k < D; ++k) ext += x.hi[k] - x.lo[k];
    }
    lo_ = all.lo, hi_ = all.hi;
    double span = 0;
    for (std::size_t k = 0; k < D; ++k) span = std::max(span, hi_[k] - lo_[k]);
    // cells about the boxes' mean extent, at least 1/1024 of the span, at most 8 per box overall
    // (the median instead made no difference on the rotated trench)
    double s = std::max(ext / static_cast<double>(n * D), span / 1024);
    if (!(s > 0) || !std::isfinite(s)) s = span > 0 && std::isfinite(span) ? span : 1.0;
    std::size_t total = 0;
    for (;;) {
      total = 1;
      for (std::size_t k = 0; k < D; ++k) {
        dims_[k] = static_cast<long>(std::min((hi_[k] - lo_[k]) / s, 1e6)) + 1;
        total *= static_cast<std::size_t>(dims_[k]);
      }
      if (total <= 8 * n + 64) break;
      s *= 1.5;
    }
    inv_ = 1 / s;
    first_.assign(total + 1, 0);
    for (const auto& x : boxes) each_cell(x, [&](std::size_t c) { ++first_[c + 1]; });
    for (std::size_t c = 1; c <= total; ++c) first_[c] += first_[c - 1];
    double mates = 0;
    for (std::size_t c = 0; c < total; ++c) {
      const auto k = static_cast<double>(first_[c + 1] - first_[c]);
      mates += k * k;
    }
    if (mates > crowded * static_cast<double>(first_.back())) {
      tree_ = sizing::box_tree<D>(boxes, std::vector<double>(n, 0.0));
      first_ = {};
      return;
    }
    items_.resize(first_.back());
    std::vector<std::uint32_t> fill(first_.begin(), first_.end() - 1);
    for (std::uint32_t i = 0; i < n; ++i) each_cell(boxes[i], [&](std::size_t c) { items_[fill[c]++] = i; });
  }
  /// Calls f(i) once for every box i meeting q (closed boxes).
  template <class F>
  void visit(const sizing::aabb<D>& q, F&& f) const {
    if (boxes_.empty()) return;
    for (std::size_t k = 0; k < D; ++k)
      if (std::isnan(q.lo[k]) || std::isnan(q.hi[k])) {  // no bounds (a degenerate face's ball): every box
        for (std::uint32_t i = 0; i < boxes_.size(); ++i) f(i);
        return;
      }
    for (std::size_t k = 0; k < D; ++k)
      if (q.hi[k] < lo_[k] || q.lo[k] > hi_[k]) return;
    if (!tree_.empty()) {
      tree_.visit(
          [&](const sizing::aabb<D>& x) {
            for (std::size_t k = 0; k < D; ++k)
              if (!(x.lo[k] <= q.hi[k] && q.lo[k] <= x.hi[k])) return false;
            return true;
          },
          [&](std::uint32_t i) {
            f(i);
            return true;
          });
      return;
    }
    each_cell(q, [&](std::size_t c) {
      for (auto j = first_[c]; j < first_[c + 1]; ++j) {
        const auto& x = boxes_[items_[j]];
        bool meet = true;
        point<D> m;
        for (std::size_t k = 0; k < D; ++k) {
          meet = meet && x.lo[k] <= q.hi[k] && q.lo[k] <= x.hi[k];
          m[k] = std::max(x.lo[k], q.lo[k]);
        }
        // once: in the cell of the overlap's lowest corner, which both boxes' cells include
        if (meet && index(m) == c) f(items_[j]);
      }
    });
  }

 private:
  long axis(std::size_t k, double x) const {
    const double t = (x - lo_[k]) * inv_;
    if (!(t > 0)) return 0;
    return t >= static_cast<double>(dims_[k]) ? dims_[k] - 1 : static_cast<long>(t);
  }
  std::size_t index(const point<D>& x) const {
    std::size_t c = 0;
    for (std::size_t k = D; k-- > 0;) c = c * static_cast<std::size_t>(dims_[k]) + static_cast<std::size_t>(axis(k, x[k]));
    return c;
  }
  template <class G>
  void each_cell(const sizing::aabb<D>& x, G&& g) const {
    std::array<long, D> a, e, at;
    for (std::size_t k = 0; k < D; ++k) a[k] = axis(k, x.lo[k]), e[k] = axis(k, x.hi[k]);
    at = a;
    for (;;) {
      std::size_t c = 0;
      for (std::size_t k = D; k-- > 0;) c = c * static_cast<std::size_t>(dims_[k]) + static_cast<std::size_t>(at[k]);
      g(c);
      std::size_t k = 0;
      while (k < D && ++at[k] > e[k]) at[k] = a[k], ++k;
      if (k == D) return;
    }
  }
  static constexpr double crowded = 64;
  const std::vector<sizing::aabb<D>>& boxes_;
  sizing::box_tree<D> tree_;  // crowded boxes: the tree, not the grid
  point<D> lo_, hi_;
  std::array<long, D> dims_{};
  double inv_ = 1;
  std::vector<std::uint32_t> first_, items_;
};

/// The diametral (2D) or equatorial (3D) ball of a boundary face, as a padded box.
template <std::size_t D>
sizing::aabb<D> face_box(const std::vector<point<D>>& p, const std::array<vertex_id, D>& F) {
  point<D> c;
  double r;
  if constexpr (D == 2) {
    c = 0.5 * (p[F[0]] + p[F[1]]);
    r = 0.5 * distance(p[F[0]], p[F[1]]);
  } else {
    const point3 u = p[F[1]] - p[F[0]], v = p[F[2]] - p[F[0]], n = cross(u, v);
    const point3 off = geometry::triangle_circumcentre_offset(u, v, n, dot(n, n));
    c = p[F[0]] + off;
    r = std::sqrt(dot(off, off));
  }
  r = r * (1 + 1e-9) + 1e-300;
  sizing::aabb<D> b;
  for (std::size_t k = 0; k < D; ++k) b.lo[k] = c[k] - r, b.hi[k] = c[k] + r;
  return b;
}

/// Points accepted in a round, found by distance: one hash grid per power-of-two radius in use,
/// so that a query of radius r visits at most 2^D cells whatever the grading. A level's cells are
/// twice the power of two above r (2r < cell <= 4r): a query's box spans one or two cells along
/// each axis (with cells of one power of two, r < cell <= 2r, it spanned two or three: up to 27
/// probes of the hash table, most of them empty; the round's accept loop is serial, and these
/// queries were its largest symbol in a 2-thread trench run: docs/benchmarks.md, sixty-fifth
/// part). The answer is the same whatever the cells. A level's grid takes the points added since
/// its last query when it is next asked, not at add(): the round asks in falling radius, so the
/// coarse levels stop early and never see the later points (scad_example009: the inserts into
/// every level were a second of its serial accept loops; docs/benchmarks.md, sixty-seventh part).
template <std::size_t D>
class accepted_points {
 public:
  accepted_points(const point<D>& origin, const std::set<int>& levels) {
    if (levels.empty()) return;
    first_ = *levels.begin();
    slot_.assign(static_cast<std::size_t>(*levels.rbegin() - first_ + 1), 0);
    for (int k : levels) {
      slot_[static_cast<std::size_t>(k - first_)] = static_cast<std::uint32_t>(grids_.size());
      grids_.emplace_back(origin, std::ldexp(1.0, k + 1));
    }
    filled_.assign(grids_.size(), 0);
  }
  static int level(double r) { return std::ilogb(r) + 1; }
  /// r's level must be among those given.
  bool any_within(const point<D>& c, double r) {
    const std::uint32_t s = slot_[static_cast<std::size_t>(level(r) - first_)];
    auto& g = grids_[s];
    for (auto& i = filled_[s]; i < points_.size(); ++i) g.insert(i, points_[i]);
    point<D> lo, hi;
    for (std::size_t k = 0; k < D; ++k) lo[k] = c[k] - r, hi[k] = c[k] + r;
    return !g.visit(lo, hi, [&](std::uint32_t i) { return !(squared_distance(points_[i], c) < r * r); });
  }
  void add(const point<D>& c) { points_.push_back(c); }

 private:
  int first_ = 0;                    // the lowest level
  std::vector<std::uint32_t> slot_;  // per level from first_: its grid's place in grids_
  std::vector<hash_grid<D>> grids_;
  std::vector<std::uint32_t> filled_;  // per grid: the points filed in it (the first ones)
  std::vector<point<D>> points_;
};

/// q's bits spread to every D-th place (bit i to bit D i), q < 2^(64 / D): each step moves the
/// upper half of every group of bits up by the shift and masks off what is not in place.
template <std::size_t D>
std::uint64_t spread_bits(std::uint64_t q) {
  static_assert(D == 2 || D == 3);
  struct step {
    int shift;
    std::uint64_t mask;
  };
  static constexpr std::array<step, 5> steps2{{{16, 0x0000ffff0000ffffull}, {8, 0x00ff00ff00ff00ffull},
                                                {4, 0x0f0f0f0f0f0f0f0full}, {2, 0x3333333333333333ull},
                                                {1, 0x5555555555555555ull}}};
  static constexpr std::array<step, 5> steps3{{{32, 0x001f00000000ffffull}, {16, 0x001f0000ff0000ffull},
                                                {8, 0x100f00f00f00f00full}, {4, 0x10c30c30c30c30c3ull},
                                                {2, 0x1249249249249249ull}}};
  q &= D == 2 ? 0xffffffffull : 0x1fffffull;
  for (const auto& [shift, mask] : D == 2 ? steps2 : steps3) q = (q | q << shift) & mask;
  return q;
}

/// The Morton code of x's cell in a 2^bits lattice over the box [lo, hi] (bits * D <= 64): the
/// lattice coordinates' bits interleaved, so that nearby codes are nearby cells.
template <std::size_t D>
std::uint64_t morton_code(const point<D>& x, const point<D>& lo, const point<D>& hi, int bits) {
  const double cells = std::ldexp(1.0, bits);
  std::uint64_t m = 0;
  for (std::size_t k = 0; k < D; ++k) {
    const double e = hi[k] - lo[k];
    const double t = e > 0 ? (x[k] - lo[k]) / e : 0;
    const auto q = static_cast<std::uint64_t>(std::clamp(t * cells, 0.0, cells - 1));
    m |= spread_bits<D>(q) << k;
  }
  return m;
}

}  // namespace

template <std::size_t D>
spacing_floor<D>::spacing_floor(const conformer::boundary<D>& b, double r) : ratio(b.plc_points > 0 ? r : 0.0) {
  if (!(ratio > 0)) return;
  const auto& p = b.points;
  std::vector<double> nn(p.size(), std::numeric_limits<double>::infinity());
  for (const auto& F : b.faces)
    for (std::size_t i = 0; i < D; ++i)
      for (std::size_t j = i + 1; j < D; ++j) {
        const double l = distance(p[F[i]], p[F[j]]);
        nn[F[i]] = std::min(nn[F[i]], l), nn[F[j]] = std::min(nn[F[j]], l);
      }
  std::vector<sizing::aabb<D>> boxes;
  std::vector<double> values;
  for (std::size_t v = 0; v < p.size(); ++v)
    if (nn[v] < std::numeric_limits<double>::infinity()) {
      auto box = sizing::aabb<D>::empty();
      box.add(p[v]);
      boxes.push_back(box), values.push_back(nn[v]);
    }
  for (double v : values) cap = std::max(cap, v);
  spacing = sizing::box_tree<D>(std::move(boxes), std::move(values));
  std::vector<sizing::aabb<D>> at;
  for (std::size_t v = 0; v < b.plc_points && v < p.size(); ++v) {
    auto box = sizing::aabb<D>::empty();
    box.add(p[v]);
    at.push_back(box);
  }
  inputs = sizing::box_tree<D>(std::move(at), std::vector<double>(std::min(b.plc_points, p.size()), 0.0));
}

template <std::size_t D>
vertex_id spacing_floor<D>::nearest_input(const point<D>& x) const {
  const double d = inputs.graded_min(x, 1.0);
  const double d2 = d * d * (1 + 1e-9) + 1e-300;
  vertex_id best = no_vertex;
  inputs.visit([&](const sizing::aabb<D>& box) { return box.distance2(x) <= d2; },
               [&](std::uint32_t i) {
                 if (inputs.box(i).distance2(x) <= d2 && (best == no_vertex || i < best)) best = i;
                 return true;
               });
  return best;
}

template struct spacing_floor<2>;
template struct spacing_floor<3>;

template <std::size_t D>
plan<D> plan_round(const cells_by_region<D>& cells_of, const conformer::boundary<D>& b, double bound, unsigned threads,
                   const std::function<double(const point<D>&)>& size, double sliver, const conformer::labelling* l,
                   std::vector<std::vector<char>>* todo, double acute_guard, balls_by_region<D>* balls,
                   const spacing_floor<D>* floor, const edge_sizes* graded, vertex_sizes* vertex_h,
                   const std::function<double(int)>* segment_maximum2) {
  plan<D> out;
  const auto& bp = b.points;
  // the cells in chunks, segment by segment: candidates are found in parallel and merged in
  // chunk order (deterministic)
  struct chunk {
    std::span<const cell_t<D>> cells;
    char* todo;            // per cell: 0 = known good, skipped; set to 0 when found good
    cell_ball<D>* balls;   // per cell: its ball, stored when measured (optional)
    double most = std::numeric_limits<double>::infinity();  // its segment's own maximum size (graded; 2D size2)
  };
  constexpr std::size_t piece = 4096;
  std::vector<chunk> chunks;
  for (std::size_t r = 0; r < cells_of.size(); ++r) {
    const std::span<const cell_t<D>> cells(cells_of[r]);
    char* flags = todo ? (*todo)[r].data() : nullptr;
    cell_ball<D>* kept = balls && (*balls)[r].size() == cells.size() ? (*balls)[r].data() : nullptr;
    double most = std::numeric_limits<double>::infinity();
    if (graded && graded->segment_maximum && l && r < l->regions.size()) most = graded->segment_maximum(l->regions[r].number);
    if (D == 2 && segment_maximum2 && *segment_maximum2 && l && r < l->regions.size()) most = (*segment_maximum2)(l->regions[r].number);
    for (std::size_t a = 0; a < cells.size(); a += piece)
      chunks.push_back({cells.subspan(a, std::min(piece, cells.size() - a)), flags ? flags + a : nullptr, kept ? kept + a : nullptr, most});
  }
  std::vector<std::vector<candidate<D>>> found(chunks.size());
  std::vector<std::vector<std::uint32_t>> faces(chunks.size());
  std::vector<std::size_t> ids(chunks.size());
  std::iota(ids.begin(), ids.end(), std::size_t{0});
  const auto& p = b.points;
  // 3D graded sizes (edge_sizes): a lower bound of h at every vertex, kept across rounds (the
  // points only grow). An edge of length e is cleared by its ends when the larger bound is at
  // least e (1 / 1.5 + slope / 2), with a margin far above rounding, so that the midpoint's own
  // query would say the same: the result does not depend on which bounds are known
  vertex_sizes own_h;
  vertex_sizes& vh = vertex_h ? *vertex_h : own_h;
  const bool ask_edges = D == 3 && graded && graded->h;
  const bool bounded = ask_edges && std::isfinite(graded->slope);
  const double clear_per_length = bounded ? (1 / 1.5 + 0.5 * graded->slope) * (1 + 1e-9) : 0.0;
  if (bounded) {
    const std::size_t n = b.points.size();
    vh.lower.resize(n, 0.0), vh.exact.resize(n, 0);
    // what this round's cells need at each vertex: the most any of their edges there needs
    std::vector<double> want(n, 0.0);
    for_each(execution::par(threads), ids, [&](std::size_t k) {
      const char* flag = chunks[k].todo;
      for (std::size_t ci = 0; ci < chunks[k].cells.size(); ++ci) {
        if (flag && !flag[ci]) continue;
        const auto& c = chunks[k].cells[ci];
        for (std::size_t i = 0; i <= D; ++i)
          for (std::size_t j = i + 1; j <= D; ++j) {
            const vertex_id u = c[i], v = c[j];
            const double need = clear_per_length * distance(p[u], p[v]);
            if (std::max(vh.lower[u], vh.lower[v]) >= need) continue;
            for (vertex_id w : {u, v}) {
              std::atomic_ref<double> at(want[w]);
              double was = at.load(std::memory_order_relaxed);
              while (was < need && !at.compare_exchange_weak(was, need, std::memory_order_relaxed)) {
              }
            }
          }
      }
    }, [&](std::size_t k) { return static_cast<double>(chunks[k].cells.size()); });
    // asked up to what is needed, no further: the capped search stays near the point (capped at
    // twice that, two thirds as many queries at about three times the cost each: the rotated
    // FinFET graded 0.5 s of queries against 0.3 s)
    std::vector<std::size_t> starts;
    for (std::size_t a = 0; a < n; a += piece) starts.push_back(a);
    if constexpr (D == 3)
      for_each(execution::par(threads), starts, [&](std::size_t a) {
        for (std::size_t v = a; v < std::min(n, a + piece); ++v) {
          if (vh.exact[v] || !(want[v] > vh.lower[v])) continue;
          const double cap = want[v];
          const double q = graded->h(b.points[v], cap);
          vh.lower[v] = q;
          vh.exact[v] = q < cap;
        }
      });
  }
  // 3D acute vertices: their protecting balls (conformer), grown by acute_guard
  struct guard {
    point<D> at;
    double r;
    vertex_id v;
  };
  std::vector<guard> guarded;
  for (std::size_t v = 0; v < b.protect.size() && v < p.size(); ++v)
    if (b.protect[v] > 0) guarded.push_back({p[v], acute_guard * b.protect[v], static_cast<vertex_id>(v)});
  // 2D small input angles (Shewchuk's rule, as Triangle applies it): a bad triangle whose
  // shortest edge joins two points on the same concentric shell about an input vertex where
  // their two input edges meet at less than 60 degrees is excepted: splitting it would only
  // make the conformer's next, smaller shell. ends[e]: the PLC vertices that end input edge e.
  std::vector<std::array<vertex_id, 2>> ends;
  if constexpr (D == 2) {
    if (acute_guard > 0) {
      std::uint32_t edges = 0;
      for (auto s : b.face_source) edges = std::max(edges, s + 1);
      ends.assign(edges, {no_vertex, no_vertex});
      for (std::size_t f = 0; f < b.faces.size(); ++f)
        for (vertex_id v : b.faces[f])
          if (v < b.plc_points) {
            auto& E = ends[b.face_source[f]];
            if (E[0] == no_vertex) E[0] = v;
            else if (E[0] != v) E[1] = v;
          }
    }
  }
  // 3D small dihedral angles: a subsegment of an input edge where two boundary faces meet at less
  // than 60 degrees (measured between their third vertices, perpendicular to the edge; doubles,
  // a refinement policy) is sharp. A bad element whose circumcentre lies within acute_guard x
  // the subsegment's length of it is excepted, and reported at the subsegment's first end.
  struct sharp_piece {
    vertex_id a, c;
    double reach;
  };
  std::vector<sharp_piece> sharp;
  std::vector<sizing::aabb<D>> sharp_boxes;
  if constexpr (D == 3) {
    if (acute_guard > 0) {
      auto on_edge = [&](vertex_id v) { return v < b.plc_points || b.homes[v].kind == conformer::home::edge; };
      // whether uv can lie on an input edge: two points of one edge, or an input vertex and a point
      // of any edge, or two input vertices. A face side between points of two different edges
      // crosses a facet's inside, and the faces on it are of that one facet, opposite: never thin
      auto along = [&](vertex_id u, vertex_id v) {
        return u < b.plc_points || v < b.plc_points || b.homes[u].id == b.homes[v].id;
      };
      // (subsegment, third vertex) of every face on two edge points, grouped by subsegment (a
      // sorted list: a hash map of lists per round cost more than the rest of the plan)
      // (in parallel over pieces of the face list: a pass over every boundary face each round)
      std::vector<std::size_t> parts((b.faces.size() + piece - 1) / piece);
      std::iota(parts.begin(), parts.end(), std::size_t{0});
      std::vector<std::vector<std::pair<std::uint64_t, vertex_id>>> around_in(parts.size());
      for_each(execution::par(threads), parts, [&](std::size_t q) {
        for (std::size_t f = q * piece; f < std::min(b.faces.size(), (q + 1) * piece); ++f) {
          const auto& F = b.faces[f];
          const std::array<bool, 3> on{on_edge(F[0]), on_edge(F[1]), on_edge(F[2])};
          if (on[0] + on[1] + on[2] < 2) continue;
          for (std::size_t i = 0; i < 3; ++i) {
            const vertex_id u = F[i], v = F[(i + 1) % 3], w = F[(i + 2) % 3];
            if (!on[i] || !on[(i + 1) % 3] || !along(u, v)) continue;
            around_in[q].push_back({(std::uint64_t{std::min(u, v)} << 32) | std::max(u, v), w});
          }
        }
      });
      std::vector<std::pair<std::uint64_t, vertex_id>> around;
      for (const auto& a : around_in) around.insert(around.end(), a.begin(), a.end());
      // by subsegment alone, each one's entries in face order (what is asked of them below does
      // not depend on their order): a linear sort, where sorting the pairs whole was 10 of the
      // 12 ms this step took each round on the Gmsh torus (136,000 entries; docs/benchmarks.md,
      // seventieth part)
      radix_sort(around);
      // the groups in pieces of about `piece` entries (cut between groups), in parallel; the
      // pieces' sharp subsegments in piece order, as one pass in order lists them (a serial pass,
      // 0.47 s of scad_example009's plans; docs/benchmarks.md, sixty-eighth part)
      std::vector<std::pair<std::size_t, std::size_t>> spans;
      for (std::size_t a = 0; a < around.size();) {
        std::size_t e = std::min(around.size(), a + piece);
        while (e < around.size() && around[e].first == around[e - 1].first) ++e;
        spans.push_back({a, e});
        a = e;
      }
      std::vector<std::vector<sharp_piece>> sharp_in(spans.size());
      std::vector<std::vector<sizing::aabb<D>>> boxes_in(spans.size());
      std::vector<std::size_t> span_ids(spans.size());
      std::iota(span_ids.begin(), span_ids.end(), std::size_t{0});
      for_each(execution::par(threads), span_ids, [&](std::size_t q) {
        std::vector<vertex_id> thirds;
        std::vector<point<D>> dirs;
        for (std::size_t at = spans[q].first; at < spans[q].second;) {
          const std::uint64_t key = around[at].first;
          thirds.clear();
          for (; at < spans[q].second && around[at].first == key; ++at) thirds.push_back(around[at].second);
          if (thirds.size() < 2) continue;
          const auto u = static_cast<vertex_id>(key >> 32), v = static_cast<vertex_id>(key & 0xffffffffu);
          const point<D> d = p[v] - p[u];
          const double dd = dot(d, d);
          dirs.clear();
          for (vertex_id w : thirds) {
            point<D> x = p[w] - p[u];
            x = x - (dot(x, d) / dd) * d;
            const double n = std::sqrt(dot(x, x));
            if (n > 0) dirs.push_back((1 / n) * x);
          }
          bool thin = false;
          for (std::size_t i = 0; i < dirs.size() && !thin; ++i)
            for (std::size_t j = i + 1; j < dirs.size(); ++j)
              if (dot(dirs[i], dirs[j]) > 0.5) thin = true;
          if (!thin) continue;
          const double reach = acute_guard * std::sqrt(dd);
          sharp_in[q].push_back({u, v, reach});
          auto box = sizing::aabb<D>::empty();
          box.add(p[u]), box.add(p[v]);
          for (std::size_t k = 0; k < D; ++k) box.lo[k] -= reach, box.hi[k] += reach;
          boxes_in[q].push_back(box);
        }
      }, [&](std::size_t q) { return static_cast<double>(spans[q].second - spans[q].first); });
      for (std::size_t q = 0; q < spans.size(); ++q) {
        sharp.insert(sharp.end(), sharp_in[q].begin(), sharp_in[q].end());
        sharp_boxes.insert(sharp_boxes.end(), boxes_in[q].begin(), boxes_in[q].end());
      }
    }
  }
  const sizing::box_tree<D> sharp_tree(sharp_boxes, std::vector<double>(sharp_boxes.size(), 0.0));
  auto near_sharp = [&](const point<D>& x) -> std::size_t {  // a sharp piece within reach of x, or none
    std::size_t hit = sharp.size();
    sharp_tree.visit([&](const sizing::aabb<D>& box) { return box.contains(x); },
                     [&](std::uint32_t i) {
                       const point<D> a = p[sharp[i].a], d = p[sharp[i].c] - a;
                       const double t = std::clamp(dot(x - a, d) / dot(d, d), 0.0, 1.0);
                       if (squared_distance(x, a + t * d) < sharp[i].reach * sharp[i].reach) {
                         hit = i;
                         return false;
                       }
                       return true;
                     });
    return hit;
  };
  // the input vertex whose small angle the shortest edge (a, c) subtends (2D), or no_vertex: a and
  // c on two input edges that share v, on one shell about v, the edges at less than 60 degrees
  // (doubles: a refinement policy, not topology)
  auto subtends = [&](vertex_id a, vertex_id c) -> vertex_id {
    const auto& ha = b.homes[a];
    const auto& hc = b.homes[c];
    if (ha.kind != conformer::home::edge || hc.kind != conformer::home::edge || ha.id == hc.id) return no_vertex;
    if (ha.id >= ends.size() || hc.id >= ends.size()) return no_vertex;
    for (vertex_id v : ends[ha.id]) {
      if (v == no_vertex || (v != ends[hc.id][0] && v != ends[hc.id][1])) continue;
      const point<D> x = p[a] - p[v], y = p[c] - p[v];
      const double da = dot(x, x), dc = dot(y, y);
      const double ratio = 1.002001;  // (1.001)^2: the same shell, as Triangle tests it
      if (da < ratio * dc && dc < ratio * da && dot(x, y) > 0.5 * std::sqrt(da * dc)) return v;
    }
    return no_vertex;
  };
  std::vector<std::vector<vertex_id>> excepted(chunks.size());  // per chunk: where each excepted element is
  std::vector<std::size_t> floored(chunks.size(), 0);  // per chunk: of those, below the spacing floor
  // the guards' boxes in a tree: the excepted elements are looked at again every round, and a CAD
  // part has hundreds of acute vertices
  std::vector<sizing::aabb<D>> guard_boxes;
  for (const auto& g : guarded) {
    auto box = sizing::aabb<D>::empty();
    box.add(g.at);
    for (std::size_t k = 0; k < D; ++k) box.lo[k] -= g.r, box.hi[k] += g.r;
    guard_boxes.push_back(box);
  }
  const sizing::box_tree<D> guard_tree(std::move(guard_boxes), std::vector<double>(guarded.size(), 0.0));
  auto near_acute = [&](const point<D>& x) -> std::size_t {  // the first guard holding x, or none
    std::size_t first = guarded.size();
    guard_tree.visit([&](const sizing::aabb<D>& box) { return box.contains(x); }, [&](std::uint32_t g) {
      if (g < first && squared_distance(x, guarded[g].at) < guarded[g].r * guarded[g].r) first = g;
      return true;
    });
    return first;
  };
  const double cos_sliver = std::cos(sliver * std::numbers::pi / 180), cos_flat = std::cos((180 - 2 * sliver) * std::numbers::pi / 180);
  const bool size_alone = size_only(bound, sliver);
  for_each(execution::par(threads), ids, [&](std::size_t k) {
    char* flag = chunks[k].todo;
    for (std::size_t ci = 0; ci < chunks[k].cells.size(); ++ci) {
      if (flag && !flag[ci]) continue;
      // the cell's vertices in ascending order: what is measured and proposed (circumcentre,
      // radius, shortest edge, centroid, all in doubles) is then a function of the cell's vertex
      // set, not of the order the front mesher listed them in (a fill that makes the same cells
      // in another order makes the same points; test `plan_does_not_depend_on_vertex_order`)
      auto c = chunks[k].cells[ci];
      std::sort(c.begin(), c.end());
      double shortest = 1e300, longest = 0;
      std::size_t si = 0, sj = 1;
      for (std::size_t i = 0; i <= D; ++i)
        for (std::size_t j = i + 1; j <= D; ++j) {
          const double l2 = squared_distance(p[c[i]], p[c[j]]);
          if (l2 < shortest) shortest = l2, si = i, sj = j;
          longest = std::max(longest, l2);
        }
      // graded (3D, edge_sizes): each edge against 1.5 h at its midpoint, the field asked there
      // (capped just above e / 1.5) only where the bound from its ends does not clear it
      auto too_long = [&] {
        if constexpr (D == 3) {
          const double most = chunks[k].most;
          for (std::size_t i = 0; i <= D; ++i)
            for (std::size_t j = i + 1; j <= D; ++j) {
              const double e = distance(p[c[i]], p[c[j]]);
              if (e <= 1.5 * most && bounded && std::max(vh.lower[c[i]], vh.lower[c[j]]) >= clear_per_length * e) continue;
              if (e > 1.5 * std::min(most, graded->h(0.5 * (p[c[i]] + p[c[j]]), e / 1.5 * (1 + 1e-9)))) return true;
            }
        }
        return false;
      };
      // size alone (no shape bound, no sliver rule): a cell whose edges the graded field clears
      // needs no circumball (the size rounds without --quality; the plan's time there is mostly
      // the field's queries, so this gains little: rotated MOSFET graded 0.25 -> 0.21-0.23 s)
      if (size_alone && ask_edges && !too_long()) {
        if (flag) flag[ci] = 0;
        continue;
      }
      point<D> at;
      double r;
      const bool round = circumball(p, c, at, r);
      if (cell_ball<D>* kb = chunks[k].balls; kb && kb[ci].pad == cell_ball<D>::unknown) kb[ci] = ball_of_cell<D>(round, at, r);
      if (!round) continue;
      const bool bad_ratio = r > bound * std::sqrt(shortest);
      bool bad_shape = bad_ratio;  // or a sliver (3D, below)
      if constexpr (D == 3) {
        if (!bad_shape && sliver > 0) {
          // an angle below `sliver` or above 180 - 2 sliver degrees, by cosines (no acos per cell)
          const auto [most, least] = geometry::dihedral_cosines(p, c);
          bad_shape = most > cos_sliver || least < cos_flat;
        }
      }
      // too large for the size field: 2D a circumradius above h / sqrt 3 (the equilateral triangle
      // of side h), 3D an edge longer than 1.5 h (the regular lattice's own tetrahedra have a
      // circumradius of 0.65 h, above h / sqrt 3; the issue's bound is 1.5 h), h at the circumcentre
      auto too_large = [&] {
        if constexpr (D == 3) {
          if (ask_edges) return too_long();
        }
        if (!size) return false;
        if constexpr (D == 2) {
          // size alone (2D size rounds): each edge against 1.5 h at its midpoint, the issue's
          // measure, as 3D; the circumradius rule would refine the lattice's own equilateral
          // triangles (circumradius exactly h / sqrt 3) on rounding
          if (size_alone) {
            for (std::size_t i = 0; i <= D; ++i)
              for (std::size_t j = i + 1; j <= D; ++j) {
                const double e = distance(p[c[i]], p[c[j]]);
                if (e > 1.5 * std::min(chunks[k].most, size(0.5 * (p[c[i]] + p[c[j]])))) return true;
              }
            return false;
          }
        }
        const double h = D == 2 ? std::min(chunks[k].most, size(at)) : size(at);
        if constexpr (D == 2)
          return 3 * r * r > h * h;
        else
          return longest > 2.25 * h * h;
      };
      if (!bad_shape && !too_large()) {
        if (flag) flag[ci] = 0;  // good, and a cell never changes: not looked at again
        continue;
      }
      if (bad_ratio && (!guarded.empty() || !sharp.empty() || !ends.empty())) {
        // small input angle (3D): a bad element whose circumcentre falls near an acute vertex or
        // a sharp input edge is excepted (left, counted): refining there makes the conformer go
        // one shell deeper each round; 2D: a bad triangle whose shortest edge subtends a small
        // input angle. A sliver within the radius-edge bound is not excepted here: its
        // circumcentre goes in unless it encroaches a boundary face whose circumcentre lies in a
        // guard (below), and the spacing floor still ends a cascade (corpus at 1.414: elements
        // with an angle below 5 degrees 18,842 -> 18,573, above 170 5,296 -> 5,019;
        // docs/benchmarks.md, thirty-second part)
        vertex_id where = no_vertex;
        if constexpr (D == 2) {
          where = subtends(c[si], c[sj]);
        } else {
          if (const std::size_t g = near_acute(at); g < guarded.size()) where = guarded[g].v;
          else if (const std::size_t e = near_sharp(at); e < sharp.size()) where = sharp[e].a;
        }
        if (where != no_vertex) {
          excepted[k].push_back(where);
          continue;
        }
      }
      // 3D: below the spacing floor (spacing_floor): excepted where no guard named it, so that
      // cascades the guards miss end
      if (bad_shape && acute_guard > 0 && floor && floor->below(at, r)) {
        excepted[k].push_back(floor->nearest_input(at));
        ++floored[k];
        continue;
      }
      if (D == 2 && bad_shape) {
        // Ungor's off-centre: on the shortest edge's bisector, no farther from it than the apex
        // of the triangle on that edge with the bound's angle (so that triangle is not bad), if
        // the circumcentre is farther (fewer points)
        const point<D> m = 0.5 * (p[c[si]] + p[c[sj]]);
        const double half = 0.5 * std::sqrt(shortest), far = distance(m, at);
        const double reach = half * (2 * bound + std::sqrt(4 * bound * bound - 1));  // cot(theta/2) * half
        if (far > reach && far > 0) {
          at = m + (reach / far) * (at - m);
          r = distance(at, p[c[si]]);
        }
      }
      point<D> g{};
      for (auto v : c) g = g + p[v];
      g = (1.0 / (D + 1)) * g;
      found[k].push_back({at, r, 0, 0, bad_shape, g, l && !strictly_inside<D>(p, c, g)});
    }
  }, [&](std::size_t k) { return static_cast<double>(chunks[k].cells.size()); });
  // the boundary faces whose closed ball holds a candidate (exact; a tie counts): the candidates'
  // circumcentres in a grid, asked by every face's ball box (a pass over the faces; a tree over
  // the faces, built every round, cost more than the round's few queries). Then, for the
  // candidates that encroach no face (only those can go in as circumcentres), whether their
  // segment from their cell's centroid may meet a face (below): a second pass, over the faces'
  // own boxes, with those segments alone. (One pass asking both of every candidate read 505,000
  // pairs of the 1e5 trench's faces and candidates in its 9 plans, each with an exact segment
  // test: the liner's thousands of bad elements lie at its walls and all encroach)
  {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> who;  // (chunk, index)
    std::vector<point<D>> spot;  // their circumcentres
    for (std::uint32_t k = 0; k < found.size(); ++k)
      for (std::uint32_t i = 0; i < found[k].size(); ++i) {
        who.push_back({k, i});
        spot.push_back(found[k][i].c);
      }
    if (!who.empty()) {
      // pieces of 512 faces (the cells' 4096 made about 9 pieces of the 1e5 trench's faces, whose
      // candidates crowd at the liner's walls: this pass took 23 ms of its 2-thread plans, 20 now)
      constexpr std::size_t face_piece = 512;
      std::vector<std::size_t> pieces((b.faces.size() + face_piece - 1) / face_piece);
      std::iota(pieces.begin(), pieces.end(), std::size_t{0});
      {
        // a point grid, nested where the circumcentres crowd (a box grid over them read
        // thousands of crowded candidates per face near the small angles of scad_example009:
        // docs/benchmarks.md, sixty-seventh part)
        const geometry::point_grid<D> centres{std::span<const point<D>>(spot)};
        std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> hits(pieces.size());  // (candidate, face)
        for_each(execution::par(threads), pieces, [&](std::size_t q) {
          for (std::size_t f = q * face_piece; f < std::min(b.faces.size(), (q + 1) * face_piece); ++f) {
            const auto& F = b.faces[f];
            auto box = face_box(bp, F);
            // 3D, a face the conformer kept with an apex (conformer::boundary::face_apex): a point
            // across it breaks it inside the sphere through it and the apex, beyond its ball
            const bool apex = D == 3 && f < b.face_apex.size() && b.face_apex[f] != no_vertex;
            if constexpr (D == 3)
              if (apex) {
                point3 sc;
                double sr = 0;
                if (geometry::circumball_bound(bp[F[0]], bp[F[1]], bp[F[2]], bp[b.face_apex[f]], sc, sr))
                  for (std::size_t k = 0; k < 3; ++k) box.lo[k] = std::min(box.lo[k], sc[k] - sr), box.hi[k] = std::max(box.hi[k], sc[k] + sr);
                else
                  for (std::size_t k = 0; k < 3; ++k) box.lo[k] = box.hi[k] = std::numeric_limits<double>::quiet_NaN();  // every candidate is asked
              }
            auto test = [&](vertex_id g, const point<D>& at) {
              if (box.contains(at)) {
                bool s;
                if constexpr (D == 2)
                  s = geometry::in_diametral(bp[F[0]], bp[F[1]], at) >= 0;
                else
                  s = apex ? conformer::face_encroached(b, f, at) : geometry::in_equatorial(bp[F[0]], bp[F[1]], bp[F[2]], at) >= 0;
                if (s) hits[q].push_back({g, static_cast<std::uint32_t>(f)});
              }
              return true;
            };
            bool finite_box = true;  // a degenerate face's ball has no bounds: every candidate is asked
            for (std::size_t k = 0; k < D; ++k) finite_box = finite_box && !std::isnan(box.lo[k]) && !std::isnan(box.hi[k]);
            if (finite_box) {
              centres.visit_box(box.lo, box.hi, test);
            } else {
              for (std::uint32_t g = 0; g < spot.size(); ++g) test(g, spot[g]);
            }
          }
        });
        // each candidate's faces, ascending: grouped by counting (the pieces hold ascending faces,
        // in ascending pieces), as a sort of the (candidate, face) pairs would give them
        std::vector<std::size_t> at(who.size() + 1, 0);
        for (const auto& h : hits)
          for (const auto& [g, f] : h) ++at[g + 1];
        for (std::size_t g = 0; g < who.size(); ++g) at[g + 1] += at[g];
        std::vector<std::uint32_t> by_candidate(at.back());
        {
          std::vector<std::size_t> next(at.begin(), at.end() - 1);
          for (const auto& h : hits)
            for (const auto& [g, f] : h) by_candidate[next[g]++] = f;
        }
        for (std::uint32_t g = 0; g < who.size(); ++g) {
          if (at[g] == at[g + 1]) continue;
          const auto [k, i] = who[g];
          auto& x = found[k][i];
          x.first = static_cast<std::uint32_t>(faces[k].size());
          faces[k].insert(faces[k].end(), by_candidate.begin() + static_cast<std::ptrdiff_t>(at[g]),
                          by_candidate.begin() + static_cast<std::ptrdiff_t>(at[g + 1]));
          x.count = static_cast<std::uint32_t>(faces[k].size()) - x.first;
        }
      }
      // the segments of the candidates that encroach nothing, against each face's own box (a
      // segment that meets the face meets its box)
      std::vector<std::uint32_t> open;
      std::vector<sizing::aabb<D>> segments;
      for (std::uint32_t g = 0; l && g < who.size(); ++g)
        if (const auto& x = found[who[g].first][who[g].second]; x.count == 0 && !x.may_leave) {
          open.push_back(g);
          auto box = sizing::aabb<D>::empty();
          box.add(x.c), box.add(x.from);
          segments.push_back(box);
        }
      if (!open.empty()) {
        const box_grid<D> near(segments);
        std::vector<std::vector<std::uint32_t>> leave(pieces.size());  // candidates whose segment may meet a face
        for_each(execution::par(threads), pieces, [&](std::size_t q) {
          for (std::size_t f = q * face_piece; f < std::min(b.faces.size(), (q + 1) * face_piece); ++f) {
            const auto& F = b.faces[f];
            auto box = sizing::aabb<D>::empty();
            for (auto v : F) box.add(bp[v]);
            near.visit(box, [&](std::uint32_t j) {
              const auto& x = found[who[open[j]].first][who[open[j]].second];
              if (may_meet(bp, F, x.from, x.c)) leave[q].push_back(open[j]);
              return true;
            });
          }
        });
        for (const auto& v : leave)
          for (auto g : v) found[who[g].first][who[g].second].may_leave = true;
      }
    }
  }
  // 3D: a bad element that encroaches a boundary face whose circumcentre lies in a guard (an acute
  // vertex's grown ball, a sharp piece's reach) is excepted too, where that guard is, instead of
  // splitting the face: its split point would land where the shells are (as TetGen does not
  // split a subface whose circumcentre lies in a protecting ball; modules/refinement/README.md)
  if constexpr (D == 3) {
    if (!guarded.empty() || !sharp.empty()) {
      auto guard_of = [&](const std::array<vertex_id, 3>& F) -> vertex_id {
        const point<D> u = bp[F[1]] - bp[F[0]], v = bp[F[2]] - bp[F[0]];
        const point<D> n = cross(u, v);
        const double nn = dot(n, n);
        if (!(nn > 0)) return no_vertex;
        const point<D> m = bp[F[0]] + geometry::triangle_circumcentre_offset(u, v, n, nn);
        if (const std::size_t g = near_acute(m); g < guarded.size()) return guarded[g].v;
        if (const std::size_t e = near_sharp(m); e < sharp.size()) return sharp[e].a;
        return no_vertex;
      };
      // each chunk's candidates apart, in parallel (serial, 0.34 s of scad_example009's plans)
      std::vector<std::size_t> chunk_ids(found.size());
      std::iota(chunk_ids.begin(), chunk_ids.end(), std::size_t{0});
      for_each(execution::par(threads), chunk_ids, [&](std::size_t k) {
        std::size_t keep = 0;
        for (std::size_t i = 0; i < found[k].size(); ++i) {
          const auto& x = found[k][i];
          vertex_id where = no_vertex;
          if (x.shape)
            for (std::uint32_t j = 0; j < x.count && where == no_vertex; ++j) where = guard_of(b.faces[faces[k][x.first + j]]);
          if (where != no_vertex) excepted[k].push_back(where);
          else found[k][keep++] = x;
        }
        found[k].resize(keep);
      }, [&](std::size_t k) { return static_cast<double>(found[k].size()); });
    }
  }
  // in order of decreasing circumradius r (ties: by position), each at least `apart` x r from the
  // points taken before it. 3D without small input angles (no acute vertex, no sharp input edge):
  // apart = 0.9, not 1: a circumcentre whose ball holds a point taken before it only in its
  // outer tenth (its cell dies with that insertion) goes in too, where it would otherwise come
  // back as the next round's bad element; the rounds' tail shortened (rotated trench 23 -> 18
  // rounds, the same points within 0.2%; docs/benchmarks.md, eighteenth part). With small angles
  // it lengthened the cascades about them instead (CAD parts of the corpus: occ_chair and
  // gmsh_primitives no longer converged in 60 rounds), so there it stays 1. The insertion radius
  // stays at least apart x r, which for an element above the bound B is more than apart x B x its
  // shortest edge, and apart x B >= 1.1 (the floor below): new edges are longer than the bad
  // element's shortest, as the termination argument of Delaunay refinement needs. 2D
  // (off-centres, Triangle's rule) keeps 1
  const bool no_small_angles = acute_guard > 0 && guarded.empty() && sharp.empty();
  const double apart = D == 3 && no_small_angles ? std::max(0.9, std::min(1.0, 1.1 / bound)) : 1.0;
  struct ref {
    std::uint32_t chunk, index;
  };
  std::vector<ref> all;
  std::set<int> levels;
  // a boundary face's circumcentre (2D: midpoint), in doubles: where the conformer will split
  // it, as far as the choice of splits below needs to know
  auto face_centre = [&](std::size_t f) -> point<D> {
    const auto& F = b.faces[f];
    if constexpr (D == 2) {
      return 0.5 * (bp[F[0]] + bp[F[1]]);
    } else {
      const point<D> u = bp[F[1]] - bp[F[0]], v = bp[F[2]] - bp[F[0]];
      const point<D> n = cross(u, v);
      const double nn = dot(n, n);
      return nn > 0 ? bp[F[0]] + geometry::triangle_circumcentre_offset(u, v, n, nn) : bp[F[0]];
    }
  };
  for (std::uint32_t k = 0; k < found.size(); ++k)
    for (std::uint32_t i = 0; i < found[k].size(); ++i) {
      all.push_back({k, i});
      levels.insert(accepted_points<D>::level(apart * found[k][i].r));
    }
  {
    std::map<vertex_id, std::size_t> at;
    for (const auto& e : excepted)
      for (vertex_id v : e) ++at[v], ++out.excepted;
    out.excepted_near.assign(at.begin(), at.end());
    for (auto n : floored) out.below_floor += n;
  }
  const auto shaped = static_cast<std::size_t>(std::count_if(all.begin(), all.end(), [&](const ref& x) { return found[x.chunk][x.index].shape; }));
  out.bad = out.excepted + shaped;
  out.large = all.size() - shaped;  // the excepted are not in `all`
  auto at = [&](const ref& x) -> const candidate<D>& { return found[x.chunk][x.index]; };
  // (candidates equal in both keys share their circumcentre, and so their encroached faces: their
  // order among themselves changes nothing below)
  gsse::stable_sort(execution::par(threads), all.begin(), all.end(), [&](const ref& x, const ref& y) {
    const auto &a = at(x), &c = at(y);
    if (a.r != c.r) return a.r > c.r;
    return lex_less(a.c, c.c);
  });
  std::vector<std::size_t> split;
  // the points taken before (circumcentres) and, in 3D, the split faces' circumcentres (below), in
  // one index: a candidate asks whether any of either lies within apart x r (one query, not one
  // for each: their queries were a seventh of the rotated trench's serial time, docs/benchmarks.md,
  // forty-ninth part)
  accepted_points<D> taken(p.empty() ? point<D>{} : p[0], levels);
  std::vector<point<D>> added;  // the circumcentres taken, in order
  // 3D: a bad element whose circumcentre encroaches boundary faces asks for their splits only if
  // no point taken before it in the round (a circumcentre, or the circumcentre of a face split for
  // an element before it) lies within `apart` x r of its circumcentre: that point lies in its
  // ball and kills it, as for the circumcentres themselves. (Every such element used to ask, and
  // in a round with thousands of them next to one wall each asked for every face its ball
  // reaches: the rotated trench split 26,850 faces for 7,078 circumcentres.) And where the PLC has
  // no small angles, for one face only (at 1.3 and above the one whose circumcentre is nearest its
  // own; below, see next): as a sequential refinement splits one encroached face and looks at the
  // element again, the others wait for the next round if the element is still there (rotated trench 41,185 -> 36,221
  // points; at --quality 1.2 the MOSFET 51,628 -> 21,129, as many as TetGen's -q1.2). About small
  // angles all of them: there one face a round made the cascades that need many take more rounds
  // (corpus at 1.414: occ_pump_nut 50 -> 59 of its 60, scad_example009 40 -> 57; all of them and
  // the filter alone: the most any input takes fell from 57 to 53). 2D keeps Triangle's rule
  // (every encroached edge split).
  // Which face, below a bound of 1.3: the largest (the greatest radius; ties by face number), not
  // the nearest. Its split point lies farthest from the facet's vertices (its insertion radius is
  // the face's radius), and with the bound close to 1 (apart x B only just above 1.1) the nearest
  // face, often a small one split a round before, was split again and again: at --quality 1.2 the
  // liner walls of the trench ended with twice the points of TetGen's, edges of 0.0074 where its
  // are 0.012, and it did not converge in 250 rounds; with the largest it converges in 66 (43k
  // points), and 5 of the 8 benchmark structures within 60 rounds instead of 3. At 1.3 and above
  // the nearest stays: there the largest made the FinFETs' tails at thin-layer corners longer (1.3:
  // 69 and 133 rounds against 23 and 44) and at 1.414 it gave up to 2% more points
  // (docs/benchmarks.md, twenty-third part)
  const bool filter_splits = D == 3;
  const bool one_face = D == 3 && no_small_angles;
  const bool largest_face = bound < largest_face_below;
  std::vector<char> may_leave;  // per accepted point
  for (const auto& x : all) {
    const auto& c = at(x);
    auto near = [&] { return taken.any_within(c.c, apart * c.r); };
    if (c.count > 0) {
      if (filter_splits && near()) continue;
      std::size_t best = 0;
      point<D> best_at{};
      double closest = std::numeric_limits<double>::infinity();  // the best face's score
      for (std::uint32_t j = 0; j < c.count; ++j) {
        const std::size_t f = faces[x.chunk][c.first + j];
        const point<D> m = filter_splits ? face_centre(f) : point<D>{};
        if (!one_face) {
          split.push_back(f);
          if (filter_splits) taken.add(m);
        } else {
          // the least score: the distance to the element's circumcentre, or minus the radius
          const double score = largest_face ? -squared_distance(m, bp[b.faces[f][0]]) : squared_distance(m, c.c);
          if (score < closest || (largest_face && score == closest && f < best)) closest = score, best = f, best_at = m;
        }
      }
      if (one_face) split.push_back(best), taken.add(best_at);
      continue;
    }
    if (near()) continue;
    taken.add(c.c);
    added.push_back(c.c);
    may_leave.push_back(c.may_leave);
  }
  out.add = std::move(added);
  // a circumcentre outside every segment that encroaches no subfacet (it may lie in a subsegment's
  // ball only, or outside by rounding) is not inserted: the conformer would project a point from
  // the outside, which it never sees otherwise. Its element stays for a later round. Only the
  // points whose segment from their cell's centroid may meet the boundary can be outside: those
  // are located (ray casting), the others lie in their cell's segment
  if (l && !out.add.empty()) {
    std::vector<point<D>> ask;
    for (std::size_t k = 0; k < out.add.size(); ++k)
      if (may_leave[k]) ask.push_back(out.add[k]);
    const auto where = conformer::locate(b, *l, ask);
    std::vector<point<D>> inside;
    for (std::size_t k = 0, j = 0; k < out.add.size(); ++k)
      if (!may_leave[k] || where[j++] != conformer::exterior) inside.push_back(out.add[k]);
    out.outside = out.add.size() - inside.size();
    out.add = std::move(inside);
  }
  gsse::stable_sort(execution::par(threads), split.begin(), split.end());
  split.erase(std::unique(split.begin(), split.end()), split.end());
  out.split = std::move(split);
  return out;
}

namespace {

template <std::size_t D>
using face_t = std::array<vertex_id, D>;

template <std::size_t D>
face_t<D> key_of(face_t<D> f) {
  std::sort(f.begin(), f.end());
  return f;
}

__extension__ typedef unsigned __int128 uint128;
/// A face key (sorted ids) as one integer whose order is the keys' lexicographic order: sorting
/// by it compares two machine words, not arrays element by element.
template <std::size_t D>
using packed_key = std::conditional_t<D == 2, std::uint64_t, uint128>;
template <std::size_t D>
packed_key<D> pack(const face_t<D>& key) {
  packed_key<D> x = 0;
  for (vertex_id v : key) x = (x << 32) | v;
  return x;
}

/// The points [first, end) of `p` in a point grid (nested where they crowd: new points gather
/// where the refinement works), for "which of them lie near this box or ball". Doubles select
/// candidates; exact predicates decide.
template <std::size_t D>
class point_bins {
 public:
  point_bins(const std::vector<point<D>>& p, std::size_t first) {
    const std::size_t m = p.size() > first ? p.size() - first : 0;
    std::vector<vertex_id> ids(m);
    std::iota(ids.begin(), ids.end(), static_cast<vertex_id>(first));
    grid_.build(std::span<const point<D>>(p.data() + first, m), ids);
  }
  /// f(id) for the points in the grid cells meeting [lo, hi]; f returning true stops.
  template <class F>
  bool any(const point<D>& lo, const point<D>& hi, F&& f) const {
    return !grid_.visit_box(lo, hi, [&](vertex_id y, const point<D>&) { return !f(y); });
  }
  /// The same for the cells meeting the ball (c, r).
  template <class F>
  bool any_in_ball(const point<D>& c, double r, F&& f) const {
    return !grid_.visit_ball(c, r, [&](vertex_id y, const point<D>&) { return !f(y); });
  }

 private:
  geometry::point_grid<D> grid_;
};

/// Does the perturbed circumball of the positive cell c hold y? (the front mesher's criterion)
template <std::size_t D>
bool in_ball(const std::vector<point<D>>& p, const cell_t<D>& c, vertex_id y) {
  if constexpr (D == 2)
    return geometry::in_circle_perturbed(p[c[0]], p[c[1]], p[c[2]], p[y]) > 0;
  else
    return geometry::in_sphere_perturbed(p[c[0]], p[c[1]], p[c[2]], p[c[3]], p[y]) > 0;
}

/// The faces of cell c, each oriented to face into it (the front mesher's convention).
template <std::size_t D>
std::array<face_t<D>, D + 1> faces_into(const cell_t<D>& c) {
  std::array<face_t<D>, D + 1> out;
  for (std::size_t i = 0; i <= D; ++i) {
    std::size_t m = 0;
    for (std::size_t j = 0; j <= D; ++j)
      if (j != i) out[i][m++] = c[j];
    if ((D - i) % 2 == 1) std::swap(out[i][0], out[i][1]);
  }
  return out;
}

/// D! times the signed volume of the cone from o over face f (divergence theorem), and of a cell.
template <std::size_t D>
double cone(const std::vector<point<D>>& p, const face_t<D>& f, const point<D>& o) {
  if constexpr (D == 2) {
    const point2 a = p[f[0]] - o, b = p[f[1]] - o;
    return a[0] * b[1] - a[1] * b[0];
  } else {
    return dot(p[f[0]] - o, cross(p[f[1]] - o, p[f[2]] - o));
  }
}
/// A bound on the rounding error of cone(p, f, o) (and, with o = a cell's first vertex and f its
/// other ones, of cell_measure): 16 eps times the product of the edge vectors' 1-norms, far above
/// the few roundings of a D x D determinant of differences.
template <std::size_t D, class Face>
double rounding_bound(const std::vector<point<D>>& p, const Face& f, const point<D>& o) {
  double bound = 16 * std::numeric_limits<double>::epsilon();
  for (std::size_t i = 0; i < D; ++i) {
    double n = 0;
    for (std::size_t k = 0; k < D; ++k) n += std::abs(p[f[i]][k] - o[k]);
    bound *= n;
  }
  return bound;
}
template <std::size_t D>
double cell_measure(const std::vector<point<D>>& p, const cell_t<D>& c) {
  if constexpr (D == 2) {
    const point2 a = p[c[1]] - p[c[0]], b = p[c[2]] - p[c[0]];
    return std::abs(a[0] * b[1] - a[1] * b[0]);
  } else {
    return std::abs(dot(p[c[1]] - p[c[0]], cross(p[c[2]] - p[c[0]], p[c[3]] - p[c[0]])));
  }
}

}  // namespace

template <std::size_t D>
std::vector<cavity_piece<D>> cavity_pieces(const std::vector<point<D>>& p, const std::vector<std::array<vertex_id, D>>& front) {
  constexpr std::uint32_t none = ~std::uint32_t{0};
  // faces sharing a vertex, by union-find over local numbers (a per-thread table over all points,
  // reset after use, not a hash map: rotated trench, this step of the cavities 63 -> 53 ms over
  // its 21 rounds)
  thread_local std::vector<std::uint32_t> local;
  if (local.size() < p.size()) local.resize(p.size(), none);
  std::vector<vertex_id> numbered;
  struct reset {  // on every way out, an exception too: the next call finds the table clean
    std::vector<std::uint32_t>& table;
    const std::vector<vertex_id>& used;
    ~reset() {
      for (vertex_id v : used) table[v] = ~std::uint32_t{0};
    }
  } clean{local, numbered};
  for (const auto& F : front)
    for (auto v : F)
      if (local[v] == none) local[v] = static_cast<std::uint32_t>(numbered.size()), numbered.push_back(v);
  union_find<std::uint32_t> uf(numbered.size());
  for (const auto& F : front)
    for (std::size_t k = 1; k < D; ++k) uf.unite(local[F[0]], local[F[k]]);
  std::vector<std::uint32_t> piece_of(numbered.size(), none);
  std::vector<cavity_piece<D>> pieces;
  for (const auto& F : front) {
    std::uint32_t& at = piece_of[uf.find(local[F[0]])];
    if (at == none) at = static_cast<std::uint32_t>(pieces.size()), pieces.emplace_back();
    pieces[at].faces.push_back(F);
  }
  for (auto& piece : pieces) {
    piece.lo = piece.hi = p[piece.faces[0][0]];
    for (const auto& F : piece.faces)
      for (auto v : F)
        for (std::size_t k = 0; k < D; ++k) piece.lo[k] = std::min(piece.lo[k], p[v][k]), piece.hi[k] = std::max(piece.hi[k], p[v][k]);
  }
  if (pieces.size() < 2) return pieces;
  // an island's faces face out of it: the volume it encloses (divergence theorem, doubles) has
  // the sign opposite to a cavity's, and the piece enclosing the most volume is a cavity (an
  // island lies inside one). Doubles decide no topology here, only what is filled together: a
  // piece misjudged fails its task's checks and the round meshes whole
  std::vector<double> volume(pieces.size(), 0.0);
  std::size_t largest = 0;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const point<D> o = p[pieces[i].faces[0][0]];
    for (const auto& F : pieces[i].faces) volume[i] += cone<D>(p, F, o);
    if (std::abs(volume[i]) > std::abs(volume[largest])) largest = i;
  }
  std::vector<std::size_t> islands, around;
  for (std::size_t i = 0; i < pieces.size(); ++i) (volume[i] * volume[largest] < 0 ? islands : around).push_back(i);
  if (islands.empty()) return pieces;
  union_find<std::uint32_t> groups(pieces.size());
  auto holds = [&](std::size_t outer, std::size_t inner) {
    for (std::size_t k = 0; k < D; ++k)
      if (pieces[outer].lo[k] > pieces[inner].lo[k] || pieces[outer].hi[k] < pieces[inner].hi[k]) return false;
    return true;
  };
  for (std::size_t i : islands)
    for (std::size_t o : around)
      if (holds(o, i)) groups.unite(static_cast<std::uint32_t>(o), static_cast<std::uint32_t>(i));
  std::vector<cavity_piece<D>> merged;
  std::vector<std::uint32_t> slot(pieces.size(), none);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    std::uint32_t& at = slot[groups.find(static_cast<std::uint32_t>(i))];
    if (at == none) {
      at = static_cast<std::uint32_t>(merged.size());
      merged.push_back(std::move(pieces[i]));
      continue;
    }
    auto& m = merged[at];
    m.faces.insert(m.faces.end(), pieces[i].faces.begin(), pieces[i].faces.end());
    for (std::size_t k = 0; k < D; ++k) m.lo[k] = std::min(m.lo[k], pieces[i].lo[k]), m.hi[k] = std::max(m.hi[k], pieces[i].hi[k]);
  }
  return merged;
}

template <std::size_t D>
bool remesh_cavities(const conformer::boundary<D>& b0, const conformer::boundary<D>& b1, const conformer::labelling& l0,
                     const conformer::labelling& l1, cells_by_region<D>& cells, unsigned threads, std::size_t* removed_count,
                     std::size_t* made_count, std::vector<std::vector<char>>* flags, balls_by_region<D>* balls,
                     runs_by_region<D>* kept_runs, std::size_t batch_faces, cavity_fill fill, std::size_t* front_regions) {
  const auto& p = b1.points;
  const std::size_t n0 = b0.points.size();
  if (p.size() < n0 || l0.regions.size() != l1.regions.size() || cells.size() != l1.regions.size()) return false;
  for (std::size_t r = 0; r < l1.regions.size(); ++r)
    if (l0.regions[r].number != l1.regions[r].number) return false;
  // the old points where and what they were (free, on a facet...): then no new cell has only old
  // vertices and wrap_cavity's apex search may read the added points alone for such faces.
  // Checked, not assumed: a free point the conformer claimed for a facet would be new to the
  // segment across it
  bool settled = b0.homes.size() == n0 && b1.homes.size() >= n0;
  for (std::size_t v = 0; settled && v < n0; ++v) settled = b0.points[v] == p[v] && b0.homes[v].kind == b1.homes[v].kind;
  // the boundary faces that went (split) and came. The conformer lists faces source by source
  // (PLC edge or facet), in the same order each round, and a source it did not touch keeps its
  // list: where the runs of sources match, only runs that differ are compared as sets
  auto runs = [](const conformer::boundary<D>& b) {
    std::vector<std::size_t> r;  // starts of the runs of equal sources, then the end
    for (std::size_t f = 0; f < b.face_source.size(); ++f)
      if (f == 0 || b.face_source[f] != b.face_source[f - 1]) r.push_back(f);
    r.push_back(b.face_source.size());
    return r;
  };
  const auto r0 = runs(b0), r1 = runs(b1);
  bool aligned = b0.face_source.size() == b0.faces.size() && b1.face_source.size() == b1.faces.size() && r0.size() == r1.size();
  std::set<std::uint32_t> sources;
  for (std::size_t i = 0; aligned && i + 1 < r0.size(); ++i)
    aligned = b0.face_source[r0[i]] == b1.face_source[r1[i]] && sources.insert(b0.face_source[r0[i]]).second;
  struct pair_of_runs {
    std::size_t a0, e0, a1, e1;
  };
  std::vector<pair_of_runs> differ;
  if (aligned) {
    for (std::size_t i = 0; i + 1 < r0.size(); ++i) {
      const std::size_t a0 = r0[i], e0 = r0[i + 1], a1 = r1[i], e1 = r1[i + 1];
      if (!(e0 - a0 == e1 - a1 && std::equal(b0.faces.begin() + static_cast<long>(a0), b0.faces.begin() + static_cast<long>(e0),
                                             b1.faces.begin() + static_cast<long>(a1), same_vertices<D>)))
        differ.push_back({a0, e0, a1, e1});
    }
  } else {
    differ.push_back({0, b0.faces.size(), 0, b1.faces.size()});
  }
  // each pair of differing runs as sorted key lists, in parallel; results in run order
  std::vector<std::vector<std::size_t>> gone_in(differ.size()), came_in(differ.size());
  std::vector<std::size_t> which(differ.size());
  std::iota(which.begin(), which.end(), std::size_t{0});
  for_each(execution::par(threads), which, [&](std::size_t i) {
    auto [a0, e0, a1, e1] = differ[i];
    // a face in the same place in both lists (a facet wrapped again keeps what no new point
    // disturbed in its place, the new triangles in the dead ones' places, the rest at the end)
    // neither went nor came: a face is listed once, so it is not elsewhere in either list. The
    // common tail first (aligned from the end: a run that grew), then place by place from the
    // start; only the faces left over are compared as sets
    auto same = same_vertices<D>;
    while (a0 < e0 && a1 < e1 && same(b0.faces[e0 - 1], b1.faces[e1 - 1])) --e0, --e1;
    std::vector<std::size_t> old_at, new_at;  // the places left over
    std::vector<face_t<D>> old_keys, new_keys;
    for (std::size_t k = 0; a0 + k < e0 || a1 + k < e1; ++k) {
      const bool in0 = a0 + k < e0, in1 = a1 + k < e1;
      if (in0 && in1 && same(b0.faces[a0 + k], b1.faces[a1 + k])) continue;
      if (in0) old_at.push_back(a0 + k), old_keys.push_back(key_of<D>(b0.faces[a0 + k]));
      if (in1) new_at.push_back(a1 + k), new_keys.push_back(key_of<D>(b1.faces[a1 + k]));
    }
    const key_set<D> old_set(old_keys), new_set(new_keys);
    for (std::size_t j = 0; j < old_at.size(); ++j)
      if (!new_set.contains(old_keys[j])) gone_in[i].push_back(old_at[j]);
    for (std::size_t j = 0; j < new_at.size(); ++j)
      if (!old_set.contains(new_keys[j])) came_in[i].push_back(new_at[j]);
  }, [&](std::size_t i) { return static_cast<double>(differ[i].e0 - differ[i].a0 + differ[i].e1 - differ[i].a1); });
  std::vector<std::size_t> gone_faces, came_faces;
  for (std::size_t i = 0; i < differ.size(); ++i) {
    gone_faces.insert(gone_faces.end(), gone_in[i].begin(), gone_in[i].end());
    came_faces.insert(came_faces.end(), came_in[i].begin(), came_in[i].end());
  }
  // the gone faces' keys in a hash set, and their vertices marked: a face with an unmarked vertex
  // is no gone face, and is not looked up (a bisection in the sorted keys for each face of every
  // cell with three marked vertices was the largest line of the 1e5 trench's cavity search:
  // docs/benchmarks.md, sixty-sixth part)
  std::vector<char> on_gone(p.size(), 0);
  std::vector<face_t<D>> gone_keys;
  gone_keys.reserve(gone_faces.size());
  for (std::size_t f : gone_faces) {
    gone_keys.push_back(key_of<D>(b0.faces[f]));
    for (auto v : b0.faces[f]) on_gone[v] = 1;
  }
  const key_set<D> gone(gone_keys);
  std::vector<face_t<D>>().swap(gone_keys);
  auto is_gone = [&](const face_t<D>& g) {
    for (auto v : g)
      if (!on_gone[v]) return false;
    return gone.contains(key_of<D>(g));
  };
  if (p.size() == n0 && gone_faces.empty() && came_faces.empty()) return true;
  // 3D: the cavities are filled by inserting the new points (cavity_insertion.hpp) where the
  // sources of the faces line up (a gone face's facet is the facet its new faces came from).
  // The search then lists every new point in each dead cell's ball: where each insertion starts
  const bool inserting = D == 3 && fill == cavity_fill::insertion && aligned;
  std::vector<std::pair<packed_key<D>, std::uint32_t>> gone_source;  // (gone face's key, facet), sorted
  std::vector<std::pair<vertex_id, std::uint32_t>> new_on;            // (new point, facet of a new face through it), sorted
  std::vector<char> on_came(p.size() - n0, 0);                        // new point on a new boundary face
  if (inserting) {
    for (std::size_t f : gone_faces) gone_source.push_back({pack<D>(key_of<D>(b0.faces[f])), b0.face_source[f]});
    std::sort(gone_source.begin(), gone_source.end());
    for (std::size_t f : came_faces)
      for (auto v : b1.faces[f])
        if (v >= n0) new_on.push_back({v, b1.face_source[f]}), on_came[v - n0] = 1;
    std::sort(new_on.begin(), new_on.end());
    new_on.erase(std::unique(new_on.begin(), new_on.end()), new_on.end());
  }
  if (flags && flags->size() != cells.size()) return false;
  if (balls && balls->size() != cells.size()) return false;
  // the runs' boxes: the caller's, kept from earlier rounds, or this call's own
  runs_by_region<D> own_runs;
  runs_by_region<D>& cell_runs = kept_runs ? *kept_runs : own_runs;
  cell_runs.resize(cells.size());
  for (std::size_t r = 0; r < cells.size(); ++r) cell_runs[r].resize((cells[r].size() + cell_run - 1) / cell_run);
  // the vertices of the faces that went, by place: a run whose balls' box holds none has no cell
  // resting on such a face
  std::vector<point<D>> gone_at;
  for (std::size_t v = 0; v < p.size(); ++v)
    if (on_gone[v]) gone_at.push_back(p[v]);
  const point_bins<D> gone_bins(gone_at, 0);
  // 1. the cavities: cells whose perturbed ball holds a new point, or that rest on a gone face
  const point_bins<D> bins(p, n0);
  struct chunk {
    std::size_t region, first, count;
  };
  constexpr std::size_t piece = 8192;
  std::vector<chunk> chunks;
  for (std::size_t r = 0; r < cells.size(); ++r)
    for (std::size_t a = 0; a < cells[r].size(); a += piece) chunks.push_back({r, a, std::min(piece, cells[r].size() - a)});
  std::vector<std::vector<char>> dead(cells.size());
  for (std::size_t r = 0; r < cells.size(); ++r) dead[r].assign(cells[r].size(), 0);
  // and each chunk's dead cells, ascending: the steps below read those, not every cell (a late
  // round kills a few hundred of a graded run's million cells)
  std::vector<std::vector<std::uint32_t>> dead_in(chunks.size());
  std::vector<std::vector<std::pair<std::uint32_t, vertex_id>>> hits_in(chunks.size());  // (dead cell, new point in its ball)
  // a cell's circumball, computed the first time it is needed and kept (balls) across rounds
  auto ball_of = [&](std::size_t r, std::size_t i, cell_ball<D>& own) -> cell_ball<D>& {
    cell_ball<D>& ball = balls ? (*balls)[r][i] : own;
    if (ball.pad == cell_ball<D>::unknown) {
      point<D> at;
      double rad;
      const bool round = circumball(p, cells[r][i], at, rad);
      ball = ball_of_cell<D>(round, at, rad);
    }
    return ball;
  };
  for_each(execution::par(threads), chunks, [&](const chunk& ch) {
    auto& died = dead_in[static_cast<std::size_t>(&ch - chunks.data())];
    auto& hits = hits_in[static_cast<std::size_t>(&ch - chunks.data())];
    // runs of cell_run cells (spatial_order makes them lie together): a run with no flat cell and
    // neither a new point nor a vertex of a gone face in the box of its balls has no dead cell
    constexpr std::size_t run = cell_run;  // chunks start at multiples of it
    constexpr std::size_t near_limit = 32;
    std::vector<vertex_id> near;
    for (std::size_t a = ch.first; a < ch.first + ch.count; a += run) {
      const std::size_t e = std::min(a + run, ch.first + ch.count);
      // the run's box (balls padded; a cell's vertices lie in its ball), made when first needed
      auto& R = cell_runs[ch.region][a / run];
      if (!R.valid) {
        R.lo.fill(std::numeric_limits<double>::infinity());
        R.hi.fill(-std::numeric_limits<double>::infinity());
        R.flat = false;
        for (std::size_t i = a; i < e; ++i) {
          cell_ball<D> own;
          const auto& ball = ball_of(ch.region, i, own);
          if (ball.pad == cell_ball<D>::flat) {
            R.flat = true;
            continue;
          }
          for (std::size_t k = 0; k < D; ++k)
            R.lo[k] = std::min(R.lo[k], ball.at[k] - ball.pad), R.hi[k] = std::max(R.hi[k], ball.at[k] + ball.pad);
        }
        R.valid = true;
      }
      // the new points in the run's box: a cell's ball lies in the box, so they are the only ones
      // it can hold (a short list read per cell; the grid only when the box holds many)
      near.clear();
      bool many = false;
      if (p.size() > n0)
        bins.any(R.lo, R.hi, [&](vertex_id y) {
          for (std::size_t k = 0; k < D; ++k)
            if (p[y][k] < R.lo[k] || p[y][k] > R.hi[k]) return false;
          near.push_back(y);
          many = near.size() > near_limit;
          return many;
        });
      const bool look = R.flat || !near.empty() || (!gone_at.empty() && gone_bins.any(R.lo, R.hi, [&](vertex_id y) {
               for (std::size_t k = 0; k < D; ++k)
                 if (gone_at[y][k] < R.lo[k] || gone_at[y][k] > R.hi[k]) return false;
               return true;
             }));
      if (!look) continue;
      for (std::size_t i = a; i < e; ++i) {
        cell_t<D> c = cells[ch.region][i];
        char& out = dead[ch.region][i];
        std::size_t marked = 0;
        for (auto v : c) marked += on_gone[v];
        if (marked >= D)
          for (const auto& g : faces_into<D>(c))
            if (is_gone(g)) {
              out = 1;
              break;
            }
        // (3D insertion) the new points in the ball of a cell that dies anyway, by exact tests
        // alone: all of them for a flat cell, those on new boundary faces for one on a gone face
        // (where their insertions start: a free point's cavity has cells of its own)
        auto exact_hits = [&](bool boundary_only) {
          if constexpr (D == 3) {
            bool oriented = false;
            auto test = [&](vertex_id y) {
              if (boundary_only && !on_came[y - n0]) return false;
              if (!oriented) {
                if (geometry::orient3d(p[c[0]], p[c[1]], p[c[2]], p[c[3]]) < 0) std::swap(c[0], c[1]);
                oriented = true;
              }
              if (in_ball(p, c, y)) hits.push_back({static_cast<std::uint32_t>(i), y});
              return false;
            };
            if (many)
              bins.any(R.lo, R.hi, test);
            else
              for (vertex_id y : near) test(y);
          }
        };
        const bool on_gone_face = out;
        if ((out && !inserting) || p.size() == n0) continue;
        cell_ball<D> own;
        const auto& ball = ball_of(ch.region, i, own);
        if (ball.pad == cell_ball<D>::flat) {
          out = 1;  // flat in double precision: re-meshed, which is always safe
          if (inserting) exact_hits(on_gone_face);
          continue;
        }
        const point<D>& at = ball.at;
        const double pad = ball.pad;
        // well inside: at least 1e-6 of the radius inside the padded ball shrunk by twice its
        // padding (the exact test's answer, perturbation or not: docs/design-decisions.md, "A
        // double test may skip an exact one only where its error is bounded")
        double m = 0;
        for (double x : at) m = std::max(m, std::abs(x));
        const double inner = std::max(0.0, pad * (1 - 1e-6) - 256 * std::numeric_limits<double>::epsilon() * (m + pad));
        bool oriented = false;
        auto holds = [&](vertex_id y) {
          const double d2 = squared_distance(p[y], at);
          if (d2 > pad * pad) return false;
          if (d2 < inner * inner) return true;
          if (!oriented) {
            int o;
            if constexpr (D == 2)
              o = geometry::orient2d(p[c[0]], p[c[1]], p[c[2]]);
            else
              o = geometry::orient3d(p[c[0]], p[c[1]], p[c[2]], p[c[3]]);
            if (o < 0) std::swap(c[0], c[1]);
            oriented = true;
          }
          return in_ball(p, c, y);
        };
        if (inserting) {  // every new point in the ball
          auto note = [&](vertex_id y) {
            if (on_gone_face && !on_came[y - n0]) return false;
            if (holds(y)) out = 1, hits.push_back({static_cast<std::uint32_t>(i), y});
            return false;
          };
          if (many)
            bins.any_in_ball(at, pad, note);
          else
            for (vertex_id y : near) note(y);
        } else if (many) {
          out = bins.any_in_ball(at, pad, holds);
        } else {
          out = 0;
          for (vertex_id y : near)
            if (holds(y)) {
              out = 1;
              break;
            }
        }
      }
      for (std::size_t i = a; i < e; ++i)
        if (dead[ch.region][i]) died.push_back(static_cast<std::uint32_t>(i));
    }
  }, [&](const chunk& ch) { return static_cast<double>(ch.count); });
  std::vector<std::vector<std::uint32_t>> dead_at(cells.size());  // per region, ascending
  std::vector<std::vector<std::pair<std::uint32_t, vertex_id>>> hits_at(cells.size());  // per region, by cell
  for (std::size_t k = 0; k < chunks.size(); ++k) {
    dead_at[chunks[k].region].insert(dead_at[chunks[k].region].end(), dead_in[k].begin(), dead_in[k].end());
    hits_at[chunks[k].region].insert(hits_at[chunks[k].region].end(), hits_in[k].begin(), hits_in[k].end());
  }
  std::vector<std::vector<std::uint32_t>>().swap(dead_in);
  std::vector<std::vector<std::pair<std::uint32_t, vertex_id>>>().swap(hits_in);
  // 2. each region's cavity boundary: the faces of its dead cells met once, less the gone faces,
  // plus the new boundary faces on its side
  // the points a cavity can use, by place: the vertices of the dead cells (the cavity's boundary
  // vertices and any old vertex inside it, all of whose cells died) and the new points; an old
  // point outside every cavity is never an apex there (the fill is Delaunay), and a grid of these
  // alone follows the round's work, not the mesh's size (a late round re-fills a few cavities)
  std::vector<char> usable(p.size(), 0);
  for (std::size_t r = 0; r < cells.size(); ++r)
    for (const auto i : dead_at[r])
      for (auto v : cells[r][i]) usable[v] = 1;
  std::vector<vertex_id> usable_ids;
  std::vector<point<D>> usable_at;
  for (std::size_t v = 0; v < p.size(); ++v)
    if (usable[v] || v >= n0) usable_ids.push_back(static_cast<vertex_id>(v)), usable_at.push_back(p[v]);
  const front::point_grid<D> grid(usable_at, usable_ids);
  point<D> all_lo = p[0], all_hi = p[0];
  for (const auto& q : p)
    for (std::size_t k = 0; k < D; ++k) all_lo[k] = std::min(all_lo[k], q[k]), all_hi[k] = std::max(all_hi[k], q[k]);
  struct task {
    std::size_t region;
    std::vector<face_t<D>> front;
    std::vector<std::pair<point<D>, point<D>>> boxes;  // the bounding box of each piece's front
    std::optional<std::vector<cell_t<D>>> inserted;    // the cells, where insertion filled the region
  };
  // per region, in parallel: its tasks, or a failure (the cavities do not close)
  struct region_tasks {
    std::vector<task> tasks;
    std::size_t removed = 0;
    bool ok = true;
    // for insertion: each dead cell's face i (place 4 k + i) across from the dead cell's face that
    // meets it, or none; the dead cells in connected pieces (cavities), each cell's place in its
    // piece; the new boundary faces on the region's side, facing into it, and their new points
    bool insertable = false;
    std::vector<std::uint32_t> mate, place;
    std::vector<std::pair<std::size_t, std::size_t>> hits_of;  // per dead cell: its hits, [begin, end)
    std::vector<std::vector<std::uint32_t>> components;
    std::vector<face_t<D>> came;
    std::vector<vertex_id> came_points;
    std::vector<std::pair<packed_key<D>, face_t<D>>> met;  // (key, face facing into the dead cell)
    std::vector<char> twice;                               // per face of met: met twice (inside)
  };
  std::vector<region_tasks> by_region(cells.size());
  // the boundary faces with one region on both sides (a facet inside a segment), by region, before
  // and after: the cavity keeps both sides of such a face apart (both its dead cells' faces are
  // on the cavity's boundary, facing away from each other), as meshing the segment whole does
  std::vector<std::vector<packed_key<D>>> inner0(cells.size()), inner1(cells.size());
  for (std::size_t f = 0; f < b0.faces.size() && f < l0.side.size(); ++f)
    if (const int r = l0.side[f][0]; r >= 0 && r == l0.side[f][1] && static_cast<std::size_t>(r) < cells.size())
      inner0[static_cast<std::size_t>(r)].push_back(pack<D>(key_of<D>(b0.faces[f])));
  for (std::size_t f = 0; f < b1.faces.size() && f < l1.side.size(); ++f)
    if (const int r = l1.side[f][0]; r >= 0 && r == l1.side[f][1] && static_cast<std::size_t>(r) < cells.size())
      inner1[static_cast<std::size_t>(r)].push_back(pack<D>(key_of<D>(b1.faces[f])));
  for (auto& v : inner0) std::sort(v.begin(), v.end());
  for (auto& v : inner1) std::sort(v.begin(), v.end());
  std::vector<std::size_t> regions(cells.size());
  std::iota(regions.begin(), regions.end(), std::size_t{0});
  // the parity of the permutation that sorts a face: faces with one key and one parity face the
  // same way
  auto parity = [](const face_t<D>& f) {
    int n = 0;
    for (std::size_t i = 0; i < D; ++i)
      for (std::size_t j = i + 1; j < D; ++j) n += f[i] > f[j];
    return n % 2;
  };
  using oriented_key = std::pair<packed_key<D>, int>;
  auto oriented = [&](const face_t<D>& f) { return oriented_key{pack<D>(key_of<D>(f)), parity(f)}; };
  // a region's front (the faces of its dead cells met once, less the gone faces, plus the new
  // boundary faces on its side) in connected pieces, batched into tasks for the front mesher.
  // `only`, for a region insertion filled but for some cavities: the dead cells of those (by
  // place in the region's dead cells), whose front is theirs alone (cavities share no face), and
  // `rest`: the new boundary faces the other cavities did not end with, theirs (sorted)
  auto make_front = [&](std::size_t r, const std::vector<char>* only = nullptr, const std::vector<oriented_key>* rest = nullptr) {
    auto& W = by_region[r];
    const auto met = std::move(W.met);
    const auto twice = std::move(W.twice);
    std::vector<std::pair<packed_key<D>, face_t<D>>> once;
    for (std::uint32_t i = 0; i < met.size(); ++i)
      if (!twice[i] && (!only || (*only)[i / (D + 1)])) once.push_back(met[i]);
    std::sort(once.begin(), once.end(), [](const auto& x, const auto& y) { return x.first < y.first || (x.first == y.first && x.second < y.second); });
    std::vector<std::pair<face_t<D>, face_t<D>>> open;  // sorted by key
    open.reserve(once.size());
    for (const auto& [k, g] : once) open.push_back({key_of<D>(g), g});
    std::vector<char> gone_here(open.size(), 0);
    for (std::size_t f : gone_faces)
      for (int side = 0; side < 2; ++side)
        if (l0.side[f][static_cast<std::size_t>(side)] == static_cast<int>(r)) {
          const auto key = key_of<D>(b0.faces[f]);
          auto it = std::lower_bound(open.begin(), open.end(), key, [](const auto& x, const face_t<D>& k) { return x.first < k; });
          // a face with the region on both sides is there twice, once facing each way
          while (it != open.end() && it->first == key && gone_here[static_cast<std::size_t>(it - open.begin())]) ++it;
          if (it == open.end() || it->first != key) {
            if (only) continue;  // a face a filled cavity's cell rested on
            W.ok = false;
            return;
          }
          gone_here[static_cast<std::size_t>(it - open.begin())] = 1;
        }
    std::vector<std::pair<face_t<D>, face_t<D>>> keyed;
    for (std::size_t i = 0; i < open.size(); ++i)
      if (!gone_here[i]) keyed.push_back(open[i]);
    const std::size_t kept = keyed.size();
    std::vector<char> rest_taken(rest ? rest->size() : 0, 0);
    for (std::size_t f : came_faces)
      for (int side = 0; side < 2; ++side)
        if (l1.side[f][static_cast<std::size_t>(side)] == static_cast<int>(r)) {
          auto F = b1.faces[f];
          if (side == 1) std::swap(F[0], F[1]);
          if (rest) {  // one of `rest`, not taken yet
            const auto o = oriented(F);
            auto it = std::lower_bound(rest->begin(), rest->end(), o);
            while (it != rest->end() && *it == o && rest_taken[static_cast<std::size_t>(it - rest->begin())]) ++it;
            if (it == rest->end() || *it != o) continue;
            rest_taken[static_cast<std::size_t>(it - rest->begin())] = 1;
          }
          keyed.push_back({key_of<D>(F), F});
        }
    std::sort(keyed.begin() + static_cast<long>(kept), keyed.end());
    std::inplace_merge(keyed.begin(), keyed.begin() + static_cast<long>(kept), keyed.end());
    for (std::size_t i = 1; i < keyed.size(); ++i)
      if (keyed[i].first == keyed[i - 1].first &&
          !(parity(keyed[i].second) != parity(keyed[i - 1].second) && (i < 2 || keyed[i - 2].first != keyed[i].first) &&
            std::binary_search(inner1[r].begin(), inner1[r].end(), pack<D>(keyed[i].first)))) {
        W.ok = false;  // a new boundary face where the cavity's boundary has one already (a face
                       // with the region on both sides is there twice, once facing each way)
        return;
      }
    if (keyed.empty()) return;
    std::vector<face_t<D>> front;
    front.reserve(keyed.size());
    for (const auto& [k, F] : keyed) front.push_back(F);
    // connected pieces, an island with the piece around it (cavity_pieces), batched into tasks of
    // about batch_faces faces (4096): a task is a union of closed fronts, so the front mesher
    // fills each. The
    // pieces in the order of the cell of a 1024^D lattice over the points (Morton order) that
    // holds their box's centre, then of their first face: a task's pieces lie together
    const auto pieces = cavity_pieces<D>(p, front);
    std::vector<std::pair<std::uint64_t, std::size_t>> order(pieces.size());
    for (std::size_t i = 0; i < pieces.size(); ++i) order[i] = {morton_code<D>(0.5 * (pieces[i].lo + pieces[i].hi), all_lo, all_hi, 10), i};
    std::sort(order.begin(), order.end());
    for (auto [m, i] : order) {
      if (W.tasks.empty() || W.tasks.back().front.size() >= batch_faces) W.tasks.push_back({r, {}, {}, {}});
      W.tasks.back().front.insert(W.tasks.back().front.end(), pieces[i].faces.begin(), pieces[i].faces.end());
      W.tasks.back().boxes.push_back({pieces[i].lo, pieces[i].hi});
    }
  };
  for_each(execution::par(threads), regions, [&](std::size_t r) {
    auto& W = by_region[r];
    // the faces of the dead cells, by key: a face met twice (by two dead cells, facing opposite
    // ways) is inside the cavity, once is on its boundary
    // (in slices, in parallel: a region is often the whole model, and these steps were a serial
    // second of scad_example009's rounds; docs/benchmarks.md, sixty-eighth part)
    const std::size_t nd = dead_at[r].size();
    W.removed += nd;
    constexpr std::size_t slice = 4096;
    std::vector<std::size_t> slices((nd + slice - 1) / slice);
    std::iota(slices.begin(), slices.end(), std::size_t{0});
    std::vector<std::pair<packed_key<D>, face_t<D>>> met((D + 1) * nd);  // (key, face facing into the dead cell)
    for_each(execution::par(threads), slices, [&](std::size_t q) {
      for (std::size_t k = q * slice; k < std::min(nd, (q + 1) * slice); ++k) {
        const auto fs = faces_into<D>(cells[r][dead_at[r][k]]);
        for (std::size_t i = 0; i <= D; ++i) met[(D + 1) * k + i] = {pack<D>(key_of<D>(fs[i])), fs[i]};
      }
    });
    // faces paired by key in open-addressing tables (sorting every face by key was most of this
    // step); those met once are sorted by key: the cavity's boundary. The faces go to 2^bits
    // parts by their hash's top bits, each part paired on its own, in parallel: a key's faces all
    // go to one part in their order, and what the pairing finds for a key depends on those alone
    constexpr std::uint32_t none = ~std::uint32_t{0};
    const auto m = static_cast<std::uint32_t>(met.size());
    std::vector<std::uint64_t> hashed(m);
    const std::vector<std::size_t> face_slices = [&] {
      std::vector<std::size_t> v((m + slice - 1) / slice);
      std::iota(v.begin(), v.end(), std::size_t{0});
      return v;
    }();
    for_each(execution::par(threads), face_slices, [&](std::size_t q) {
      for (std::size_t i = q * slice; i < std::min<std::size_t>(m, (q + 1) * slice); ++i) {
        const packed_key<D> k = met[i].first;
        std::uint64_t h = static_cast<std::uint64_t>(k);
        if constexpr (D == 3) h ^= static_cast<std::uint64_t>(k >> 64) * 0xC2B2AE3D27D4EB4Full;
        hashed[i] = h * 0x9E3779B97F4A7C15ull;
      }
    });
    const int bits = m < (1u << 16) ? 0 : 6;
    const std::size_t parts = std::size_t{1} << bits;
    auto part_of = [&](std::uint32_t i) { return bits == 0 ? std::size_t{0} : static_cast<std::size_t>(hashed[i] >> (64 - bits)); };
    // each part's faces, ascending: counted per slice, then placed
    std::vector<std::uint32_t> by_part(m);
    std::vector<std::size_t> part_at(parts + 1, 0);
    {
      std::vector<std::vector<std::uint32_t>> counts(face_slices.size(), std::vector<std::uint32_t>(parts, 0));
      for_each(execution::par(threads), face_slices, [&](std::size_t q) {
        for (std::size_t i = q * slice; i < std::min<std::size_t>(m, (q + 1) * slice); ++i) ++counts[q][part_of(static_cast<std::uint32_t>(i))];
      });
      std::vector<std::vector<std::size_t>> next(face_slices.size(), std::vector<std::size_t>(parts));
      std::size_t at = 0;
      for (std::size_t g = 0; g < parts; ++g) {
        part_at[g] = at;
        for (std::size_t q = 0; q < face_slices.size(); ++q) next[q][g] = at, at += counts[q][g];
      }
      part_at[parts] = at;
      for_each(execution::par(threads), face_slices, [&](std::size_t q) {
        for (std::size_t i = q * slice; i < std::min<std::size_t>(m, (q + 1) * slice); ++i) by_part[next[q][part_of(static_cast<std::uint32_t>(i))]++] = static_cast<std::uint32_t>(i);
      });
    }
    std::vector<char> twice(m, 0);
    if (inserting) W.mate.assign(m, none);
    std::vector<char> part_failed(parts, 0);
    std::vector<std::size_t> part_ids(parts);
    std::iota(part_ids.begin(), part_ids.end(), std::size_t{0});
    for_each(execution::par(threads), part_ids, [&](std::size_t g) {
      const std::size_t first = part_at[g], count = part_at[g + 1] - first;
      std::size_t cap = 16;
      while (cap < 2 * count) cap *= 2;
      std::vector<std::uint32_t> table(cap, none);
      for (std::size_t x = first; x < first + count; ++x) {
        const std::uint32_t i = by_part[x];
        const packed_key<D> k = met[i].first;
        std::size_t at = static_cast<std::size_t>(hashed[i] >> 20) & (cap - 1);
        for (;; at = (at + 1) & (cap - 1)) {
          const std::uint32_t j = table[at];
          if (j == none) {
            table[at] = i;
            break;
          }
          if (met[j].first != k) continue;
          if (!inner0[r].empty() && std::binary_search(inner0[r].begin(), inner0[r].end(), k)) {
            if (parity(met[j].second) == parity(met[i].second)) {
              part_failed[g] = 1;  // two dead cells on one side of a face
              return;
            }
            break;  // both sides stay on the cavity's boundary
          }
          if (twice[j] || parity(met[j].second) == parity(met[i].second)) {
            part_failed[g] = 1;  // two dead cells on one side of a face
            return;
          }
          twice[j] = twice[i] = 1;
          if (inserting) W.mate[i] = j, W.mate[j] = i;
          break;
        }
      }
    }, [&](std::size_t g) { return static_cast<double>(part_at[g + 1] - part_at[g]); });
    if (std::find(part_failed.begin(), part_failed.end(), 1) != part_failed.end()) {
      W.ok = false;
      return;
    }
    if (inserting && inner0[r].empty() && inner1[r].empty()) {  // the cavities: dead cells meeting at faces
      W.insertable = true;
      const auto n = static_cast<std::uint32_t>(dead_at[r].size());
      union_find<std::uint32_t> uf(n);
      for (std::uint32_t i = 0; i < met.size(); ++i)
        if (W.mate[i] != none && W.mate[i] > i) uf.unite(i / (D + 1), W.mate[i] / (D + 1));
      std::vector<std::uint32_t> numbered(n, none);  // by root: the component's number
      W.place.assign(n, 0);
      for (std::uint32_t k = 0; k < n; ++k) {
        std::uint32_t& at = numbered[uf.find(k)];
        if (at == none) at = static_cast<std::uint32_t>(W.components.size()), W.components.emplace_back();
        W.place[k] = static_cast<std::uint32_t>(W.components[at].size());
        W.components[at].push_back(k);
      }
      // each dead cell's run of the region's hits (both lists ascend by cell): read directly by
      // the insertion below, where a bisection per cell was
      const auto& hr = hits_at[r];
      W.hits_of.resize(n);
      for (std::size_t k = 0, h = 0; k < n; ++k) {
        const std::uint32_t i = dead_at[r][k];
        while (h < hr.size() && hr[h].first < i) ++h;
        const std::size_t a = h;
        while (h < hr.size() && hr[h].first == i) ++h;
        W.hits_of[k] = {a, h};
      }
    }
    if (W.insertable) {  // the new boundary faces on its side, facing into it, and their new points
      for (std::size_t f : came_faces)
        for (int side = 0; side < 2; ++side)
          if (l1.side[f][static_cast<std::size_t>(side)] == static_cast<int>(r)) {
            auto F = b1.faces[f];
            if (side == 1) std::swap(F[0], F[1]);
            W.came.push_back(F);
            for (auto v : F)
              if (v >= n0) W.came_points.push_back(v);
          }
      std::sort(W.came_points.begin(), W.came_points.end());
      W.came_points.erase(std::unique(W.came_points.begin(), W.came_points.end()), W.came_points.end());
    }
    W.met = std::move(met);
    W.twice = std::move(twice);
    if (!W.insertable) make_front(r);
  }, [&](std::size_t r) { return static_cast<double>(cells[r].size()); });
  for (const auto& W : by_region)
    if (!W.ok) return false;
  std::vector<std::size_t> unfilled;  // the regions insertion did not fill
  // 3. (3D) insertion: each cavity (connected dead cells of a region) takes the new points that lie
  // in it, and the new points on the region's new boundary faces that its balls hold, one at a
  // time (cavity_insertion.hpp). A region whose cavities do not end with exactly the new boundary
  // faces the conformer made on its side, or where any insertion of a point inside failed, goes
  // to the front mesher below
  if constexpr (D == 3) {
    if (inserting) {
      struct job {
        std::size_t region, component;
      };
      std::vector<job> jobs;
      for (std::size_t r = 0; r < cells.size(); ++r)
        if (by_region[r].insertable)
          for (std::size_t k = 0; k < by_region[r].components.size(); ++k) jobs.push_back({r, k});
      struct result {
        std::vector<cell_t<D>> cells;
        std::vector<face_t<D>> walls;  // the droppable walls left: new boundary faces
        bool ok = true;
      };
      std::vector<result> results(jobs.size());
      for_each(execution::par(threads), jobs, [&](const job& jb) {
        auto& out = results[static_cast<std::size_t>(&jb - jobs.data())];
        const auto& W = by_region[jb.region];
        const auto& dr = dead_at[jb.region];
        const auto& K = W.components[jb.component];
        std::vector<insertion::cell> cs(K.size());
        std::vector<std::array<std::int32_t, 4>> nb(K.size());
        for (std::size_t x = 0; x < K.size(); ++x) {
          const auto k = K[x];
          cs[x] = cells[jb.region][dr[k]];
          if (geometry::orient3d(p[cs[x][0]], p[cs[x][1]], p[cs[x][2]], p[cs[x][3]]) <= 0) {
            out.ok = false;
            return;
          }
          for (int i = 0; i < 4; ++i) {
            const std::uint32_t m = W.mate[k * 4 + static_cast<std::uint32_t>(i)];
            std::int32_t& n = nb[x][static_cast<std::size_t>(i)];
            if (m != ~std::uint32_t{0}) {
              n = static_cast<std::int32_t>(W.place[m / 4]);
            } else {
              n = insertion::fixed;
              if (const auto g = insertion::face_of(cs[x], i); is_gone(g)) {
                const auto key = pack<D>(key_of<D>(g));
                const auto it = std::lower_bound(gone_source.begin(), gone_source.end(), std::pair{key, std::uint32_t{0}});
                if (it != gone_source.end() && it->first == key) n = insertion::droppable(it->second);
              }
            }
          }
        }
        const auto walls_of = nb;  // for a second try (below)
        insertion::cavity cav(std::span<const point<D>>(p), cs, std::move(nb));
        // the points: those on the region's new boundary faces first (kind 0), then free ones
        // (kind 1), each with the cells whose balls held it (walks start there), by id
        // placed by counting: a first pass counts each (kind, point)'s entries, the second puts
        // them in their runs in cell order, the order a sort of the pairs gives, in one array the
        // size of the list (a torus's first round: 13 million hits, which std::sort took 1.2 s
        // over and a radix sort doubled in memory)
        std::vector<std::pair<std::uint64_t, std::uint32_t>> todo;  // ((kind, point), cell)
        const auto& hr = hits_at[jb.region];
        const std::size_t fresh_points = p.size() - n0;
        // per (kind, point) slot, its count then its run's start: a buffer per thread, all zero
        // between cavities (only the slots this cavity touched are counted and cleared, so a
        // round of many small cavities does not fill and sum the whole range for each)
        thread_local std::vector<std::size_t> run_at;
        if (run_at.size() < 2 * fresh_points) run_at.resize(2 * fresh_points, 0);
        std::vector<std::size_t> touched;
        auto each_hit = [&](auto&& f) {
          for (std::size_t x = 0; x < K.size(); ++x) {  // K ascends, and so do its cells' indices
            const auto [from, to] = W.hits_of[K[x]];
            for (std::size_t h = from; h < to; ++h) {
              const vertex_id y = hr[h].second;
              if (!on_came[y - n0])
                f(fresh_points + (y - n0), (std::uint64_t{1} << 32) | y, static_cast<std::uint32_t>(x));
              else if (std::binary_search(W.came_points.begin(), W.came_points.end(), y))
                f(y - n0, std::uint64_t{y}, static_cast<std::uint32_t>(x));
            }
          }
        };
        each_hit([&](std::size_t slot, std::uint64_t, std::uint32_t) {
          if (run_at[slot]++ == 0) touched.push_back(slot);
        });
        std::sort(touched.begin(), touched.end());
        std::size_t total = 0;
        for (std::size_t slot : touched) total += std::exchange(run_at[slot], total);
        todo.resize(total);
        each_hit([&](std::size_t slot, std::uint64_t key, std::uint32_t x) { todo[run_at[slot]++] = {key, x}; });
        for (std::size_t slot : touched) run_at[slot] = 0;
        std::vector<std::uint32_t> hints(todo.size());
        for (std::size_t k = 0; k < todo.size(); ++k) hints[k] = todo[k].second;
        std::vector<std::pair<std::size_t, std::size_t>> pending;  // each point's run of todo
        for (std::size_t a = 0, e = 0; a < todo.size(); a = e) {
          for (e = a; e < todo.size() && todo[e].first == todo[a].first; ++e) {
          }
          pending.push_back({a, e});
        }
        // a point may wait for another: one on a facet whose balls meet a face another point
        // on a neighbouring facet removes. Passes until one inserts nothing (a free point no cell
        // here holds lies in another segment: dropped)
        std::vector<std::pair<std::size_t, std::size_t>> later;
        bool cut = false;
        auto passes = [&](bool cutting) {
          for (bool progress = true; progress && !pending.empty();) {
            progress = false;
            later.clear();
            for (const auto& [a, e] : pending) {
              const auto y = static_cast<vertex_id>(todo[a].first);
              const bool free = todo[a].first >> 32;
              const auto on = [&](std::uint32_t s) { return std::binary_search(new_on.begin(), new_on.end(), std::pair{y, s}); };
              const std::span<const std::uint32_t> at = std::span<const std::uint32_t>(hints).subspan(a, e - a);
              if (cav.insert(y, at, free, on)) {
                progress = true;
              } else if (cav.outside) {
                continue;
              } else if (cutting && !free && cav.insert(y, at, free, on, true)) {
                progress = cut = true;
              } else {
                later.push_back({a, e});
              }
            }
            std::swap(pending, later);
          }
        };
        const auto every_point = pending;
        passes(false);
        // points on new boundary faces that wait for each other: a split point of an input edge
        // whose conflict region meets, from behind, a face of a third facet made through an
        // earlier point, which another such point would replace, and that one waits for a wall
        // the first would remove (a cycle about a vertex of a curved surface; docs/benchmarks.md,
        // sixty-third part). They go in with their conflict regions cut back to what they see;
        // a cell a point's cut left may then hold a later point in its ball, and Lawson's flips
        // mend that (cavity::flip_to_delaunay): the cavity must end Delaunay across every face
        // between its cells (gmsh_revolve at --quality 1.414 from a boundary of Delaunay faces
        // left one cavity to the front mesher without the flips; docs/benchmarks.md,
        // seventy-third part)
        passes(true);
        if (cut && !cav.flip_to_delaunay()) {
          // once more from the start, the points on new boundary faces in the opposite order (the
          // free ones after them as before): which of the waiting points goes in with its region
          // cut back depends on the order, and another choice can leave the cavity Delaunay
          // (gmsh_piece and gmsh_revolve at --quality 1.414 each had one cavity left to the front
          // mesher after the conformer's smooth-surface rule; docs/benchmarks.md, sixty-ninth part)
          cav = insertion::cavity(std::span<const point<D>>(p), cs, walls_of);
          pending.clear();
          for (auto it = every_point.rbegin(); it != every_point.rend(); ++it)
            if (!(todo[it->first].first >> 32)) pending.push_back(*it);
          for (const auto& r : every_point)
            if (todo[r.first].first >> 32) pending.push_back(r);
          cut = false;
          passes(false);
          passes(true);
          if (cut && !cav.flip_to_delaunay()) {
            out.ok = false;
            return;
          }
        }
        // a free point left fails the cavity; a point on a new boundary face whose balls this
        // cavity holds may lie on another's side (the region's walls tell)
        for (const auto& [a, e] : pending)
          if (todo[a].first >> 32) {
            out.ok = false;
            return;
          }
        out.cells = cav.cells();
        out.walls = cav.droppable_walls();
      }, [&](const job& jb) { return static_cast<double>(by_region[jb.region].components[jb.component].size()); });
      // each region: every cavity filled, and the walls left exactly the new boundary faces. Or
      // some cavities not (their insertion failed), and the others' walls among the new boundary
      // faces: those cavities alone go to the front mesher, with the new boundary faces left
      // (one cavity of scad_example009 sent the whole model to the front mesher in 13 rounds;
      // docs/benchmarks.md, sixty-eighth part)
      std::vector<char> filled(cells.size(), 0), partly(cells.size(), 0);
      std::vector<std::vector<oriented_key>> rest(cells.size());
      std::vector<std::pair<std::size_t, std::size_t>> jobs_of(cells.size(), {0, 0});
      std::vector<std::size_t> checked;  // the insertable regions
      for (std::size_t r = 0, j = 0; r < cells.size(); ++r) {
        if (!by_region[r].insertable) continue;
        const std::size_t first = j;
        while (j < jobs.size() && jobs[j].region == r) ++j;
        jobs_of[r] = {first, j};
        checked.push_back(r);
      }
      // in parallel over the regions (each sorts its own lists: serial, these sorts were the
      // second largest symbol of a 2-thread trench run's serial samples, about 1% of its time)
      for_each(execution::par(threads), checked, [&](std::size_t r) {
        bool good = true;
        std::vector<std::pair<packed_key<D>, int>> left, want;
        for (std::size_t j = jobs_of[r].first; j < jobs_of[r].second; ++j) {
          good = good && results[j].ok;
          for (const auto& f : results[j].walls) left.push_back(oriented(f));
        }
        for (const auto& f : by_region[r].came) want.push_back(oriented(f));
        std::sort(left.begin(), left.end());
        std::sort(want.begin(), want.end());
        filled[r] = good && left == want;
        bool some = false;  // a cavity filled
        for (std::size_t j = jobs_of[r].first; j < jobs_of[r].second && !some; ++j) some = results[j].ok;
        if (!good && some && std::includes(want.begin(), want.end(), left.begin(), left.end())) {
          partly[r] = 1;
          std::set_difference(want.begin(), want.end(), left.begin(), left.end(), std::back_inserter(rest[r]));
        }
      }, [&](std::size_t r) { return static_cast<double>(by_region[r].came.size()); });
      // every free new point in a cell of a filled region, or held by a ball of a region the
      // front mesher fills (its own, as far as this round can tell): else that point was left out
      // (all its cells' balls were only tested for points on new faces) and the front mesher
      // fills every region
      std::vector<char> placed(p.size() - n0, 0);
      for (std::size_t r = 0; r < cells.size(); ++r) {
        if (partly[r]) {
          // a free point lies in the cavity whose cell holds it, and that cell's ball holds it:
          // one that a filled cavity's balls held but that cavity left out, and that a cavity of
          // the front mesher's may hold, is not known to be placed: then the front mesher fills
          // the whole region, as before
          std::vector<char> seen(p.size() - n0, 0);  // 1: inserted, 2: held by a filled cavity, 4: by another
          const auto& W = by_region[r];
          for (std::size_t k = jobs_of[r].first; k < jobs_of[r].second; ++k) {
            for (const auto& c : results[k].cells)
              for (auto v : c)
                if (v >= n0) seen[v - n0] |= 1;
            for (const auto x : W.components[jobs[k].component])
              for (std::size_t h = W.hits_of[x].first; h < W.hits_of[x].second; ++h)
                seen[hits_at[r][h].second - n0] |= static_cast<char>(results[k].ok ? 2 : 4);
          }
          for (std::size_t y = 0; y < seen.size() && partly[r]; ++y)
            if (seen[y] == 6) partly[r] = 0;
          if (partly[r]) {
            for (std::size_t y = 0; y < seen.size(); ++y)
              if (seen[y] & 5) placed[y] = 1;
            continue;
          }
        }
        if (filled[r]) {
          for (std::size_t k = jobs_of[r].first; k < jobs_of[r].second; ++k)
            for (const auto& c : results[k].cells)
              for (auto v : c)
                if (v >= n0) placed[v - n0] = 1;
        } else {
          for (const auto& [c, y] : hits_at[r]) placed[y - n0] = 1;
        }
      }
      bool all_placed = true;
      for (std::size_t y = 0; y < placed.size() && all_placed; ++y) all_placed = placed[y] || on_came[y];
      for (std::size_t r = 0; r < cells.size(); ++r) {
        auto& W = by_region[r];
        if (!W.insertable) continue;
        if (partly[r] && all_placed) {
          std::vector<char> only(dead_at[r].size(), 0);
          for (std::size_t k = jobs_of[r].first; k < jobs_of[r].second; ++k)
            if (!results[k].ok)
              for (const auto x : W.components[jobs[k].component]) only[x] = 1;
          W.tasks.clear();
          make_front(r, &only, &rest[r]);  // its tasks first, then the filled cavities' cells
          task t{r, {}, {}, std::vector<cell_t<D>>{}};
          for (std::size_t k = jobs_of[r].first; k < jobs_of[r].second; ++k)
            t.inserted->insert(t.inserted->end(), results[k].cells.begin(), results[k].cells.end());
          W.tasks.push_back(std::move(t));
          continue;
        }
        if (!filled[r] || !all_placed) {
          unfilled.push_back(r);
          continue;
        }
        task t{r, {}, {}, std::vector<cell_t<D>>{}};
        for (std::size_t k = jobs_of[r].first; k < jobs_of[r].second; ++k)
          t.inserted->insert(t.inserted->end(), results[k].cells.begin(), results[k].cells.end());
        W.tasks.clear();
        W.tasks.push_back(std::move(t));
      }
    }
  }
  {  // the regions insertion did not fill: their fronts, for the front mesher
    for_each(execution::par(threads), unfilled, [&](std::size_t r) { make_front(r); }, [&](std::size_t r) { return static_cast<double>(by_region[r].met.size()); });
    for (const auto& W : by_region)
      if (!W.ok) return false;
  }
  std::vector<task> tasks;
  std::vector<std::size_t> region_first(cells.size() + 1, 0);
  std::size_t removed = 0;
  for (std::size_t r = 0; r < cells.size(); ++r) {
    if (!by_region[r].ok) return false;
    region_first[r] = tasks.size();
    removed += by_region[r].removed;
    for (auto& t : by_region[r].tasks) tasks.push_back(std::move(t));
  }
  region_first[cells.size()] = tasks.size();
  // 3. fill every task's cavities with the front mesher, in parallel; a task whose cells do not
  // fill the volume its front encloses (doubles, relative 1e-8: a safety net for a front that is
  // not Delaunay, never a topological decision) fails the round
  std::vector<std::vector<cell_t<D>>> made(tasks.size());
  std::vector<char> ok(tasks.size(), 1);
  std::vector<std::size_t> order(tasks.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  for (std::size_t t = 0; t < tasks.size(); ++t)
    if (tasks[t].inserted) made[t] = std::move(*tasks[t].inserted);
  for_each(execution::par(threads), order, [&](std::size_t t) {
    const auto& tk = tasks[t];
    if (tk.inserted) return;
    // the points a cavity's cells can use lie in the box of its front (its vertices, the new
    // points inside it, an old vertex all of whose cells died): a grid over those fits the local
    // spacing, where the grid over all points is crowded wherever the refinement went
    std::vector<vertex_id> ids;
    for (const auto& [lo, hi] : tk.boxes)
      grid.visit_box(lo, hi, [&](vertex_id y, const point<D>& q) {
        bool in = true;
        for (std::size_t k = 0; k < D; ++k) in = in && lo[k] <= q[k] && q[k] <= hi[k];
        if (in) ids.push_back(y);
        return true;
      });
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    std::vector<point<D>> at(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) at[i] = p[ids[i]];
    const front::point_grid<D> near(at, ids);
    try {
      const std::string label = "segment " + std::to_string(l1.regions[tk.region].number) + " '" + l1.regions[tk.region].name + "' (cavity)";
      // a face of old vertices only takes an added point as its apex (front::wrap_cavity): ids
      // are sorted, the added ones (n0 on) last
      if (settled) {
        const auto first = static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), static_cast<vertex_id>(n0)) - ids.begin());
        const front::point_grid<D> added(std::span<const point<D>>(at).subspan(first), std::span<const vertex_id>(ids).subspan(first));
        made[t] = front::wrap_cavity(std::span<const point<D>>(p), near, added, static_cast<vertex_id>(n0), tk.front, label);
      } else {
        made[t] = front::wrap(std::span<const point<D>>(p), near, tk.front, label);
      }
    } catch (const std::exception&) {
      ok[t] = 0;
      return;
    }
    // (plus a bound on the sums' rounding: cones from one origin over the long, thin faces of a
    // CAD part's cavity are nearly flat, and their rounding alone exceeded the relative 1e-8 and
    // sent four rounds of scad_example009 to a full meshing)
    const point<D> o = p[tk.front[0][0]];
    double enclosed = 0, filled = 0, scale = 0, error = 0;
    for (const auto& F : tk.front) {
      const double v = cone<D>(p, F, o);
      enclosed += v, scale += std::abs(v), error += rounding_bound<D>(p, F, o);
    }
    for (const auto& c : made[t]) {
      filled += cell_measure<D>(p, c);
      std::array<vertex_id, D> rest;
      for (std::size_t i = 0; i < D; ++i) rest[i] = c[i + 1];
      error += rounding_bound<D>(p, rest, p[c[0]]);
    }
    if (!(std::abs(std::abs(enclosed) - filled) <= 1e-8 * std::max(scale, filled) + error + 1e-300)) ok[t] = 0;
  }, [&](std::size_t t) { return static_cast<double>(tasks[t].front.size()); });
  if (std::find(ok.begin(), ok.end(), 0) != ok.end()) return false;
  // every new point must be a vertex of a new cell (none lies outside every cavity)
  std::vector<char> used(p.size() - n0, 0);
  for (const auto& m : made)
    for (const auto& c : m)
      for (auto v : c)
        if (v >= n0) used[v - n0] = 1;
  if (std::find(used.begin(), used.end(), 0) != used.end()) return false;
  // 4. each region: the new cells take the places of the dead ones near them, and the rest are
  // appended: a round costs what it changes, and a run of cells stays about one place, so the
  // cavity search above can skip it. Near: both sorted by the Morton code of their centroids
  // (the lattice spatial_order uses, over the same box), paired within blocks of the code of
  // about 64 cells; the new cells left over go, in code order, to the dead places left over
  // (each to the first at or after its code), then at the end. (Paired in task order, as
  // first written, a round scattered far cavities' cells over every run: on the rotated
  // trench the search read 80-85% of all runs each round, 190,000 cells for 2,000-5,000 dead
  // ones.) Fewer new cells than dead ones: the survivors close up, in order. The regions in
  // parallel; the result depends on codes and indices only.
  std::vector<std::size_t> added(cells.size(), 0);
  for_each(execution::par(threads), regions, [&](std::size_t r) {
    auto& cs = cells[r];
    auto& dr = dead[r];
    constexpr int bits = D == 2 ? 31 : 21;
    auto code = [&](const cell_t<D>& c) {
      point<D> g{};
      for (auto v : c) g = g + p[v];
      return morton_code<D>((1.0 / (D + 1)) * g, all_lo, all_hi, bits);
    };
    std::vector<const cell_t<D>*> made_cells;
    for (std::size_t t = region_first[r]; t < region_first[r + 1]; ++t)
      for (const auto& c : made[t]) made_cells.push_back(&c);
    added[r] = made_cells.size();
    const std::size_t old_size = cs.size();
    // the codes in slices, in parallel (a region is often the whole model: serial, these were
    // half a second of scad_example009's rounds; docs/benchmarks.md, sixty-eighth part)
    std::vector<std::pair<std::uint64_t, std::uint32_t>> fresh(made_cells.size()), slots(dead_at[r].size());  // (code, new cell) and (code, dead place)
    constexpr std::size_t slice = 4096;
    std::vector<std::size_t> slices((std::max(fresh.size(), slots.size()) + slice - 1) / slice);
    std::iota(slices.begin(), slices.end(), std::size_t{0});
    for_each(execution::par(threads), slices, [&](std::size_t q) {
      for (std::size_t k = q * slice; k < std::min(fresh.size(), (q + 1) * slice); ++k) fresh[k] = {code(*made_cells[k]), static_cast<std::uint32_t>(k)};
      for (std::size_t k = q * slice; k < std::min(slots.size(), (q + 1) * slice); ++k) slots[k] = {code(cs[dead_at[r][k]]), dead_at[r][k]};
    });
    radix_sort(fresh);  // both built in index order: std::sort's order of the pairs
    radix_sort(slots);
    // blocks of the code holding about 64 cells: 2^(D L) blocks for L levels
    int levels = 0;
    while (levels < bits && (std::size_t{1} << (D * static_cast<std::size_t>(levels + 1))) * 64 <= old_size + made_cells.size()) ++levels;
    const int shift = static_cast<int>(D) * (bits - levels);
    auto block = [&](std::uint64_t c) { return shift >= 64 ? std::uint64_t{0} : c >> shift; };
    std::vector<std::int64_t> place(made_cells.size(), -1);  // per new cell: its dead place, or -1
    std::vector<char> taken(slots.size(), 0);
    for (std::size_t a = 0, d = 0; a < fresh.size() && d < slots.size();) {
      const auto ba = block(fresh[a].first), bd = block(slots[d].first);
      if (ba == bd) {
        place[fresh[a].second] = slots[d].second;
        taken[d] = 1;
        ++a, ++d;
      } else if (ba < bd) {
        ++a;
      } else {
        ++d;
      }
    }
    // leftovers: each new cell to the first free dead place at or after its code, while any
    std::vector<std::uint32_t> free_places;  // indices into slots, in code order
    for (std::size_t d = 0; d < slots.size(); ++d)
      if (!taken[d]) free_places.push_back(static_cast<std::uint32_t>(d));
    std::size_t left = free_places.size();  // dead places no new cell takes: holes, if any
    {
      std::size_t at = 0;
      std::vector<char> spent(free_places.size(), 0);
      for (std::size_t a = 0; a < fresh.size() && left > 0; ++a) {
        if (place[fresh[a].second] >= 0) continue;
        while (at < free_places.size() && (spent[at] || slots[free_places[at]].first < fresh[a].first)) ++at;
        std::size_t pick = at;
        if (pick == free_places.size())  // past the last: the last free one (left > 0: there is one)
          while (spent[--pick]) {
          }
        spent[pick] = 1, --left;
        place[fresh[a].second] = slots[free_places[pick]].second;
      }
    }
    for (std::size_t k = 0; k < made_cells.size(); ++k) {
      if (place[k] < 0) continue;
      const auto i = static_cast<std::size_t>(place[k]);
      cs[i] = *made_cells[k];
      dr[i] = 0;
      if (balls) (*balls)[r][i] = cell_ball<D>{};  // unknown
      if (flags) (*flags)[r][i] = 1;               // not looked at yet
      cell_runs[r][i / cell_run].valid = false;
    }
    if (left > 0) {  // every new cell is placed: close up over the dead ones left
      std::size_t w = 0;
      for (std::size_t i = 0; i < old_size; ++i)
        if (!dr[i]) {
          cs[w] = cs[i];
          if (balls) (*balls)[r][w] = (*balls)[r][i];
          if (flags) (*flags)[r][w] = (*flags)[r][i];
          ++w;
        }
      cs.resize(w);
      if (balls) (*balls)[r].resize(w);
      if (flags) (*flags)[r].resize(w);
      cell_runs[r].assign((w + cell_run - 1) / cell_run, run_box<D>{});  // cells moved
      return;
    }
    for (const auto& [c, k] : fresh)
      if (place[k] < 0) cs.push_back(*made_cells[k]);
    if (balls) (*balls)[r].resize(cs.size());
    if (flags) (*flags)[r].resize(cs.size(), 1);
    if (cs.size() > old_size && old_size % cell_run != 0) cell_runs[r][old_size / cell_run].valid = false;
    cell_runs[r].resize((cs.size() + cell_run - 1) / cell_run);  // new runs: not valid yet
  }, [&](std::size_t r) { return static_cast<double>(cells[r].size()); });
  const std::size_t count = std::accumulate(added.begin(), added.end(), std::size_t{0});
  if (removed_count) *removed_count = removed;
  if (front_regions) {
    *front_regions = 0;
    for (std::size_t r = 0; r < cells.size(); ++r)
      for (std::size_t t = region_first[r]; t < region_first[r + 1]; ++t)
        if (!tasks[t].inserted) {
          ++*front_regions;
          break;
        }
  }
  if (made_count) *made_count = count;
  return true;
}

namespace {
/// Each region's cells in the Morton order of their centroids (a 2^21 lattice over the points'
/// box; ties in their order before): consecutive cells lie together, so that a run of them has a
/// small box (remesh_cavities skips the runs no new point comes near).
template <std::size_t D>
void spatial_order(cells_by_region<D>& cells, const std::vector<point<D>>& p, unsigned threads) {
  if (p.empty()) return;
  point<D> lo = p[0], hi = p[0];
  for (const auto& q : p)
    for (std::size_t k = 0; k < D; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
  constexpr int bits = D == 2 ? 31 : 21;
  // one region after another, the keys and the gather on every thread (one region, the
  // substrate, usually holds most cells); the sort is a radix sort, stable: the same order for
  // any thread count
  constexpr std::size_t chunk = 1 << 14;
  for (auto& cs : cells) {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> key(cs.size());
    std::vector<std::size_t> starts;
    for (std::size_t a = 0; a < cs.size(); a += chunk) starts.push_back(a);
    for_each(execution::par(threads), starts, [&](std::size_t a) {
      for (std::size_t i = a; i < std::min(cs.size(), a + chunk); ++i) {
        point<D> g{};
        for (auto v : cs[i]) g = g + p[v];
        key[i] = {morton_code<D>((1.0 / (D + 1)) * g, lo, hi, bits), static_cast<std::uint32_t>(i)};
      }
    });
    radix_sort(key);  // the keys in index order: ties keep it, as the pairs' own order does
    std::vector<cell_t<D>> sorted(cs.size());
    for_each(execution::par(threads), starts, [&](std::size_t a) {
      for (std::size_t i = a; i < std::min(cs.size(), a + chunk); ++i) sorted[i] = cs[key[i].second];
    });
    cs = std::move(sorted);
  }
}
}  // namespace

template <std::size_t D>
domain<D> refine(const plc<D>& p, conformer::boundary<D>& b, conformer::labelling& l, cells_by_region<D> cells,
                 const conformer::options& co, const options& o, const meshers<D>& mesh, stats& st,
                 conformer::session<D>* rounds) {
  st = stats{};  // a report used before starts over (its rounds are the cap's count)
  const double bound = ratio_bound(D, o.bound);
  // per cell: 1 until the plan has found it good (a cell's shape and size never change, so a
  // good one that survives a round is not measured again)
  auto all_todo = [](const cells_by_region<D>& c) {
    std::vector<std::vector<char>> t(c.size());
    for (std::size_t r = 0; r < c.size(); ++r) t[r].assign(c[r].size(), 1);
    return t;
  };
  // size alone (no shape bound, no sliver rule: the size rounds) keeps no balls: the plan asks
  // few cells for theirs, the rounds are one or two, and the balls are 32 bytes a cell (the graded
  // trench's 11.1 million cells: 356 MB)
  const bool keep_balls = !size_only(bound, D == 3 ? o.sliver_angle : 0.0);
  // the cells in Morton order (the cavity search reads runs of them): not for size alone, whose
  // one or two rounds re-fill a few cavities, while the order's keys and copy are 32 bytes a cell
  // at the run's peak (the graded trench's 11.1 million cells: 356 MB, for a round that inserted
  // one point); the cavity search then reads runs in the front mesher's own order
  if (keep_balls) spatial_order(cells, b.points, o.threads);
  auto todo = all_todo(cells);
  auto no_balls = [](const cells_by_region<D>& c) {
    balls_by_region<D> kept(c.size());
    for (std::size_t r = 0; r < c.size(); ++r) kept[r].resize(c[r].size());
    return kept;
  };
  auto balls = keep_balls ? no_balls(cells) : balls_by_region<D>{};
  runs_by_region<D> runs;  // built by remesh_cavities as it needs them
  // the conformer stays alive between rounds: each round's boundary work follows the points it
  // adds, not the size of the boundary (conformer::session)
  std::optional<conformer::session<D>> own;
  conformer::session<D>& boundary_rounds = rounds ? *rounds : own.emplace(p, co);
  const spacing_floor<D> floor(b, D == 3 ? spacing_floor<D>::default_ratio : 0.0);
  // the bad elements' count a round before, and whether it rose in each of the last rounds (bit
  // 0 the latest): a dip or a flat round among the rises does not start the count over
  std::size_t last_bad = 0;
  std::uint32_t rises = 0;
  vertex_sizes vertex_h;  // 3D graded sizes: h at the points (plan_round fills it)
  if (o.graded3 && std::isfinite(o.graded3->slope) && o.graded3->volume_lower.size() == b.volume_points &&
      b.plc_points + b.volume_points <= b.points.size()) {
    vertex_h.lower.assign(b.points.size(), 0.0);
    vertex_h.exact.assign(b.points.size(), 0);
    std::copy(o.graded3->volume_lower.begin(), o.graded3->volume_lower.end(), vertex_h.lower.begin() + static_cast<long>(b.plc_points));
  }
  bool growth_asked = false;
  for (;;) {
    std::function<double(const point<D>&)> size;
    if constexpr (D == 2)
      size = o.size2;
    else
      size = o.size3;
    auto clock = std::chrono::steady_clock::now();
    auto lap = [&clock]() {
      const auto now = std::chrono::steady_clock::now();
      const double s = std::chrono::duration<double>(now - clock).count();
      clock = now;
      return s;
    };
    auto pl = plan_round(cells, b, bound, o.threads, size, D == 3 ? o.sliver_angle : 0.0, &l, &todo, o.acute_guard,
                         keep_balls ? &balls : nullptr, &floor,
                         D == 3 ? o.graded3.get() : nullptr, &vertex_h, &o.segment_maximum2);
    const double plan_seconds = lap();
    st.plan_seconds += plan_seconds;
    st.outside += pl.outside;
    st.bad_left = pl.bad;
    st.excepted = pl.excepted;
    st.excepted_near = pl.excepted_near;
    st.below_floor = pl.below_floor;
    if (pl.bad == pl.excepted && pl.large == 0) {
      st.converged = true;
      break;
    }
    if (st.rounds >= (o.max_rounds ? o.max_rounds : 250) || b.points.size() >= o.max_points || (pl.add.empty() && pl.split.empty())) break;
    // the bad elements growing round after round: asked once whether the input can be met at all
    // (outside the round's try: its error ends the refinement)
    rises = (rises << 1) | (st.rounds > 0 && pl.bad > last_bad ? 1u : 0u);
    last_bad = pl.bad;
    const auto window = std::min<std::size_t>(o.growth_rounds + 2, 32);
    const std::uint32_t recent = window >= 32 ? rises : rises & ((std::uint32_t{1} << window) - 1);
    if (o.on_growth && !growth_asked && o.growth_rounds > 0 && static_cast<std::size_t>(std::popcount(recent)) >= o.growth_rounds) {
      growth_asked = true;
      o.on_growth(pl.bad, st.rounds);
    }
    ++st.rounds;
    st.inserted += pl.add.size();
    st.split_requests += pl.split.size();
    auto& rec = st.per_round.emplace_back();
    rec.bad = pl.bad, rec.inserted = pl.add.size(), rec.split_requests = pl.split.size(), rec.plan_seconds = plan_seconds;
    if (o.progress)
      o.progress((std::isfinite(bound) ? "quality round " : "size round ") + std::to_string(st.rounds) + ": " + std::to_string(pl.bad) +
                 (std::isfinite(bound) ? " elements above the bound, " : " elements too large, ") +
                 std::to_string(pl.add.size()) + " circumcentres, " + std::to_string(pl.split.size()) + " boundary splits");
    // a round that fails (an error from the conformer, the labelling or the mesher) leaves the
    // last good mesh, its boundary and labels as they were; the failure is reported, not hidden
    try {
      auto b2 = boundary_rounds.next(b, pl.add, pl.split);
      rec.conform_seconds = lap();
      st.conform_seconds += rec.conform_seconds;
      auto l2 = conformer::label_refined(b2, p, b, l, o.threads);
      rec.label_seconds = lap();
      st.label_seconds += rec.label_seconds;
      // remesh_cavities changes cells and todo only when it succeeds, and a full meshing that
      // throws assigns nothing: the last good mesh survives a failed round without a copy
      std::size_t removed = 0, made = 0, front_regions = 0;
      if (remesh_cavities(b, b2, l, l2, cells, o.threads, &removed, &made, &todo, keep_balls ? &balls : nullptr, &runs, default_batch_faces, o.fill, &front_regions)) {
        st.cavity_cells += removed, st.cavity_made += made;
        rec.cavity_cells = removed, rec.cavity_made = made;
        st.cavity_front_regions += front_regions, rec.cavity_front_regions = front_regions;
      } else {
        cells = mesh.wrap(b2, l2);
        spatial_order(cells, b2.points, o.threads);
        todo = all_todo(cells);
        if (keep_balls) balls = no_balls(cells);
        runs.clear();
        ++st.full_remeshes;
      }
      rec.mesh_seconds = lap();
      st.mesh_seconds += rec.mesh_seconds;
      b = std::move(b2), l = std::move(l2);
    } catch (const std::exception& e) {
      st.failure = "round " + std::to_string(st.rounds) + ": " + e.what();
      st.per_round.pop_back();
      --st.rounds;
      st.inserted -= pl.add.size();
      st.split_requests -= pl.split.size();
      break;
    }
  }
  // what the rounds kept (the conformer's state too) is freed before the assembly, the run's
  // peak (the balls alone are 32 bytes a cell)
  balls_by_region<D>().swap(balls);
  std::vector<std::vector<char>>().swap(todo);
  runs_by_region<D>().swap(runs);
  vertex_h = vertex_sizes{};
  boundary_rounds.end();
  return mesh.assemble(b, l, std::move(cells));
}

template plan<2> plan_round<2>(const cells_by_region<2>&, const conformer::boundary<2>&, double, unsigned,
                               const std::function<double(const point2&)>&, double, const conformer::labelling*,
                               std::vector<std::vector<char>>*, double, balls_by_region<2>*, const spacing_floor<2>*,
                               const edge_sizes*, vertex_sizes*, const std::function<double(int)>*);
template plan<3> plan_round<3>(const cells_by_region<3>&, const conformer::boundary<3>&, double, unsigned,
                               const std::function<double(const point3&)>&, double, const conformer::labelling*,
                               std::vector<std::vector<char>>*, double, balls_by_region<3>*, const spacing_floor<3>*,
                               const edge_sizes*, vertex_sizes*, const std::function<double(int)>*);
template std::vector<cavity_piece<2>> cavity_pieces<2>(const std::vector<point<2>>&, const std::vector<std::array<vertex_id, 2>>&);
template std::vector<cavity_piece<3>> cavity_pieces<3>(const std::vector<point<3>>&, const std::vector<std::array<vertex_id, 3>>&);
template bool remesh_cavities<2>(const conformer::boundary<2>&, const conformer::boundary<2>&, const conformer::labelling&,
                                 const conformer::labelling&, cells_by_region<2>&, unsigned, std::size_t*, std::size_t*,
                                 std::vector<std::vector<char>>*, balls_by_region<2>*, runs_by_region<2>*, std::size_t,
                                 cavity_fill, std::size_t*);
template bool remesh_cavities<3>(const conformer::boundary<3>&, const conformer::boundary<3>&, const conformer::labelling&,
                                 const conformer::labelling&, cells_by_region<3>&, unsigned, std::size_t*, std::size_t*,
                                 std::vector<std::vector<char>>*, balls_by_region<3>*, runs_by_region<3>*, std::size_t,
                                 cavity_fill, std::size_t*);
template domain<2> refine<2>(const plc<2>&, conformer::boundary<2>&, conformer::labelling&, cells_by_region<2>, const conformer::options&,
                             const options&, const meshers<2>&, stats&, conformer::session<2>*);
template domain<3> refine<3>(const plc<3>&, conformer::boundary<3>&, conformer::labelling&, cells_by_region<3>, const conformer::options&,
                             const options&, const meshers<3>&, stats&, conformer::session<3>*);

}  // namespace gsse::refinement
