#pragma once
// A bounding-volume hierarchy over axis-aligned boxes (median splits of the box centres), with a
// value per box and the minimum of the values in every subtree. Built once, then read-only, so
// any number of threads may query it. Used for the graded minimum
//   h(x) = min over boxes b of (value(b) + slope * distance(x, b))
// (branch and bound on value + slope * distance to the node's box), and for nearest-feature and
// point-location queries through `visit`. Sizing only: doubles place points, they decide no
// topology.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "gsse/geometry/point.hpp"

namespace gsse::sizing {

template <std::size_t D>
struct aabb {
  point<D> lo, hi;
  static aabb empty() {
    aabb b;
    for (std::size_t k = 0; k < D; ++k) b.lo[k] = std::numeric_limits<double>::infinity(), b.hi[k] = -std::numeric_limits<double>::infinity();
    return b;
  }
  void add(const point<D>& q) {
    for (std::size_t k = 0; k < D; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
  }
  void add(const aabb& b) {
    add(b.lo);
    add(b.hi);
  }
  /// Squared distance from q to the box (0 inside).
  double distance2(const point<D>& q) const {
    double s = 0;
    for (std::size_t k = 0; k < D; ++k) {
      const double d = q[k] < lo[k] ? lo[k] - q[k] : (q[k] > hi[k] ? q[k] - hi[k] : 0.0);
      s += d * d;
    }
    return s;
  }
  bool contains(const point<D>& q) const {
    for (std::size_t k = 0; k < D; ++k)
      if (q[k] < lo[k] || q[k] > hi[k]) return false;
    return true;
  }
};

template <std::size_t D>
class box_tree {
 public:
  box_tree() = default;
  /// Boxes and their values; item i keeps its index for the visitors.
  box_tree(std::vector<aabb<D>> boxes, std::vector<double> values) : boxes_(std::move(boxes)), values_(std::move(values)) {
    order_.resize(boxes_.size());
    std::iota(order_.begin(), order_.end(), 0u);
    if (!boxes_.empty()) {
      nodes_.reserve(2 * boxes_.size() / leaf_size + 2);
      build(0, static_cast<std::uint32_t>(boxes_.size()));
    }
  }
  std::size_t size() const { return boxes_.size(); }
  bool empty() const { return boxes_.empty(); }
  const aabb<D>& box(std::uint32_t i) const { return boxes_[i]; }
  double value(std::uint32_t i) const { return values_[i]; }

  /// min over items of value + slope * distance(x, box), or +infinity when empty; `cap` is a known
  /// upper bound (nodes that cannot beat it are skipped).
  double graded_min(const point<D>& x, double slope, double cap = std::numeric_limits<double>::infinity()) const {
    return graded_min(x, slope, cap, [](std::uint32_t, double box_distance2) { return box_distance2; });
  }

  /// min over items of value + slope * distance(x, item), where `distance2(i, d2)` is item i's
  /// squared distance from x, given d2, its box's (no smaller: the item lies in its box). Asked
  /// only for items whose box could beat the minimum so far, so an exact distance to the item
  /// itself (a slanted triangle, whose box reaches far off it) costs little more than the box's.
  template <class Distance2>
  double graded_min(const point<D>& x, double slope, double cap, Distance2&& distance2, std::uint32_t* hint = nullptr) const {
    double best = cap;
    if (nodes_.empty()) return best;
    // a warm start: the item that won the caller's last query (nearby, as a placement's are) is
    // asked first, so that the search prunes with a tight bound from its first node. Its value is
    // an item's, no smaller than the minimum: the result is the one a cold search gives
    std::uint32_t won = hint ? *hint : ~std::uint32_t{0};
    if (won < boxes_.size()) best = std::min(best, values_[won] + slope * std::sqrt(distance2(won, boxes_[won].distance2(x))));
    auto bound = [&](const node& n) { return n.min_value + slope * std::sqrt(n.box.distance2(x)); };
    std::uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const node& n = nodes_[stack[--top]];
      if (bound(n) >= best) continue;
      if (n.leaf) {
        for (std::uint32_t k = n.a; k < n.b; ++k) {
          const std::uint32_t i = order_[k];
          const double d2 = boxes_[i].distance2(x);
          if (values_[i] + slope * std::sqrt(d2) >= best) continue;
          const double v = values_[i] + slope * std::sqrt(distance2(i, d2));
          if (v < best) best = v, won = i;
        }
        continue;
      }
      const node &l = nodes_[n.a], &r = nodes_[n.b];
      const double bl = bound(l), br = bound(r);
      // nearer child last, so it is popped first
      if (bl < br) {
        if (br < best) stack[top++] = n.b;
        if (bl < best) stack[top++] = n.a;
      } else {
        if (bl < best) stack[top++] = n.a;
        if (br < best) stack[top++] = n.b;
      }
    }
    if (hint) *hint = won;
    return best;
  }

  /// Calls f(i) for every item whose box `keep(box)` accepts, descending only into nodes whose box
  /// `keep` accepts (e.g. "within distance r of q" or "contains q"). f returning false stops.
  template <class Keep, class F>
  bool visit(Keep&& keep, F&& f) const {
    return walk(keep, f, [](const node&) { return true; });
  }

  /// visit, the nearer child (by box distance to q) first: for searches whose `keep` tightens as
  /// `f` finds closer items (a nearest-feature search), which then skip more.
  template <class Keep, class F>
  bool visit_near(const point<D>& q, Keep&& keep, F&& f) const {
    return walk(keep, f, [&](const node& n) { return nodes_[n.a].box.distance2(q) <= nodes_[n.b].box.distance2(q); });
  }

 private:
  /// The depth-first walk of visit and visit_near; `a_first(inner node)`: its child a before b.
  template <class Keep, class F, class Order>
  bool walk(Keep& keep, F& f, Order&& a_first) const {
    if (nodes_.empty()) return true;
    std::uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const node& n = nodes_[stack[--top]];
      if (!keep(n.box)) continue;
      if (n.leaf) {
        for (std::uint32_t k = n.a; k < n.b; ++k)
          if (keep(boxes_[order_[k]]) && !f(order_[k])) return false;
        continue;
      }
      const bool af = a_first(n);
      stack[top++] = af ? n.b : n.a;
      stack[top++] = af ? n.a : n.b;
    }
    return true;
  }
  static constexpr std::uint32_t leaf_size = 8;
  struct node {
    aabb<D> box;
    double min_value;
    std::uint32_t a, b;  // leaf: items order_[a, b); inner: children
    bool leaf;
  };
  std::uint32_t build(std::uint32_t a, std::uint32_t b) {
    const auto id = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({});
    aabb<D> box = aabb<D>::empty(), centres = aabb<D>::empty();
    double mv = std::numeric_limits<double>::infinity();
    for (std::uint32_t k = a; k < b; ++k) {
      const auto& bx = boxes_[order_[k]];
      box.add(bx);
      centres.add(0.5 * (bx.lo + bx.hi));
      mv = std::min(mv, values_[order_[k]]);
    }
    if (b - a <= leaf_size) {
      nodes_[id] = {box, mv, a, b, true};
      return id;
    }
    std::size_t axis = 0;
    for (std::size_t k = 1; k < D; ++k)
      if (centres.hi[k] - centres.lo[k] > centres.hi[axis] - centres.lo[axis]) axis = k;
    const std::uint32_t m = a + (b - a) / 2;
    // ties broken by index: the tree (and so every query's result) is the same on every run
    std::nth_element(order_.begin() + a, order_.begin() + m, order_.begin() + b, [&](std::uint32_t x, std::uint32_t y) {
      const double cx = boxes_[x].lo[axis] + boxes_[x].hi[axis], cy = boxes_[y].lo[axis] + boxes_[y].hi[axis];
      return cx < cy || (cx == cy && x < y);
    });
    const std::uint32_t l = build(a, m), r = build(m, b);
    nodes_[id] = {box, mv, l, r, false};
    return id;
  }
  std::vector<aabb<D>> boxes_;
  std::vector<double> values_;
  std::vector<std::uint32_t> order_;
  std::vector<node> nodes_;
};

}  // namespace gsse::sizing
