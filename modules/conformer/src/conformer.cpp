#include "gsse/conformer/conformer.hpp"
#include "gsse/geometry/plane_axes.hpp"
#include "gsse/sizing/place_points.hpp"
#include "gsse/sizing/distance.hpp"

#include <algorithm>
#include <functional>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <span>
#include <stdexcept>
#include <tuple>

#include "balls.hpp"
#include "encroachment.hpp"
#include "thin_layers.hpp"
#include "gsse/front/front_mesher.hpp"
#include "gsse/geometry/hash_grid.hpp"
#include "gsse/container/key_set.hpp"
#include "gsse/geometry/point_grid.hpp"
#include "gsse/plc/facet_regions.hpp"
#include "gsse/conformer/regions.hpp"
#include "gsse/front/gift_wrap.hpp"
#include "gsse/front/kernels.hpp"
#include "gsse/rules/defaults.hpp"
#include "gsse/rules/split_rule.hpp"
#include "gsse/traversal/for_each.hpp"

namespace gsse::conformer {
namespace {

using rules::element_kind;
using rules::relation;

/// The largest extent of the box of pts (at least 1e-300).
template <std::size_t D>
double extent_of(const std::vector<point<D>>& pts) {
  if (pts.empty()) return 1;
  point<D> lo = pts[0], hi = pts[0];
  for (const auto& q : pts)
    for (std::size_t k = 0; k < D; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
  double ext = 1e-300;
  for (std::size_t k = 0; k < D; ++k) ext = std::max(ext, hi[k] - lo[k]);
  return ext;
}

/// Grid cells for `count` points (pts.size() if 0) in the box of pts: about one point per cell if
/// they filled the box, never above `size` when given.
template <std::size_t D>
double cell_size_for(const std::vector<point<D>>& pts, double size, std::size_t count = 0) {
  const double ext = extent_of(pts);
  if (count == 0) count = pts.size();
  double h = ext / std::max(1.0, std::pow(static_cast<double>(count), 1.0 / static_cast<double>(D)));
  if (size > 0) h = std::min(h, size);
  return h > 1e-300 ? h : 1.0;
}

/// PLC edge: its end vertices and its chain of subsegment vertices (ends included).
struct plc_edge {
  vertex_id u, v;
  std::vector<vertex_id> chain;
  std::vector<std::uint32_t> facets;  // 3D: facets containing the edge
  // 3D: the direction into one of its facets, in that facet's plane, and the sign of
  // orient2d(u, v, x) that "x inside that facet" has in each coordinate projection (0: the
  // projection is not checked, the facet is nearly parallel to its axis). See on_edge().
  point3 inward{};
  std::array<int, 3> inside_sign{};
};

/// Points inserted since some moment: an element checked clean before can be encroached only by
/// one of them. Their bounding box rules out most balls without a grid lookup (the later rounds
/// insert a handful of points, and every element is asked).
template <std::size_t D>
struct recent_points {
  hash_grid<D> grid;
  point<D> lo{}, hi{};
  bool empty = true;
  /// `to_freeze`: all points come before any search, and freeze() comes between (a point grid is
  /// built then; the hash grid stays empty). Otherwise the hash grid takes points as they come.
  recent_points(const point<D>& origin, double cell, bool freeze_later = false) : grid(origin, cell), to_freeze(freeze_later) {}
  void add(vertex_id v, const point<D>& q) {
    if (frozen) throw std::logic_error("recent_points: add after freeze");
    if (to_freeze) {
      ids.push_back(v);
      at.push_back(q);
    } else {
      grid.insert(v, q);
    }
    for (std::size_t k = 0; k < D; ++k) lo[k] = empty ? q[k] : std::min(lo[k], q[k]), hi[k] = empty ? q[k] : std::max(hi[k], q[k]);
    empty = false;
  }
  /// No more points: searches go to a point grid over them (nested where they crowd, rows clipped
  /// to the ball) instead of the hash grid, whose box scan reads every cell of a large ball's box,
  /// or sorts every occupied cell when the box has more (the hammer's coarse subfacets).
  void freeze() {
    if (!to_freeze) throw std::logic_error("recent_points: freeze of a growing set");
    frozen = true;
    fixed.build(std::span<const point<D>>(at), ids);
  }
  /// False if none lies in the box [a, b].
  bool near_box(const point<D>& a, const point<D>& b) const {
    if (empty) return false;
    for (std::size_t k = 0; k < D; ++k)
      if (b[k] < lo[k] || hi[k] < a[k]) return false;
    return true;
  }
  /// False if none lies in the closed box [a, b]: the box test, then (frozen) the points of the
  /// grid cells that meet it. Growing: the box test alone (true means "may be").
  bool any_in_box(const point<D>& a, const point<D>& b) const {
    if (!near_box(a, b)) return false;
    if (!frozen) return true;
    return !fixed.visit_box(a, b, [&](vertex_id, const point<D>& q) {
      for (std::size_t k = 0; k < D; ++k)
        if (q[k] < a[k] || b[k] < q[k]) return true;
      return false;
    });
  }
  /// False if none lies within r of c (the box test; true means "look in the grid").
  bool near(const point<D>& c, double r) const {
    if (empty) return false;
    double d2 = 0;
    for (std::size_t k = 0; k < D; ++k) {
      const double x = std::clamp(c[k], lo[k], hi[k]) - c[k];
      d2 += x * x;
    }
    return d2 <= r * r;
  }
  /// f(id) for (at least) the points within r of c; false from f stops, and visit_ball returns
  /// false.
  template <class F>
  bool visit_ball(const point<D>& c, double r, F&& f) const {
    if (frozen) return fixed.visit_ball(c, r, [&](vertex_id y, const point<D>&) { return f(y); });
    if (to_freeze) throw std::logic_error("recent_points: search before freeze");
    point<D> a, b;
    for (std::size_t k = 0; k < D; ++k) a[k] = c[k] - r, b[k] = c[k] + r;
    return grid.visit(a, b, f);
  }

 private:
  bool to_freeze, frozen = false;
  std::vector<vertex_id> ids;
  std::vector<point<D>> at;
  geometry::point_grid<D> fixed;
};

/// Conformer state shared by 2D and 3D.
template <std::size_t D>
class state {
 public:
  state(const plc<D>& p, const std::vector<point<D>>& volume, const options& o)
      : plc_(p), opt_(o), grid_h_(p.points.empty() ? 1.0 : cell_size_for(p.points, o.size, p.points.size() + volume.size())),
        grid_(p.points.empty() ? point<D>{} : p.points[0], grid_h_, extent_of(p.points)) {
    if (p.points.empty()) throw conform_error(p.source + ": the PLC has no points");
    out_.points = p.points;
    out_.homes.assign(p.points.size(), {});
    for (vertex_id v = 0; v < p.points.size(); ++v) out_.homes[v] = {home::vertex, v};
    out_.plc_points = p.points.size();
    for (const auto& q : volume) {
      out_.points.push_back(q);
      out_.homes.push_back({home::free, 0});
    }
    out_.volume_points = volume.size();
    grid_sized_for_ = out_.points.size();
    {
      point<D> lo = p.points[0], hi = lo;
      for (const auto& q : p.points)
        for (std::size_t k = 0; k < D; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
      model_size_ = distance(lo, hi) > 0 ? distance(lo, hi) : 1;
    }
    box_lo_ = box_hi_ = out_.points[0];
    for (vertex_id v = 0; v < out_.points.size(); ++v) {
      grid_.insert(v, out_.points[v]);
      for (std::size_t k = 0; k < D; ++k)
        box_lo_[k] = std::min(box_lo_[k], out_.points[v][k]), box_hi_[k] = std::max(box_hi_[k], out_.points[v][k]);
    }
    rules_ = o.rules ? o.rules : &own_rules_;
    if (!o.rules) own_rules_ = rules::default_rules(D == 2 ? "conformer2d" : "conformer3d");
  }

  boundary<D>& out() { return out_; }
  const plc<D>& input() const { return plc_; }

  /// A size field is set (options::local_size2/3).
  bool graded() const {
    if constexpr (D == 2)
      return static_cast<bool>(opt_.local_size2);
    else
      return static_cast<bool>(opt_.local_size3);
  }
  bool sized() const { return opt_.size > 0 || graded(); }
  /// The target size at q: the size field's value, or the uniform size (0: none). With a cap, the
  /// size field's min(h(q), cap) (the same comparisons against any bound up to cap, for a search
  /// that stops at the cap).
  double size_at(const point<D>& q, double cap = std::numeric_limits<double>::infinity()) const {
    if constexpr (D == 2) {
      if (opt_.local_size2) return opt_.local_size2(q, cap);
    } else {
      if (opt_.local_size3) return opt_.local_size3(q, cap);
    }
    return opt_.size;
  }
  std::vector<plc_edge>& edges() { return edges_; }

  vertex_id add_point(const point<D>& q, home h) {
    if (out_.steiner >= opt_.max_steiner)
      throw conform_error(plc_.source + ": more than " + std::to_string(opt_.max_steiner) +
                          " boundary points inserted; the input likely has features far below the mesh size "
                          "(raise --max-steiner to continue)");
    const vertex_id v = push_point(q, h);
    ++out_.steiner;
    return v;
  }

  /// resume(): the points of an earlier result beyond the PLC's and the volume ones, with their
  /// homes, in order (ids kept), each boundary one on its edge's chain (by its place along the
  /// edge) or in its facet; then `added` free points. The earlier result's volume points take
  /// back the homes they were given (a volume point exactly on the boundary became a vertex of it).
  void restore(const boundary<D>& prev, const std::vector<point<D>>& added) {
    if (prev.points.size() < out_.points.size() || prev.plc_points != out_.plc_points)
      throw conform_error(plc_.source + ": resume() given a boundary of another input");
    for (vertex_id v = static_cast<vertex_id>(out_.plc_points); v < prev.points.size(); ++v) {
      if (v < out_.points.size())
        out_.homes[v] = prev.homes[v];
      else
        push_point(prev.points[v], prev.homes[v]);
      if (prev.homes[v].kind == home::facet) on_facet(prev.homes[v].id, v);
    }
    out_.steiner = prev.steiner;
    out_.rounds = prev.rounds;
    const auto& p = out_.points;
    std::vector<std::vector<vertex_id>> on(edges_.size());
    for (vertex_id v = static_cast<vertex_id>(out_.plc_points); v < p.size(); ++v)
      if (out_.homes[v].kind == home::edge) on.at(out_.homes[v].id).push_back(v);
    for (std::uint32_t e = 0; e < edges_.size(); ++e) {
      auto& E = edges_[e];
      const point<D> a = p[E.u], d = p[E.v] - p[E.u];
      auto& mid = on[e];
      std::sort(mid.begin(), mid.end(), [&](vertex_id x, vertex_id y) { return dot(p[x] - a, d) < dot(p[y] - a, d); });
      E.chain.clear();
      E.chain.push_back(E.u);
      E.chain.insert(E.chain.end(), mid.begin(), mid.end());
      E.chain.push_back(E.v);
    }
    for (const auto& q : added) add_free(q);
  }
  /// A free point (session::next()'s added points), as restore() adds them.
  vertex_id add_free(const point<D>& q) { return push_point(q, {home::free, 0}); }
  virtual void on_facet(std::uint32_t, vertex_id) {}
  /// 3D: the shift along PLC edge e of its points (state3::edge_shear), none in 2D
  virtual point<D> edge_shear(std::uint32_t) const { return point<D>{}; }
  /// The spacing PLC edge e is split at with a uniform size: the size, or in 3D finer along a
  /// thin layer's wall (state3::edge_size, options::thin_layer)
  virtual double edge_size(std::uint32_t) const { return opt_.size; }
  virtual ~state() = default;

  /// Splits subsegment (a, b) of PLC edge e as one too long is split (the on-carrier rule: a shell
  /// about a small-angle end, else the midpoint); false if (a, b) is no longer a subsegment.
  bool split_requested(std::uint32_t e, vertex_id a, vertex_id b) {
    auto& E = edges_.at(e);
    for (std::size_t i = 0; i + 1 < E.chain.size(); ++i)
      if ((E.chain[i] == a && E.chain[i + 1] == b) || (E.chain[i] == b && E.chain[i + 1] == a)) {
        if (protected_subsegment(e, i)) return false;
        std::optional<rules::split_action> fired;
        const point<D> q = subsegment_split(e, i, relation::on_carrier, out_.points[a], nullptr, fired);
        const vertex_id m = add_point(q, {home::edge, e});
        E.chain.insert(E.chain.begin() + static_cast<long>(i) + 1, m);
        return true;
      }
    return false;
  }

 private:
  vertex_id push_point(const point<D>& q, home h) {
    out_.points.push_back(q);
    out_.homes.push_back(h);
    const auto v = static_cast<vertex_id>(out_.points.size() - 1);
    if (out_.points.size() > 4 * grid_sized_for_) {
      // boundary refinement far beyond the points the grid was made for (a fine surface in a
      // coarse box): cells as for today's count, else each lookup scans crowded cells
      grid_sized_for_ = out_.points.size();
      grid_h_ = std::min(grid_h_, cell_size_for(out_.points, opt_.size, grid_sized_for_));
      // cell_size_for sizes cells as if the points filled their box; boundary points fill a
      // surface, about count^(1/3) to a cell of that size, so halve the cells until an occupied
      // one holds about 4 (every ball test reads the crowded cells about it)
      for (;;) {
        hash_grid<D> fine(out_.points[0], grid_h_);
        for (vertex_id w = 0; w < out_.points.size(); ++w) fine.insert(w, out_.points[w]);
        if (out_.points.size() <= 4 * fine.occupied() || grid_h_ < 1e-6 * model_size_) break;
        grid_h_ *= 0.5;
      }
      grid_ = grid_levels<D>(out_.points[0], grid_h_, extent_of(out_.points));
      for (vertex_id w = 0; w < out_.points.size(); ++w) grid_.insert(w, out_.points[w]);
    } else {
      grid_.insert(v, q);
    }
    for (std::size_t k = 0; k < D; ++k) box_lo_[k] = std::min(box_lo_[k], q[k]), box_hi_[k] = std::max(box_hi_[k], q[k]);
    return v;
  }

 public:

  /// Registers PLC edge (u,v) once; returns its index.
  std::uint32_t edge_id(vertex_id u, vertex_id v, std::size_t line) {
    if (u == v) throw conform_error(plc_.source + ":" + std::to_string(line) + ": degenerate edge (repeated vertex " + std::to_string(u + 1) + ")");
    const auto key = std::minmax(u, v);
    auto [it, fresh] = edge_index_.try_emplace({key.first, key.second}, static_cast<std::uint32_t>(edges_.size()));
    if (fresh) {
      edges_.push_back({key.first, key.second, {key.first, key.second}, {}});
      vertex_edges_[key.first].push_back(it->second);
      vertex_edges_[key.second].push_back(it->second);
    }
    return it->second;
  }

  /// True if a point lies within ratio * scale of q (scale: the size of the element q splits), or
  /// within 1e-11 of the model size. With ratio 1e-8, a split point there would be the same point
  /// (an encroacher rotated onto its image of an earlier split, an ulp away): it would not end the
  /// encroachment, and the next round would make it again; and a slanted facet's plane coordinates
  /// (rounded once, front::wrap_frame) cannot tell points that close apart. The split point is a
  /// construction, so this bound decides no topology.
  bool occupied(const point<D>& q, double scale, double ratio = 1e-8) const {
    const double r = std::max(ratio * scale, 1e-11 * model_size_);
    point<D> lo, hi;
    for (std::size_t k = 0; k < D; ++k) lo[k] = q[k] - r, hi[k] = q[k] + r;
    return !grid_.for_box(lo, hi).visit(lo, hi, [&](vertex_id y) { return squared_distance(out_.points[y], q) > r * r; });
  }
  /// occupied(q, scale, near_ratio): a point beside q, closer than this fraction of the local
  /// scale (conform_facets, rotations' images)
  static constexpr double near_ratio = 1e-3;

  /// The angle below which an input angle is small (acute_): 60 degrees in 2D, where Ruppert's
  /// proof covers every angle from 60 up; 62 in 3D, where no theory covers angles between 60 and
  /// 90 and a CAD "60 degrees" arrives rounded to either side: scad_example001 has two facets at
  /// 60.13 degrees about a vertex, and at --quality 1.414 one round split the five edges there
  /// down to 1e-9 from it (26 halvings, 3,469 point pairs closer than 1e-5 in the mesh; with a
  /// ball there, 21). docs/design-decisions.md, "A margin over 60 degrees for small angles in 3D".
  static constexpr double acute_cos = D == 3 ? 0.46947156278589086 : 0.5;  // cos 62, cos 60
  static constexpr std::uint32_t no_edge = ~std::uint32_t{0};
  static constexpr double acute_sin = 0.8829475928589269;                 // sin 62 (3D only)
  /// 3D: facets meeting at an edge fold by less than this (15 degrees, cos) are a smooth surface
  /// there; a vertex all of whose edges are such gets no protecting ball for its small angles
  /// (find_acute3). docs/design-decisions.md, "A vertex inside a smooth surface gets no protecting
  /// ball": 30 degrees spared more points on the corpus but left a sliver at a guard.
  static constexpr double flat_cos = 0.96592582628906831;  // cos 15
  /// Marks the PLC vertices where two PLC edges meet at less than the small angle (60 degrees
  /// in 2D, 62 in 3D): their edges are split on concentric shells (the `shell` rule action).
  void find_acute() {
    const auto& p = out_.points;
    acute_.assign(out_.plc_points, 0);
    for (const auto& [v, es] : vertex_edges_) {
      std::vector<point<D>> dirs;
      for (auto e : es) {
        const point<D> d = p[edges_[e].u == v ? edges_[e].v : edges_[e].u] - p[v];
        dirs.push_back((1.0 / std::sqrt(dot(d, d))) * d);
      }
      for (std::size_t i = 0; i < dirs.size() && !acute_[v]; ++i)
        for (std::size_t j = i + 1; j < dirs.size(); ++j)
          if (dot(dirs[i], dirs[j]) > acute_cos) acute_[v] = 1;
    }
  }

  /// Uniform pre-split of every PLC edge longer than the target size.
  /// The radius of vertex v's protecting ball, 0 if it has none.
  double ball(vertex_id v) const { return v < ball_.size() ? ball_[v] : 0; }

  /// Every PLC edge split where it leaves the protecting balls of its ends, and with a size
  /// uniformly (points in or near a ball left out).
  void presplit_edges() {
    for (std::uint32_t e = 0; e < edges_.size(); ++e) {
      const auto& E = edges_[e];
      const point<D> pu = out_.points[E.u], pv = out_.points[E.v];
      const double len = distance(pu, pv), ru = ball(E.u), rv = ball(E.v);
      std::vector<std::pair<double, point<D>>> at;  // (distance from u, point)
      if (ru > 0) at.push_back({ru, on_edge(pu + (ru / len) * (pv - pu), e)});
      if (rv > 0) at.push_back({len - rv, on_edge(pv + (rv / len) * (pu - pv), e)});
      if (opt_.size > 0 && !graded()) {
        // from the lexicographically smaller end, so parallel edges get identical (mirror) splits
        point<D> a = pu, b = pv;
        const bool flip = lex_less(b, a);
        if (flip) std::swap(a, b);
        const auto n = static_cast<int>(std::ceil(len / edge_size(e) - 1e-9));
        point<D> sheared = n > 1 ? edge_shear(e) : point<D>{};
        if (std::sqrt(dot(sheared, sheared)) > 0.05 * len / n) sheared = point<D>{};
        for (int i = 1; i < n; ++i) {
          const double t = static_cast<double>(i) / n, s = (flip ? 1 - t : t) * len;
          if ((ru > 0 && s < 1.5 * ru) || (rv > 0 && len - s < 1.5 * rv)) continue;
          // sheared along the edge as the slanted planes through it are (state3::edge_shear), the
          // same for every point of the edge, and never by more than a twentieth of a piece
          point<D> q = a + t * (b - a);
          if (dot(sheared, sheared) > 0) q = q + sheared;
          at.push_back({s, on_edge(q, e, len / n)});
        }
      } else if (graded()) {
        // graded: n pieces at equal steps of the integral of 1/h along the edge (sampled a
        // quarter of the local size apart, trapezoids), from the lexicographically smaller end
        point<D> a = pu, b = pv;
        const bool flip = lex_less(b, a);
        if (flip) std::swap(a, b);
        std::vector<std::pair<double, double>> cum{{0.0, 0.0}};  // (t, integral up to t)
        double t = 0, ha = size_at(a);
        while (t < 1) {
          const double step = std::max(0.25 * ha / len, 1e-6);
          const double t2 = std::min(1.0, t + step);
          const double hb = size_at(a + t2 * (b - a));
          cum.push_back({t2, cum.back().second + 0.5 * (t2 - t) * len * (1 / ha + 1 / hb)});
          t = t2, ha = hb;
        }
        const double total = cum.back().second;
        const auto n = static_cast<long>(std::ceil(total - 1e-9));
        std::size_t k = 1;
        for (long i = 1; i < n; ++i) {
          const double want = total * static_cast<double>(i) / static_cast<double>(n);
          while (k + 1 < cum.size() && cum[k].second < want) ++k;
          const auto [t0, c0] = cum[k - 1];
          const auto [t1, c1] = cum[k];
          const double ti = c1 > c0 ? t0 + (t1 - t0) * (want - c0) / (c1 - c0) : t1;
          const double s = (flip ? 1 - ti : ti) * len;
          if ((ru > 0 && s < 1.5 * ru) || (rv > 0 && len - s < 1.5 * rv)) continue;
          at.push_back({s, on_edge(a + ti * (b - a), e, len / static_cast<double>(n))});
        }
      }
      std::sort(at.begin(), at.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      std::vector<vertex_id> chain{E.u};
      for (const auto& [s, q] : at) chain.push_back(add_point(q, {home::edge, e}));
      chain.push_back(E.v);
      edges_[e].chain = std::move(chain);
    }
  }

  /// Subsegment i of edge e runs from an end to where it leaves that end's protecting ball: it is
  /// never split (nothing lies in the ball to encroach it).
  bool protected_subsegment(std::uint32_t e, std::size_t i) const {
    const auto& E = edges_[e];
    return (i == 0 && ball(E.u) > 0) || (i + 2 == E.chain.size() && ball(E.v) > 0);
  }

  /// The box of the ball (c, r) within the bounding box of all points (no cell outside holds one).
  void ball_box(const point<D>& c, double r, point<D>& lo, point<D>& hi) const {
    for (std::size_t k = 0; k < D; ++k) lo[k] = std::max(c[k] - r, box_lo_[k]), hi[k] = std::min(c[k] + r, box_hi_[k]);
  }

  /// Whether point y in the diametral ball of a subsegment of PLC edge e asks for its split. In 2D
  /// always. In 3D not where e is smooth (two facets folding by less than 15 degrees) between two
  /// vertices inside a smooth surface, and y is a PLC vertex of a facet through e that is convex
  /// at e, or a point on an edge of that facet that meets e at 60 degrees or more (or not at all):
  /// every point of a facet convex at e lies on one side of e's line, so the subsegment is an
  /// edge of the facet's Delaunay triangulation (its wrap) whatever such points encroach, and the
  /// 3D Delaunay property comes from the subfacets through it, whose balls are checked against
  /// every point. Points inside the facet, free points, and points on edges at smaller angles
  /// (the shells keep those from descending) count as before. Why: docs/design-decisions.md,
  /// "Subsegments of a smooth surface are not split for their own facets' corners".
  bool counts_against(std::uint32_t e, vertex_id y) const {
    if constexpr (D == 2) {
      return true;
    } else {
      const auto& E = edges_[e];
      if (e >= smooth_edge_.size() || !smooth_edge_[e] || E.u >= flat_vertex_.size() || !flat_vertex_[E.u] ||
          E.v >= flat_vertex_.size() || !flat_vertex_[E.v])
        return true;
      const home h = out_.homes[y];
      if (h.kind != home::vertex && h.kind != home::edge) return true;
      for (auto f : E.facets) {
        if (std::binary_search(facet_reflex_[f].begin(), facet_reflex_[f].end(), e)) continue;
        if (h.kind == home::vertex ? std::binary_search(facet_corners_[f].begin(), facet_corners_[f].end(), y)
                                   : std::binary_search(facet_edges_[f].begin(), facet_edges_[f].end(), h.id) && wide(e, h.id))
          return false;
      }
      return true;
    }
  }

  /// 3D: PLC edges e and e2 share no vertex, or meet at one at 60 degrees or more (e2 != e).
  bool wide(std::uint32_t e, std::uint32_t e2) const {
    const auto& A = edges_[e];
    const auto& B = edges_[e2];
    if (e == e2) return false;
    const vertex_id s = A.u == B.u || A.u == B.v ? A.u : A.v == B.u || A.v == B.v ? A.v : no_vertex;
    if (s == no_vertex) return true;
    const auto& p = out_.points;
    const point<D> d1 = p[A.u == s ? A.v : A.u] - p[s], d2 = p[B.u == s ? B.v : B.u] - p[s];
    return dot(d1, d2) <= 0.5 * std::sqrt(dot(d1, d1) * dot(d2, d2));
  }

  /// Vertices on the diametral sphere of (a,b) or strictly inside: returns an encroacher, the one
  /// of smallest id in the nearest ring of grid cells about the ball's centre that holds one
  /// (deterministic; a large ball is not scanned whole), or no_vertex. Given the subsegment's PLC
  /// edge e, only vertices that count against it (counts_against).
  vertex_id segment_encroacher(vertex_id a, vertex_id b, std::vector<vertex_id>& ties, std::uint32_t e = no_edge) const {
    const auto& p = out_.points;
    const auto [c, r] = detail::diametral_bound(p[a], p[b]);
    point<D> lo, hi;
    ball_box(c, r, lo, hi);
    vertex_id strict = no_vertex;
    ties.clear();
    const double r2 = r * r;
    grid_.for_box(lo, hi).visit_rings(c, lo, hi, [&](vertex_id y) {
      if (y == a || y == b || (strict != no_vertex && y > strict)) return;
      if (squared_distance(c, p[y]) > r2) return;  // double prefilter, padded
      if (e != no_edge && !counts_against(e, y)) return;
      const int s = geometry::in_diametral(p[a], p[b], p[y]);
      if (s > 0) strict = y;
      else if (s == 0) ties.push_back(y);
    }, [&] { return strict != no_vertex; });
    if (strict != no_vertex) return strict;
    if (ties.empty()) return no_vertex;
    std::sort(ties.begin(), ties.end());
    bool ok;
    if constexpr (D == 2)
      ok = detail::edge_in_cocircular_dt(p, a, b, ties);
    else
      ok = detail::edge_in_cospherical_dt(p, a, b, ties);
    return ok ? no_vertex : ties.front();
  }

  /// PLC edges sharing a vertex with edge e, by shared vertex.
  std::optional<vertex_id> shared_vertex(std::uint32_t e, const home& h) const {
    const auto& E = edges_[e];
    auto touches = [&](vertex_id w) -> std::optional<vertex_id> {
      for (vertex_id s : {E.u, E.v})
        if (s == w) return s;
      return std::nullopt;
    };
    if (h.kind == home::vertex) {
      for (auto f : vertex_edges_.count(h.id) ? vertex_edges_.at(h.id) : std::vector<std::uint32_t>{})
        for (vertex_id s : {edges_[f].u, edges_[f].v})
          if (auto t = touches(s); t && s != h.id) return t;
      return std::nullopt;
    }
    if (h.kind == home::edge) {
      if (auto t = touches(edges_[h.id].u)) return t;
      return touches(edges_[h.id].v);
    }
    return std::nullopt;
  }

  /// Splits subsegment chain[i], chain[i+1] of edge e, encroached by y. Returns true on a split.
  void split_segment(std::uint32_t e, std::size_t i, vertex_id y) {
    auto& E = edges_[e];
    const vertex_id a = E.chain[i], b = E.chain[i + 1];
    const auto& p = out_.points;
    // a vertex exactly on the open subsegment becomes a boundary vertex
    if (on_open_segment(p[a], p[b], p[y]) && out_.homes[y].kind == home::free) {
      out_.homes[y] = {home::edge, e};
      E.chain.insert(E.chain.begin() + static_cast<long>(i) + 1, y);
      return;
    }
    relation rel = relation::free;
    std::optional<vertex_id> shared;
    const home h = out_.homes[y];
    if (h.kind == home::edge && h.id == e) {
      rel = relation::on_carrier;
    } else if ((shared = shared_vertex(e, h))) {
      rel = relation::on_incident_vertex;
    } else if constexpr (D == 3) {
      if (h.kind == home::facet &&
          std::find(E.facets.begin(), E.facets.end(), h.id) != E.facets.end())
        rel = relation::on_incident_edge;
    }
    std::optional<rules::split_action> fired;
    point<D> q = subsegment_split(e, i, rel, p[y], shared ? &p[*shared] : nullptr, fired);
    if (h.kind == home::edge && h.id != e && fired && *fired == rules::split_action::project) {
      // the projection of another edge's point (a rim's edge pair): this edge's shear in place of
      // that edge's (state3::edge_shear), along this edge, if it stays well inside the subsegment
      const point<D> d = p[b] - p[a], c = edge_shear(e) - edge_shear(h.id);
      const point<D> along = (dot(c, d) / dot(d, d)) * d;
      if (dot(along, along) > 0 && dot(along, along) < 0.0025 * dot(d, d)) {
        const point<D> q2 = on_edge(q + along, e, std::sqrt(dot(d, d)));
        if (q2 != p[a] && q2 != p[b] && dot(q2 - p[a], d) > 0 && dot(q2 - p[b], d) < 0 && !occupied(q2, std::sqrt(dot(d, d)))) q = q2;
      }
    }
    if constexpr (D == 3) count_split(element_kind::subsegment, rel, fired);
    const vertex_id m = add_point(q, {home::edge, e});
    E.chain.insert(E.chain.begin() + static_cast<long>(i) + 1, m);
  }

  /// The split point of subsegment chain[i], chain[i+1] of edge e for an encroacher at `enc`:
  /// the rule's point, on the edge (on_edge). A subsegment with exactly one end at a small-angle
  /// PLC vertex gets that vertex as the centre of the `shell` action. The point must lie strictly
  /// inside the subsegment and differ from its ends; when rounding leaves no such point the
  /// subsegment is too short to split in double precision, which is an error, not a loop.
  point<D> subsegment_split(std::uint32_t e, std::size_t i, relation rel, const point<D>& enc, const point<D>* shared,
                            std::optional<rules::split_action>& fired) const {
    const auto& E = edges_[e];
    const auto& p = out_.points;
    const vertex_id a = E.chain[i], b = E.chain[i + 1];
    // shells about a small-angle end: for the subsegment at it (also from where the edge leaves
    // its protecting ball), and for any subsegment an edge sharing that end encroaches, so that
    // the edges meeting there are split at the same dyadic distances from it and stop encroaching
    // one another (midpoints of edges of different lengths do not match, and cascaded along edges
    // meeting at a fraction of a degree: scad_example002 14,724 Steiner points, now 8,778)
    const bool at_u = (a == E.u && acute_[E.u]) || (i == 1 && ball(E.u) > 0),
               at_v = (b == E.v && acute_[E.v]) || (i + 3 == E.chain.size() && ball(E.v) > 0);
    const point<D>* shell = at_u != at_v ? &p[at_u ? E.u : E.v] : nullptr;
    if (!shell && rel == relation::on_incident_vertex && shared) {
      if (*shared == p[E.u] && (acute_[E.u] || ball(E.u) > 0)) shell = &p[E.u];
      if (*shared == p[E.v] && (acute_[E.v] || ball(E.v) > 0)) shell = &p[E.v];
    }
    const double len = distance(p[a], p[b]);
    const point<D> q = on_edge(split_point_of(element_kind::subsegment, rel, {p[a], p[b]}, enc, shared, nullptr, shell, fired), e, len);
    auto strictly_inside = [&](const point<D>& x) {
      return x != p[a] && x != p[b] && dot(x - p[a], p[b] - p[a]) > 0 && dot(x - p[b], p[a] - p[b]) > 0;
    };
    const double l = len;
    if (strictly_inside(q) && !occupied(q, l)) return q;
    const point<D> m = on_edge(0.5 * (p[a] + p[b]), e, len);
    fired = rules::split_action::midpoint;
    if (strictly_inside(m) && !occupied(m, l)) return m;
    throw conform_error(plc_.source + ": the boundary segment between vertices " + std::to_string(a + 1) + " and " +
                        std::to_string(b + 1) + " (on the input edge " + std::to_string(E.u + 1) + "-" +
                        std::to_string(E.v + 1) + ", length " + std::to_string(distance(p[a], p[b])) +
                        ") is too short to split in double precision: the input has features (or a small angle "
                        "near that edge) too fine for its coordinates");
  }
  /// split_at without the trace count (const: subfacet splits are planned in parallel); `fired`
  /// receives the action of the rule step that gave the point.
  point<D> split_point_of(element_kind kind, relation rel, const std::vector<point<D>>& elem, const point<D>& enc,
                          const point<D>* shared, const std::array<point3, 2>* shared_edge, const point<D>* shell,
                          std::optional<rules::split_action>& fired,
                          const std::function<bool(const point<D>&)>* in_facet = nullptr) const {
    const rules::split_rule* r = rules_->split.lookup(kind, rel);
    if (!r) throw conform_error("conformer rules have no rule for " + std::string(rules::to_string(kind)) + "/" +
                                std::string(rules::to_string(rel)));
    // a candidate on an existing point is no split (occupied()): the rule's next action is tried
    double scale = 1e300;
    for (std::size_t i = 0; i < elem.size(); ++i)
      for (std::size_t j = i + 1; j < elem.size(); ++j) scale = std::min(scale, distance(elem[i], elem[j]));
    // and a subfacet's point from a projection or rotation must lie in the facet (else the next
    // action: the circumcentre, which when outside splits the subsegment it encroaches)
    auto usable = [&](const point<D>& q, rules::split_action a) {
      if (in_facet && a != rules::split_action::midpoint && !(*in_facet)(q)) return false;
      return !occupied(q, scale);
    };
    if constexpr (D == 2) {
      std::optional<point2> sv;
      if (shared) sv = *shared;
      const std::array<point2, 2> s{elem[0], elem[1]};
      std::optional<point2> sc;
      if (shell) sc = *shell;
      if (auto c = rules::split_point(*r, std::span<const point2, 2>(s), enc, sv, sc, usable)) {
        fired = c->action;
        return c->action == rules::split_action::project ? exact_projection(c->at, elem, enc) : c->at;
      }
    } else {
      rules::shared3 sh;
      if (shared) sh.vertex = *shared;
      if (shared_edge) sh.edge = *shared_edge;
      if (shell) sh.shell = *shell;
      if (auto c = rules::split_point(*r, std::span<const point3>(elem), enc, sh, usable)) {
        fired = c->action;
        return c->action == rules::split_action::project ? exact_projection(c->at, elem, enc) : c->at;
      }
    }
    // the validator guarantees a final unconditional midpoint; reaching here means a custom set
    // without it
    point<D> m{};
    for (const auto& q : elem) m = m + (1.0 / static_cast<double>(elem.size())) * q;
    return m;
  }
  void count_split(element_kind kind, relation rel, const std::optional<rules::split_action>& fired) {
    if (trace_on_ && fired)
      ++trace_[std::string(rules::to_string(kind)) + "/" + std::string(rules::to_string(rel)) + "/" + std::string(rules::to_string(*fired))];
  }

  /// On an axis-aligned element the orthogonal projection of p only replaces the element's constant
  /// coordinates: done that way it is exact, so a point and its projection on a parallel carrier
  /// are exact mirror images (rounding would leave them an ulp apart and make flat slivers).
  static point<D> exact_projection(const point<D>& rounded, const std::vector<point<D>>& elem, const point<D>& p) {
    point<D> q = p;
    std::size_t varying = 0;
    for (std::size_t k = 0; k < D; ++k) {
      bool constant = true;
      for (const auto& e : elem) constant = constant && e[k] == elem[0][k];
      if (constant)
        q[k] = elem[0][k];
      else
        ++varying;
    }
    return varying + 1 == elem.size() ? q : rounded;
  }

  /// Coordinates that are constant along the carrier stay exact, so split points of axis-aligned
  /// edges and facets lie exactly on them (no rounding off the input plane).
  static point<D> snap_to_edge(point<D> q, const point<D>& a, const point<D>& b) {
    for (std::size_t k = 0; k < D; ++k)
      if (a[k] == b[k]) q[k] = a[k];
    return q;
  }

  /// A split point of PLC edge e. Coordinates constant along the edge are copied exactly. In 3D a
  /// point of a slanted edge is on its line only up to rounding; it is moved by a few ulps, if
  /// need be, so that it lies in the closed region of one of the edge's facets in every
  /// coordinate projection (exact orientations against the edge's end vertices): a point
  /// rounded to the outside of every facet through the edge would belong to none of them.
  point<D> on_edge(point<D> q, std::uint32_t e, double scale = 0) const {
    const auto& E = edges_[e];
    const point<D>&a = out_.points[E.u], &b = out_.points[E.v];
    q = snap_to_edge(q, a, b);
    if constexpr (D == 3) {
      // along an edge parallel to no axis, off the exact split point by a pseudo-random 1e-10 of
      // the subsegment (detail::jitter): see the design decision on slanted carriers
      int constant = 0;
      for (std::size_t k = 0; k < 3; ++k) constant += a[k] == b[k];
      if (constant < 2 && scale > 0) q = snap_to_edge(q + (1e-10 * scale * detail::jitter(q)[0]) * (1.0 / distance(a, b)) * (b - a), a, b);
      auto inside = [&](const point3& x) {
        for (int k = 0; k < 3; ++k) {
          const int want = E.inside_sign[static_cast<std::size_t>(k)];
          if (want == 0) continue;
          const int o = geometry::orient_projected(a, b, x, k);
          if (o != 0 && o != want) return false;
        }
        return true;
      };
      if (inside(q) || dot(E.inward, E.inward) == 0) return q;
      double step = detail::magnitude(q) * detail::eps;
      for (int i = 0; i < 64; ++i, step *= 2) {
        point3 x = snap_to_edge(q + step * E.inward, a, b);
        if (inside(x)) return x;
      }
    }
    return q;
  }

  static bool on_open_segment(const point<D>& a, const point<D>& b, const point<D>& y) {
    if constexpr (D == 2) {
      if (geometry::orient2d(a, b, y) != 0) return false;
    } else {
      if (!geometry::collinear(a, b, y)) return false;
    }
    return dot(y - a, b - a) > 0 && dot(y - b, a - b) > 0;  // between (exact for collinear points)
  }

  /// Phase A: split subsegments until none is encroached. Returns the number of splits.
  std::size_t conform_segments() {
    index_edge_balls();
    std::size_t splits = 0;
    std::vector<vertex_id> ties;
    std::size_t upto = segments_clean_upto_;
    for (bool again = true; again;) {
      again = false;
      // which edges have an encroached subsegment, checked in parallel: the sequential pass below
      // skips the others as long as no split has added a point that might encroach them. A
      // subsegment between points older than `upto` was clean then (at the last call's end, or
      // at the start of the last pass, which checked every subsegment): only a point inserted
      // since can encroach it (closed ball: a new tie counts)
      const auto& p = out_.points;
      const std::size_t pass_start = p.size();
      recent_points<D> recent(p[0], grid_h_, true);
      for (std::size_t v = upto; upto > 0 && v < p.size(); ++v) recent.add(static_cast<vertex_id>(v), p[v]);
      recent.freeze();
      // the edges to look at: all on the first call; after that, those with a subsegment end
      // inserted since `upto` (want 1), and those whose ball holds a recent point or that are too
      // long for the index (want 2). The others' subsegments are between old points, and no
      // recent point lies in the edge's ball, which holds each subsegment's: they are clean.
      std::vector<char> want(edges_.size(), upto == 0 ? 1 : 0);
      if (upto > 0) {
        for (std::uint32_t e : ball_big_) want[e] = 2;
        for (std::size_t v = upto; v < pass_start; ++v) edges_near(p[v], [&](std::uint32_t e) { want[e] = 2; });
        // the edges whose chain holds a point inserted since: a chain's points between its ends
        // are those whose home is that edge, and its ends are PLC vertices, older than any `upto`
        // (the new points' homes are read, not every chain: a pass over the Gmsh torus's 48,000
        // chains was 8% of its refinement's tail; docs/benchmarks.md, seventieth part)
        for (std::size_t v = upto; v < pass_start; ++v)
          if (const home& h = out_.homes[v]; h.kind == home::edge && !want[h.id]) want[h.id] = 1;
      }
      std::vector<std::uint32_t> todo;
      for (std::uint32_t e = 0; e < edges_.size(); ++e)
        if (want[e]) todo.push_back(e);
      std::vector<char> encroached(edges_.size(), 0);
      for_each(execution::par(opt_.threads), todo, [&](std::uint32_t e) {
        std::vector<vertex_id> scratch;
        const auto& ch = edges_[e].chain;
        // no recent point near the whole edge: none near a subsegment between old points
        const bool far = want[e] != 2 || !near_edge(recent, e);
        for (std::size_t i = 0; i + 1 < ch.size() && !encroached[e]; ++i) {
          const vertex_id a = ch[i], b = ch[i + 1];
          if (a < upto && b < upto) {
            if (!far) encroached[e] = near_subsegment(recent, a, b);
          } else {
            encroached[e] = segment_encroacher(a, b, scratch, e) != no_vertex;
          }
        }
      }, [&](std::uint32_t e) { return static_cast<double>(edges_[e].chain.size()); });
      // an edge found clean above can be encroached only by a point split in since: it is checked
      // again only if one of those lies in the closed ball of one of its subsegments (so in the
      // edge's ball: `hit`, or the edge is too long for the index)
      recent_points<D> added(p[0], 2 * grid_h_);
      std::vector<char> hit(edges_.size(), 0);
      for (std::uint32_t e : ball_big_) hit[e] = 1;
      auto touched = [&](std::uint32_t e) {
        if (!hit[e] || !near_edge(added, e)) return false;
        const auto& ch = edges_[e].chain;
        for (std::size_t i = 0; i + 1 < ch.size(); ++i)
          if (near_subsegment(added, ch[i], ch[i + 1])) return true;
        return false;
      };
      // A subsegment between points older than `upto` is encroached only by a point of `recent`
      // or `added` in its closed ball (as in the parallel pass above): one without is not searched
      // again. (Each encroached edge's subsegments were all searched here, and an edge of hundreds
      // of them by a small input angle was searched whole for each split: on occ_pump_nut at
      // --quality 1.414 these searches were a fifth of the run, all on one thread;
      // docs/benchmarks.md, sixty-eighth part)
      auto clean_since = [&](vertex_id a, vertex_id b) {
        return a < upto && b < upto && !near_subsegment(recent, a, b) && (added.empty || !near_subsegment(added, a, b));
      };
      for (std::uint32_t e = 0; e < edges_.size(); ++e) {
        if (!encroached[e] && (added.empty || !touched(e))) continue;
        for (std::size_t i = 0; i + 1 < edges_[e].chain.size();) {
          const vertex_id a = edges_[e].chain[i], b = edges_[e].chain[i + 1];
          const vertex_id y = protected_subsegment(e, i) || clean_since(a, b) ? no_vertex : segment_encroacher(a, b, ties, e);
          if (y == no_vertex) {
            ++i;
            continue;
          }
          const std::size_t n0 = p.size();
          split_segment(e, i, y);  // then re-check the first half, now at position i
          for (std::size_t v = n0; v < p.size(); ++v) {
            added.add(static_cast<vertex_id>(v), p[v]);
            edges_near(p[v], [&](std::uint32_t f) { hit[f] = 1; });
          }
          ++splits;
          again = true;
        }
      }
      upto = pass_start;
    }
    segments_clean_upto_ = out_.points.size();  // no subsegment is encroached by any point now
    return splits;
  }

  /// A ball about PLC edge e that holds the diametral bound of each of its subsegments (their
  /// points lie on the edge up to rounding): centre and radius.
  std::pair<point<D>, double> edge_ball(std::uint32_t e) const {
    const auto& p = out_.points;
    const auto& E = edges_[e];
    const point<D> c = 0.5 * (p[E.u] + p[E.v]);
    const double l = distance(p[E.u], p[E.v]);
    return {c, 0.5 * l * (1 + 1e-6) + 1e-6 * l + 64 * detail::eps * detail::magnitude(c) + 1e-300};
  }

  /// False if no point of g lies near PLC edge e (in the box of all of g's points that meets
  /// edge_ball(e)): a prefilter that spares a pass over the edge's subsegments (their balls, each
  /// one's box test).
  bool near_edge(const recent_points<D>& g, std::uint32_t e) const {
    if (g.empty) return false;
    const auto [c, r] = edge_ball(e);
    return g.near(c, r);
  }

  /// The PLC edges' balls (edge_ball), which never move, filed in a hash grid by the cells their
  /// boxes meet, so that a pass asks "which edges' balls hold this recent point" once per point
  /// instead of a search per edge (a round that adds points all over a curved surface puts every
  /// edge in the box of the recent points; the torus's 58k edges cost 10 ms a pass that way).
  /// Edges whose box meets more than 64 cells (long ones, against the cell: the 75th percentile
  /// of the balls' diameters) are not filed: they go in ball_big_ and are always looked at.
  void index_edge_balls() {
    if (ball_grid_ && ball_indexed_ == edges_.size()) return;
    ball_indexed_ = edges_.size();
    ball_c_.resize(edges_.size());
    ball_r2_.resize(edges_.size());
    ball_big_.clear();
    std::vector<double> d(edges_.size());
    for (std::uint32_t e = 0; e < edges_.size(); ++e) {
      const auto [c, r] = edge_ball(e);
      ball_c_[e] = c, ball_r2_[e] = r * r, d[e] = 2 * r;
    }
    double s = 1;
    if (!d.empty()) {
      auto q = d.begin() + static_cast<long>(3 * d.size() / 4);
      std::nth_element(d.begin(), q, d.end());
      if (*q > 0 && std::isfinite(*q)) s = *q;
    }
    ball_grid_.emplace(out_.points[0], s);
    for (std::uint32_t e = 0; e < edges_.size(); ++e) {
      const double r = std::sqrt(ball_r2_[e]);
      point<D> lo, hi;
      for (std::size_t k = 0; k < D; ++k) lo[k] = ball_c_[e][k] - r, hi[k] = ball_c_[e][k] + r;
      const auto a = ball_grid_->cell_of(lo), b = ball_grid_->cell_of(hi);
      double cells = 1;
      for (std::size_t k = 0; k < D; ++k) cells *= static_cast<double>(b[k] - a[k] + 1);
      if (cells > 64) {
        ball_big_.push_back(e);
      } else {
        ball_grid_->insert_box(e, lo, hi);
      }
    }
  }

  /// f(e) for every filed PLC edge whose ball holds q (the same test as near_edge's for one
  /// point; the edges in ball_big_ are not asked).
  template <class F>
  void edges_near(const point<D>& q, F&& f) const {
    ball_grid_->visit(q, q, [&](std::uint32_t e) {
      double d2 = 0;
      for (std::size_t k = 0; k < D; ++k) {
        const double x = ball_c_[e][k] - q[k];
        d2 += x * x;
      }
      if (d2 <= ball_r2_[e]) f(e);
    });
  }

  /// Whether a point of g lies in the closed diametral ball of subsegment ab (a tie counts).
  bool near_subsegment(const recent_points<D>& g, vertex_id a, vertex_id b) const {
    const auto& p = out_.points;
    const auto [c, r] = detail::diametral_bound(p[a], p[b]);
    if (!g.near(c, r)) return false;
    return !g.visit_ball(c, r, [&](vertex_id y) {
      return squared_distance(c, p[y]) > r * r || geometry::in_diametral(p[a], p[b], p[y]) < 0;
    });
  }

 protected:
  const plc<D>& plc_;
  options opt_;
  boundary<D> out_;
  double grid_h_;
  grid_levels<D> grid_;
  std::size_t grid_sized_for_ = 0;  // points the cell size was chosen for
  point<D> box_lo_{}, box_hi_{};  // bounding box of all points
  double model_size_ = 1;         // diagonal of the PLC's bounding box
  rules::rule_set own_rules_;
  const rules::rule_set* rules_;
  std::vector<plc_edge> edges_;
  // 3D, for counts_against: per facet, its constraint edges, those at which it is not convex
  // (a PLC vertex of it strictly on each side of the edge's line) and its PLC vertices, sorted;
  // per edge, whether it is smooth (two facets folding by less than 15 degrees); per PLC vertex,
  // whether it lies inside a smooth surface (every edge through it smooth)
  std::vector<std::vector<std::uint32_t>> facet_edges_, facet_reflex_;
  std::vector<std::vector<vertex_id>> facet_corners_;
  std::vector<char> smooth_edge_, flat_vertex_;
  std::map<std::pair<vertex_id, vertex_id>, std::uint32_t> edge_index_;
  std::map<vertex_id, std::vector<std::uint32_t>> vertex_edges_;
  std::size_t segments_clean_upto_ = 0;  // points when conform_segments last returned
  std::optional<hash_grid<D>> ball_grid_;  // index_edge_balls: PLC edges by their balls' cells
  std::size_t ball_indexed_ = 0;           // edges_.size() when it was built
  std::vector<point<D>> ball_c_;           // per PLC edge: edge_ball's centre
  std::vector<double> ball_r2_;            // and squared radius
  std::vector<std::uint32_t> ball_big_;    // edges not filed (their boxes meet too many cells)
  std::vector<char> acute_;               // per PLC vertex: a small angle meets there (find_acute)
  std::vector<double> ball_;              // per PLC vertex: radius of its protecting ball, 0 for none
  std::vector<char> ball_wanted_;         // 3D, per PLC vertex: it gets a protecting ball (find_acute3)
  std::vector<double> guard_;             // 3D, per PLC vertex without a ball where a small angle meets: the radius it would have
  // GSSE_CONFORM_TRACE=1: per round, the number of splits and which rule/action fired how often
  bool trace_on_ = std::getenv("GSSE_CONFORM_TRACE") != nullptr;
  std::map<std::string, std::size_t> trace_;
};

// ------------------------------------------------------------------------------------------ 3D
struct facet_state {
  int axis = 2;
  std::uint32_t source = 0;                                        // input facet naming it (first member)
  std::vector<std::pair<std::uint32_t, bool>> sides;               // (edge, forward): facet on the left
  std::vector<vertex_id> interior;                                 // Steiner and embedded points
  std::set<vertex_id> corners;                                     // PLC vertices of the facet
  std::vector<std::array<vertex_id, 2>> seams;                     // merged facets' shared edges (no constraint)
  std::vector<vertex_id> balls;                                    // corners with a protecting ball
  std::vector<std::array<vertex_id, 4>> not_flat;                  // pairs known not to be flat cells (sorted)
  std::vector<vertex_id> flat_checked;                             // `wrapped` at the last flat_pairs
  std::vector<std::array<vertex_id, 3>> triangles;                 // ccw in the projection
  // the triangles by cells of a uniform grid over their projected boxes (locate())
  struct triangle_cells {
    point2 lo{};
    double inv = 1;
    long nx = 0, ny = 0;
    std::vector<std::uint32_t> start, items;
    // places whose triangle changed since the cells were filled, ascending (a few, after local
    // re-wraps; the cells are filled again beyond 64): searched besides the cells. A cell may
    // still list such a place: the triangle there now is tested, so it is only a candidate more
    std::vector<std::uint32_t> extra;
  } cells;
  std::vector<vertex_id> wrapped;                                  // sorted vertices when triangulated
  std::vector<std::array<vertex_id, 2>> wrapped_boundary;          // the boundary edges then
  std::size_t boundary_size = 0;                                   // chain vertices when triangulated
  std::array<bool, 3> constant{};                                  // coordinate shared by all corners
  // a slanted facet's plane (unit normal through the corners' centroid) and an orthonormal frame
  // of it (e1 x e2 = unit) in which it is triangulated (front::wrap_frame)
  point3 unit{}, centre{}, e1{}, e2{};
  // a slanted facet's wall shear (state3::wall_shift): the in-plane direction and the normal its
  // class of parallel planes shares, and that class (-1: none, an axis-aligned facet)
  point3 shear_u{}, shear_n{};
  int shear_class = -1;
  std::array<double, 3> constant_value{};
  // encroachment bookkeeping (see encroachers()): whether `triangles` were all checked at the last
  // check and which were clean then; after a new triangulation, the sorted corners of the old
  // triangles that were clean
  bool checked = false;
  std::vector<char> was_clean;
  // per triangle at the last check (options::delaunay_faces): its equatorial ball held points but
  // it was a Delaunay face all the same (state3::delaunay_face); it is checked again only if a
  // point inserted since lies in `held`
  std::vector<char> relaxed;
  std::vector<std::pair<point3, double>> held;  // per relaxed triangle: the ball a point must enter to break it
  std::vector<vertex_id> apex;                   // per relaxed triangle: x (boundary::face_apex)
  std::vector<char> fresh;  // after a local rewrap since the last check: per triangle, new since
  bool flat_local = false;  // fresh also marks the triangles new since the last flat_pairs
  // per piece of 512 subfacets at the last check: the box of their balls, and whether none was
  // to split then (such a piece stays so until a point is inserted in that box)
  struct piece_summary {
    point3 lo, hi;
    bool quiet;
  };
  std::vector<piece_summary> pieces;
  key_set<3> clean;
  // per triangle, by place, kept while the same triangle stays in its place (local re-wraps keep
  // the undisturbed ones where they were): its equatorial ball bound (detail::equatorial_bound;
  // ball_known 0: not computed yet) and its circle in the wrap's plane coordinates
  // (front::facet_change::circles)
  std::vector<std::pair<point3, double>> ball;
  std::vector<char> ball_known;
  std::vector<std::array<double, 3>> circles;
};

class state3 : public state<3> {
 public:
  state3(const plc<3>& p, const std::vector<point3>& volume, const options& o) : state<3>(p, volume, o) {
    input::facet_options fo;
    fo.merge_coplanar = o.merge_coplanar;
    std::vector<input::facet_region> regions;
    try {
      regions = input::facet_regions(p, fo);
    } catch (const input::input_error& e) {
      throw conform_error(e.what());
    }
    facets_.resize(regions.size());
    for (std::uint32_t f = 0; f < regions.size(); ++f) setup_facet(f, regions[f]);
    find_convexity();
    // each edge's way into its first facet (on_edge)
    for (std::uint32_t f = 0; f < regions.size(); ++f)
      for (auto [e, fw] : facets_[f].sides) {
        auto& E = edges_[e];
        if (dot(E.inward, E.inward) != 0) continue;
        const point3& n = regions[f].normal;
        const point3 d = fw ? out_.points[E.v] - out_.points[E.u] : out_.points[E.u] - out_.points[E.v];
        // the facet lies on the left of d in the projection dropping its axis
        const point3 w = (n[static_cast<std::size_t>(S_axis(f))] > 0 ? 1.0 : -1.0) * cross(n, d);
        E.inward = (1.0 / std::sqrt(dot(w, w))) * w;
        const point3 side = cross(out_.points[E.v] - out_.points[E.u], E.inward);
        const double big = std::max({std::abs(n[0]), std::abs(n[1]), std::abs(n[2])});
        for (std::size_t k = 0; k < 3; ++k)
          E.inside_sign[k] = std::abs(n[k]) >= 0.1 * big ? (side[k] > 0 ? 1 : -1) : 0;
      }
    choose_shear_frames();
    find_acute3();
    find_balls3();
    for (auto& S : facets_)
      for (vertex_id v : S.corners)
        if (ball(v) > 0) S.balls.push_back(v);
  }
  int S_axis(std::uint32_t f) const { return facets_[f].axis; }

  /// Protecting balls (Cohen-Steiner, de Verdiere and Yvinec, "Conforming Delaunay triangulations
  /// in 3D"): a vertex where a small angle meets gets a ball of power-of-two radius, at most a third
  /// of its distance to any feature not through it, half its distance to any volume point and a
  /// third of its shortest edge. Its edges are split where they leave the ball (presplit_edges),
  /// no point is inserted inside it (out_of_balls moves one to its sphere), and the pieces inside
  /// it, a subsegment from the vertex to the sphere or a triangle of the vertex and two points on
  /// the sphere, lie in balls no point enters: they need no split. Shells about the vertex go on
  /// outside. Without it, the splits about a vertex where facets and edges meet at small angles
  /// chase each other towards it, a shell at a time.
  void find_balls3() {
    const auto& p = out_.points;
    const std::size_t n = out_.plc_points;
    ball_.assign(n, 0);
    guard_.assign(n, 0);
    // features near each vertex: PLC edges and facets by the cells of their boxes
    double total = 0;
    for (const auto& E : edges_) total += distance(p[E.u], p[E.v]);
    const double cell = edges_.empty() ? 1.0 : std::max(total / static_cast<double>(edges_.size()), 1e-300);
    hash_grid<3> features(p[0], cell);
    auto box_of = [&](const std::vector<vertex_id>& vs, point3& lo, point3& hi) {
      lo = hi = p[vs[0]];
      for (vertex_id v : vs)
        for (std::size_t k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[v][k]), hi[k] = std::max(hi[k], p[v][k]);
    };
    for (std::uint32_t e = 0; e < edges_.size(); ++e) {
      point3 lo, hi;
      box_of({edges_[e].u, edges_[e].v}, lo, hi);
      features.insert_box(e, lo, hi);
    }
    const auto F = static_cast<std::uint32_t>(edges_.size());
    for (std::uint32_t f = 0; f < facets_.size(); ++f) {
      point3 lo, hi;
      box_of(std::vector<vertex_id>(facets_[f].corners.begin(), facets_[f].corners.end()), lo, hi);
      features.insert_box(F + f, lo, hi);
    }
    for (vertex_id v = 0; v < n; ++v) {
      if (!acute_[v] || !vertex_edges_.count(v)) continue;
      double r = 1e300;
      for (auto e : vertex_edges_.at(v)) r = std::min(r, distance(p[edges_[e].u], p[edges_[e].v]) / 3);
      // other points (PLC vertices, volume points) within 3r
      point3 lo, hi;
      for (std::size_t k = 0; k < 3; ++k) lo[k] = p[v][k] - 3 * r, hi[k] = p[v][k] + 3 * r;
      grid_.for_box(lo, hi).visit(lo, hi, [&](vertex_id y) {
        if (y == v) return;
        const double d = distance(p[y], p[v]);
        r = std::min(r, y < n ? d / 3 : d / 2);
      });
      for (std::size_t k = 0; k < 3; ++k) lo[k] = p[v][k] - 3 * r, hi[k] = p[v][k] + 3 * r;
      features.visit(lo, hi, [&](vertex_id id) {
        if (id < F) {  // an edge not through v: distance to the segment
          const auto& E = edges_[id];
          if (E.u == v || E.v == v) return;
          const point3 a = p[E.u], d = p[E.v] - a;
          const double t = std::clamp(dot(p[v] - a, d) / dot(d, d), 0.0, 1.0);
          r = std::min(r, distance(p[v], a + t * d) / 3);
        } else {  // a facet not through v: distance to its plane, where v projects into it
          const auto& S = facets_[id - F];
          if (S.corners.count(v)) return;
          const double h = std::abs(dot(p[v] - S.centre, S.unit));
          if (h >= 3 * r) return;
          const point3 q = p[v] - dot(p[v] - S.centre, S.unit) * S.unit;
          int wn = 0;  // winding number of the facet's edges about q, in its projection
          const point2 pq = geometry::project(q, S.axis);
          for (auto [e2, fw] : S.sides) {
            point2 a = geometry::project(p[edges_[e2].u], S.axis), b = geometry::project(p[edges_[e2].v], S.axis);
            if (!fw) std::swap(a, b);
            if (a[1] <= pq[1]) {
              if (b[1] > pq[1] && geometry::orient2d(a, b, pq) > 0) ++wn;
            } else if (b[1] <= pq[1] && geometry::orient2d(a, b, pq) < 0) {
              --wn;
            }
          }
          if (wn != 0) r = std::min(r, h / 3);
        }
      });
      // the pieces inside are not split for size (min(h, 2r) / 2 is min(h / 2, r): halving is exact)
      if (sized()) r = std::min(r, size_at(p[v], 2 * r) / 2);
      if (r > 0 && r < 1e300) (ball_wanted_[v] ? ball_ : guard_)[v] = rules::snap_to_shell(r * (1 - 1e-8));
    }
  }

  /// q, or if it lies inside the protecting ball of a corner of facet f, its radial projection
  /// onto that ball's sphere.
  point3 out_of_balls(std::uint32_t f, const point3& q) const {
    for (vertex_id v : facets_[f].balls) {
      const point3 d = q - out_.points[v];
      const double l = std::sqrt(dot(d, d)), r = ball(v);
      if (l < r && l > 0) return out_.points[v] + (r / l) * d;
    }
    return q;
  }

  /// find_acute(), and also vertices where an edge meets a facet through the vertex that does not
  /// contain it at less than 62 degrees (acute_sin), and the ends of edges where two facets fold
  /// at less than 62. ball_wanted_: those that get a protecting ball (find_balls3), all but the
  /// vertices inside a smooth surface.
  void find_acute3() {
    find_acute();
    const auto& p = out_.points;
    // per edge, the way into each facet side at it, across it: facets folding onto each other
    // there (a dihedral angle below 62 degrees) make its ends small-angle vertices; exactly two
    // facets, once each, folding by less than 15 degrees (flat_cos) make it smooth
    std::vector<char> smooth(edges_.size(), 0);
    for (std::uint32_t e = 0; e < edges_.size(); ++e) {
      const auto& E = edges_[e];
      std::vector<std::pair<std::uint32_t, point3>> into;  // (facet, the way into it)
      for (auto f : E.facets)
        for (auto [e2, fw] : facets_[f].sides)
          if (e2 == e) {
            const point3& n = facets_[f].unit;
            const point3 d = fw ? p[E.v] - p[E.u] : p[E.u] - p[E.v];
            into.push_back({f, (n[static_cast<std::size_t>(facets_[f].axis)] > 0 ? 1.0 : -1.0) * cross(n, d)});
          }
      // (the dot product of two of them, and the product of their lengths)
      auto dot_norms = [&](std::size_t i, std::size_t j) {
        const point3 &a = into[i].second, &b = into[j].second;
        return std::pair{dot(a, b), std::sqrt(dot(a, a) * dot(b, b))};
      };
      for (std::size_t i = 0; i < into.size(); ++i)
        for (std::size_t j = i + 1; j < into.size(); ++j)
          if (const auto [ab, l] = dot_norms(i, j); ab > acute_cos * l) {
            if (E.u < acute_.size()) acute_[E.u] = 1;
            if (E.v < acute_.size()) acute_[E.v] = 1;
          }
      if (E.facets.size() == 2 && into.size() == 2 && into[0].first != into[1].first) {
        const auto [ab, l] = dot_norms(0, 1);
        smooth[e] = ab < -flat_cos * l;
      }
    }
    smooth_edge_ = smooth;
    // a vertex inside a smooth surface (every edge through it smooth): its small angles are those
    // of a triangulated surface, the corners of its facets, which the shells about it handle as
    // in 2D; it gets no protecting ball for them, only a guard radius for the refinement (guard_)
    std::vector<char> flat(out_.plc_points, 0);
    for (const auto& [v, es] : vertex_edges_)
      if (v < flat.size()) flat[v] = !es.empty() && std::all_of(es.begin(), es.end(), [&](std::uint32_t e) { return smooth[e] != 0; });
    flat_vertex_ = flat;
    ball_wanted_.assign(acute_.begin(), acute_.end());
    for (std::size_t v = 0; v < flat.size(); ++v)
      if (flat[v]) ball_wanted_[v] = 0;
    for (std::uint32_t f = 0; f < facets_.size(); ++f)
      for (vertex_id v : facets_[f].corners) {
        if (v >= acute_.size() || acute_[v] || !vertex_edges_.count(v)) continue;
        for (auto e : vertex_edges_.at(v)) {
          const auto& E = edges_[e];
          if (std::find(E.facets.begin(), E.facets.end(), f) != E.facets.end()) continue;
          const point3 d = p[E.u == v ? E.v : E.u] - p[v];
          if (std::abs(dot(d, facets_[f].unit)) < acute_sin * std::sqrt(dot(d, d)) && near_corner(f, v, d)) {
            acute_[v] = 1;
            if (!flat[v]) ball_wanted_[v] = 1;
          }
        }
      }
  }
  /// Whether direction d from corner v of facet f makes a small angle (below 62 degrees) with the
  /// facet itself, given that it does with its plane: its projection on the plane lies in the
  /// facet's corner at v, or d is within 62 degrees of a side of the facet at v. An edge in the plane of
  /// a facet it does not bound, outside the facet's corner (where coplanar facets of different
  /// markers meet), is at 90 degrees from the facet, not 0. Where v is not a simple corner (no
  /// side or more than two sides of f at it) the plane decides, as before.
  bool near_corner(std::uint32_t f, vertex_id v, const point3& d) const {
    const auto& S = facets_[f];
    const auto& p = out_.points;
    point3 out{}, in{};
    int outs = 0, ins = 0;
    for (auto [e, fw] : S.sides) {
      const auto& E = edges_[e];
      const vertex_id a = fw ? E.u : E.v, b = fw ? E.v : E.u;  // the facet on the left of a -> b
      if (a == v) out = p[b] - p[v], ++outs;
      if (b == v) in = p[a] - p[v], ++ins;
    }
    if (outs != 1 || ins != 1) return true;
    auto angle_cos = [](const point3& x, const point3& y) { return dot(x, y) / std::sqrt(dot(x, x) * dot(y, y)); };
    if (angle_cos(d, out) > acute_cos || angle_cos(d, in) > acute_cos) return true;
    // counter-clockwise about the facet's normal from `out`: the corner spans [0, angle of `in`]
    auto angle = [&](const point3& x) {
      const double a = std::atan2(dot(x, S.e2), dot(x, S.e1)), o = std::atan2(dot(out, S.e2), dot(out, S.e1));
      double t = a - o;
      while (t < 0) t += 2 * std::acos(-1.0);
      return t;
    };
    const point3 dp = d - dot(d, S.unit) * S.unit;
    if (dot(dp, dp) == 0) return true;  // along the normal: not below 62 degrees by the test above anyway
    return angle(dp) < angle(in);
  }

  /// facet_edges_, facet_corners_ and facet_reflex_ (counts_against). A facet of more than 256 PLC
  /// vertices counts as not convex at any edge (the test is quadratic; merged planar regions).
  void find_convexity() {
    facet_edges_.assign(facets_.size(), {});
    facet_corners_.assign(facets_.size(), {});
    facet_reflex_.assign(facets_.size(), {});
    for (std::uint32_t f = 0; f < facets_.size(); ++f) {
      const auto& S = facets_[f];
      for (auto [e, fw] : S.sides) facet_edges_[f].push_back(e);
      std::sort(facet_edges_[f].begin(), facet_edges_[f].end());
      facet_edges_[f].erase(std::unique(facet_edges_[f].begin(), facet_edges_[f].end()), facet_edges_[f].end());
      facet_corners_[f].assign(S.corners.begin(), S.corners.end());
      for (std::uint32_t e : facet_edges_[f]) {
        // which side of the plane through e along the facet's normal each PLC vertex lies on (exact)
        const point3 &a = out_.points[edges_[e].u], &b = out_.points[edges_[e].v];
        const point3 up = a + S.unit;
        bool pos = S.corners.size() > 256, neg = pos;
        for (auto it = S.corners.begin(); it != S.corners.end() && !(pos && neg); ++it) {
          const int o = geometry::orient3d(a, b, up, out_.points[*it]);
          pos = pos || o > 0, neg = neg || o < 0;
        }
        if (pos && neg) facet_reflex_[f].push_back(e);
      }
    }
  }

  /// Facet f from its region: constraint edges (registered as PLC edges) and embedded points.
  void setup_facet(std::uint32_t f, const input::facet_region& R) {
    auto& S = facets_[f];
    S.source = R.members[0];
    S.axis = R.axis;
    const std::size_t line = plc_.facets[S.source].line;
    for (const auto& [a, b] : R.edges) {
      const auto e = edge_id(a, b, line);
      S.sides.push_back({e, edges_[e].u == a});
      if (std::find(edges_[e].facets.begin(), edges_[e].facets.end(), f) == edges_[e].facets.end())
        edges_[e].facets.push_back(f);
      S.corners.insert(a);
      S.corners.insert(b);
    }
    for (vertex_id v : R.points) {
      S.corners.insert(v);
      S.interior.push_back(v);
    }
    if (R.members.size() > 1) {  // the edges between merged facets: no constraint, but seams (plan_split)
      std::set<std::array<vertex_id, 2>> kept, seams;
      for (const auto& [a, b] : R.edges) kept.insert({std::min(a, b), std::max(a, b)});
      for (auto m : R.members)
        for (const auto& loop : plc_.facets[m].polygons)
          for (std::size_t i = 0; loop.size() >= 3 && i < loop.size(); ++i) {
            const vertex_id a = loop[i], b = loop[(i + 1) % loop.size()];
            const std::array<vertex_id, 2> e{std::min(a, b), std::max(a, b)};
            if (!kept.count(e)) seams.insert(e);
          }
      S.seams.assign(seams.begin(), seams.end());
    }
    for (std::size_t k = 0; k < 3; ++k) {
      S.constant[k] = true;
      S.constant_value[k] = out_.points[*S.corners.begin()][k];
      for (vertex_id v : S.corners) S.constant[k] = S.constant[k] && out_.points[v][k] == S.constant_value[k];
    }
    S.unit = (1.0 / std::sqrt(dot(R.normal, R.normal))) * R.normal;
    for (vertex_id v : S.corners) S.centre = S.centre + out_.points[v];
    S.centre = (1.0 / static_cast<double>(S.corners.size())) * S.centre;
    const auto across = geometry::plane_axes(S.unit);
    S.e1 = across[0], S.e2 = across[1];
  }

  /// "FILE: facet N" of the input facet that names facet f (the first of a merged group).
  std::string facet_name(std::uint32_t f) const {
    return plc_.source + ":" + std::to_string(plc_.facets[facets_[f].source].line) + ": facet " +
           std::to_string(facets_[f].source + 1);
  }

  /// All vertices of facet f.
  std::vector<vertex_id> facet_vertices(std::uint32_t f) const {
    // the interior points come in id order (added points get the next id; a claimed free point,
    // an older one, breaks it): the chains' points sorted and merged in, not the facet sorted
    // again on every wrap of a large facet in a late round
    const auto& in = facets_[f].interior;
    std::vector<vertex_id> ring;
    for (auto [e, fw] : facets_[f].sides) ring.insert(ring.end(), edges_[e].chain.begin(), edges_[e].chain.end());
    std::sort(ring.begin(), ring.end());
    std::vector<vertex_id> vs;
    vs.reserve(in.size() + ring.size());
    if (std::is_sorted(in.begin(), in.end())) {
      std::merge(in.begin(), in.end(), ring.begin(), ring.end(), std::back_inserter(vs));
    } else {
      vs = in;
      vs.insert(vs.end(), ring.begin(), ring.end());
      std::sort(vs.begin(), vs.end());
    }
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    return vs;
  }

  std::size_t boundary_size(std::uint32_t f) const {
    std::size_t n = 0;
    for (auto [e, fw] : facets_[f].sides) n += edges_[e].chain.size();
    return n;
  }

  void triangulate(std::uint32_t f) {
    auto& S = facets_[f];
    // the last triangulation, whose triangles the wrap keeps where no point added since disturbs
    // them (same result, fewer searches: the conformer's late rounds re-wrap a large facet for a
    // few points)
    const auto previous = std::move(S.triangles);
    S.triangles.clear();
    S.boundary_size = boundary_size(f);
    auto vs = facet_vertices(f);
    std::vector<vertex_id> added;
    std::set_difference(vs.begin(), vs.end(), S.wrapped.begin(), S.wrapped.end(), std::back_inserter(added));
    const front::facet_rewrap again{previous, added};
    const bool reuse = !previous.empty() && added.size() + S.wrapped.size() == vs.size();  // vertices only grow
    // every constraint edge at once: outer loops, loops around holes (reversed) and edges with
    // the facet on both sides (both directions) bound one region
    std::vector<std::array<vertex_id, 2>> b;
    for (auto [e, fw] : S.sides) {
      const auto& ch = edges_[e].chain;
      if (fw)
        for (std::size_t i = 0; i + 1 < ch.size(); ++i) b.push_back({ch[i], ch[i + 1]});
      else
        for (std::size_t i = ch.size() - 1; i > 0; --i) b.push_back({ch[i], ch[i - 1]});
    }
    // where the facet was wrapped before, only the cavity the added points and split edges make is
    // wrapped again (front::rewrap_facet_local): the same triangles, kept ones in their places
    S.circles.resize(previous.size(), {0, 0, std::numeric_limits<double>::quiet_NaN()});
    const front::facet_change change{previous, added, S.wrapped_boundary, &S.circles};
    const bool local = reuse && !S.wrapped_boundary.empty();
    static const bool check_local = std::getenv("GSSE_CHECK_REWRAP") != nullptr;
    bool local_done = false;
    try {
      std::optional<std::vector<std::array<vertex_id, 3>>> part;
      if (S.constant[static_cast<std::size_t>(S.axis)]) {
        // an axis-aligned facet's points share the dropped coordinate exactly (splits copy it)
        if (local) part = front::rewrap_facet_local(out_.points, S.axis, b, change, facet_name(f), &lines_);
        if (!part || check_local) {
          const auto grid = front::make_grid(out_.points, S.axis, vs);
          S.triangles = front::wrap_facet(out_.points, S.axis, grid, b, facet_name(f), nullptr, 0, true,
                                          reuse ? &again : nullptr, &lines_);
        }
      } else {
        std::vector<point2> uv(vs.size());
        for (std::size_t i = 0; i < vs.size(); ++i) {
          const point3 d = out_.points[vs[i]] - S.centre;
          uv[i] = {dot(d, S.e1), dot(d, S.e2)};
        }
        if (local) part = front::rewrap_frame_local(vs, uv, b, change, facet_name(f), &lines_);
        if (!part || check_local) S.triangles = front::wrap_frame(vs, uv, b, facet_name(f), &lines_, reuse ? &again : nullptr);
      }
      if (part && check_local) {
        auto canon = [](std::vector<std::array<vertex_id, 3>> ts) {
          for (auto& t : ts) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
          std::sort(ts.begin(), ts.end());
          return ts;
        };
        if (canon(*part) != canon(S.triangles))
          throw std::logic_error(facet_name(f) + ": local rewrap differs (" + std::to_string(part->size()) + " vs " +
                                 std::to_string(S.triangles.size()) + " triangles)");
      }
      if (part) S.triangles = std::move(*part);
      local_done = part && !check_local;
    } catch (const front::front_error& e) {
      throw conform_error(std::string(e.what()) + " (facet polygons overlap or self-intersect?)");
    }
    // the check's bookkeeping (encroachers()). Rewrapped locally after a check: the kept
    // triangles keep their places, and those clean then stay known clean; the new ones are
    // marked fresh. Else the triangles known clean at the last check are kept as keys
    // (fresh since the check: also those fresh at an earlier re-wrap with no check between, and a
    // fresh place never counts as clean, whatever the triangle there before was)
    const std::vector<char> fresh_before = std::move(S.fresh);
    S.fresh.clear();
    // the last flat check saw the vertices of the last wrap: the triangles new since are the fresh ones
    S.flat_local = local_done && S.checked && S.flat_checked == S.wrapped;
    if (S.checked && local_done) {
      S.fresh.assign(S.triangles.size(), 1);
      for (std::size_t t = 0; t < std::min(previous.size(), S.triangles.size()); ++t)
        S.fresh[t] = S.triangles[t] != previous[t] || (t < fresh_before.size() && fresh_before[t]);
      S.was_clean.resize(S.triangles.size(), 0);
      S.relaxed.resize(S.triangles.size(), 0);
      for (std::size_t t = 0; t < S.triangles.size(); ++t)
        if (S.fresh[t]) S.was_clean[t] = 0, S.relaxed[t] = 0;
    } else {
      if (S.checked) {
        std::vector<key_set<3>::key> keys;
        for (std::size_t t = 0; t < previous.size(); ++t)
          if (S.was_clean[t]) {
            auto key = previous[t];
            std::sort(key.begin(), key.end());
            keys.push_back(key);
          }
        S.clean = key_set<3>(keys);
      }
      S.checked = false;
      S.relaxed.clear();
    }
    // the per-place caches: a place whose triangle changed (or is new) is unknown; the triangle
    // cells are filled again only if places moved (a shorter list) or many changed
    {
      const std::size_t n = S.triangles.size(), kept = std::min(previous.size(), n);
      const double unknown = std::numeric_limits<double>::quiet_NaN();
      S.ball.resize(n);
      S.ball_known.resize(n, 0);
      S.circles.resize(n, {0, 0, unknown});
      constexpr std::size_t extra_limit = 64;
      auto& C = S.cells;
      bool refill = C.start.empty() || n < previous.size();
      std::vector<std::uint32_t> extra;
      for (std::size_t t = 0; t < n; ++t)
        if (t >= kept || S.triangles[t] != previous[t]) {
          S.ball_known[t] = 0, S.circles[t] = {0, 0, unknown};
          if (!refill && extra.size() < extra_limit + 1) extra.push_back(static_cast<std::uint32_t>(t));
        }
      if (!refill) {
        std::vector<std::uint32_t> all;
        std::set_union(C.extra.begin(), C.extra.end(), extra.begin(), extra.end(), std::back_inserter(all));
        refill = all.size() > extra_limit;
        C.extra = std::move(all);
      }
      if (refill) index_triangles(f);
    }
    S.wrapped = std::move(vs);
    S.wrapped_boundary = std::move(b);
  }

  /// Triangulates the given facets, in parallel: each reads the shared points and chains and
  /// writes only its own facet state.
  void triangulate_all(const std::vector<std::uint32_t>& fs) {
    // which points lie inside which PLC edge: split points of a slanted edge are on its line only
    // up to rounding, and the facet triangulation takes them as collinear (front::facet_lines)
    edge_of_.resize(out_.points.size());
    for (std::size_t v = 0; v < out_.points.size(); ++v)
      edge_of_[v] = out_.homes[v].kind == home::edge ? out_.homes[v].id + 1 : 0;
    ends_.resize(edges_.size());
    for (std::size_t e = 0; e < edges_.size(); ++e) ends_[e] = {edges_[e].u, edges_[e].v};
    lines_ = {edge_of_, ends_};
    for_each(execution::par(opt_.threads), fs, [&](std::uint32_t f) { triangulate(f); },
             [&](std::uint32_t f) { return static_cast<double>(vertex_count(f)); });
  }

  /// The encroacher of subfacet abc (strictly inside its closed equatorial ball: the smallest id in
  /// the nearest ring of grid cells holding one, see segment_encroacher; or a
  /// tie that keeps it out of the cospherical Delaunay set), or no_vertex. Read-only: facets are
  /// checked in parallel, each thread with its own `ties` scratch. (cc, r): the ball's bound,
  /// detail::equatorial_bound.
  vertex_id facet_encroacher(vertex_id a, vertex_id b, vertex_id c, const point3& cc, double r,
                             std::vector<vertex_id>& ties) const {
    const auto& p = out_.points;
    point3 lo, hi;
    ball_box(cc, r, lo, hi);
    vertex_id strict = no_vertex;
    ties.clear();
    const double r2 = r * r;
    grid_.for_box(lo, hi).visit_rings(cc, lo, hi, [&](vertex_id y) {
      if (y == a || y == b || y == c || (strict != no_vertex && y > strict)) return;
      if (squared_distance(cc, p[y]) > r2) return;  // double prefilter, padded
      const int s = geometry::in_equatorial(p[a], p[b], p[c], p[y]);
      if (s > 0) strict = y;
      else if (s == 0) ties.push_back(y);
    }, [&] { return strict != no_vertex; });
    if (strict != no_vertex) return strict;
    if (ties.empty()) return no_vertex;
    std::sort(ties.begin(), ties.end());
    return detail::triangle_in_cospherical_dt(p, a, b, c, ties) ? no_vertex : ties.front();
  }

  /// options::delaunay_faces: whether subfacet abc, whose closed equatorial ball (bound cc, r)
  /// holds points, is a face of the perturbed Delaunay tetrahedralization of all points all the
  /// same. The points in the ball must lie strictly on one side of its plane (points on both
  /// sides, or in the plane, and it is not); x, the perturbed gift-wrap apex among them, gives the
  /// tetrahedron abcx, and abc is a face iff abcx's circumsphere is perturbed-empty of every point
  /// (a point on x's side outside the equatorial ball lies outside it: the sphere bulges to the
  /// other side). A sphere over 64 r (a double estimate) answers no without a scan, as does a
  /// degenerate triangle. On yes, `held` receives a ball holding the equatorial ball and the
  /// sphere: only a point inserted there can make abc a non-face (one on x's side must lie in
  /// the sphere through abc and the apex on the other side, whose cap on x's side lies in the
  /// equatorial ball).
  bool delaunay_face(vertex_id a, vertex_id b, vertex_id c, const point3& cc, double r,
                     std::pair<point3, double>& held, vertex_id& apex) const {
    const auto& p = out_.points;
    if (geometry::collinear(p[a], p[b], p[c])) return false;
    point3 lo, hi;
    ball_box(cc, r, lo, hi);
    std::vector<vertex_id> pos, neg;
    bool flat = false;
    const double r2 = r * r;
    grid_.for_box(lo, hi).visit(lo, hi, [&](vertex_id y) {
      if (y == a || y == b || y == c || squared_distance(cc, p[y]) > r2) return true;
      if (geometry::in_equatorial(p[a], p[b], p[c], p[y]) < 0) return true;
      const int s = geometry::orient3d(p[a], p[b], p[c], p[y]);
      if (s == 0) return !(flat = true);
      (s > 0 ? pos : neg).push_back(y);
      return pos.empty() || neg.empty();
    });
    if (flat || pos.empty() == neg.empty()) return false;
    vertex_id u = a, v = b;
    const std::vector<vertex_id>& side = pos.empty() ? neg : pos;
    if (pos.empty()) std::swap(u, v);  // (u, v, c, x) positively oriented
    vertex_id x = side[0];
    for (vertex_id y : side)
      if (y != x && geometry::in_sphere_perturbed(p[u], p[v], p[c], p[x], p[y]) > 0) x = y;
    // the sphere's ball (doubles padded by a bound of their rounding, exact where that is not
    // small); a sphere far larger than the equatorial ball is not scanned
    point3 sc;
    double sr = 0;
    if (!geometry::circumball_bound(p[u], p[v], p[c], p[x], sc, sr, 64 * r)) return false;
    ball_box(sc, sr, lo, hi);
    const double sr2 = sr * sr;
    const bool empty = grid_.for_box(lo, hi).visit(lo, hi, [&](vertex_id y) {
      if (y == a || y == b || y == c || y == x || squared_distance(sc, p[y]) > sr2) return true;
      return geometry::in_sphere_perturbed(p[u], p[v], p[c], p[x], p[y]) <= 0;
    });
    if (empty) held = {sc, std::max(sr, distance(sc, cc) + r) * (1 + 1e-12)}, apex = x;
    return empty;
  }

  /// Relation of vertex y (by its home) to facet f, with the shared vertex or edge.
  relation facet_relation(std::uint32_t f, const home& h, std::optional<vertex_id>& sv,
                          std::optional<std::array<vertex_id, 2>>& se) const {
    const auto& S = facets_[f];
    auto corner_of = [&](vertex_id w) { return S.corners.count(w) > 0; };
    if (h.kind == home::facet) {
      if (h.id == f) return relation::on_carrier;
      std::vector<vertex_id> common;
      for (vertex_id w : facets_[h.id].corners)
        if (corner_of(w)) common.push_back(w);
      if (common.size() >= 2) {
        // a shared PLC edge?
        for (auto [e, fw] : facets_[h.id].sides)
            if (corner_of(edges_[e].u) && corner_of(edges_[e].v) &&
                std::find(edges_[e].facets.begin(), edges_[e].facets.end(), f) != edges_[e].facets.end()) {
              se = std::array<vertex_id, 2>{edges_[e].u, edges_[e].v};
              return relation::on_incident_edge;
            }
      }
      if (!common.empty()) {
        sv = common.front();
        return relation::on_incident_vertex;
      }
      return relation::free;
    }
    if (h.kind == home::edge) {
      const auto& E = edges_[h.id];
      if (std::find(E.facets.begin(), E.facets.end(), f) != E.facets.end()) return relation::on_carrier;
      if (corner_of(E.u)) return sv = E.u, relation::on_incident_vertex;
      if (corner_of(E.v)) return sv = E.v, relation::on_incident_vertex;
      return relation::free;
    }
    if (h.kind == home::vertex) {
      if (corner_of(h.id)) return relation::on_carrier;
      if (vertex_edges_.count(h.id))
        for (auto e : vertex_edges_.at(h.id))
          for (vertex_id s : {edges_[e].u, edges_[e].v})
            if (s != h.id && corner_of(s)) return sv = s, relation::on_incident_vertex;
    }
    return relation::free;
  }

  /// The triangle of facet f containing q (closed), or -1.
  /// Files the triangles of facet f in a uniform grid of about one triangle per cell, by their
  /// projected boxes (padded: the exact test decides), so that locate() tests a few of them.
  void index_triangles(std::uint32_t f) {
    auto& S = facets_[f];
    auto& C = S.cells;
    const auto& p = out_.points;
    C = {};
    if (S.triangles.empty()) return;
    std::vector<std::array<point2, 2>> box(S.triangles.size());
    point2 lo{1e300, 1e300}, hi{-1e300, -1e300};
    for (std::size_t t = 0; t < S.triangles.size(); ++t) {
      point2 a{1e300, 1e300}, b{-1e300, -1e300};
      for (auto v : S.triangles[t]) {
        const point2 x = geometry::project(p[v], S.axis);
        for (std::size_t k = 0; k < 2; ++k) a[k] = std::min(a[k], x[k]), b[k] = std::max(b[k], x[k]);
      }
      for (std::size_t k = 0; k < 2; ++k) {
        const double pad = 1e-9 * (b[k] - a[k]) + 1e-300;
        a[k] -= pad, b[k] += pad;
        lo[k] = std::min(lo[k], a[k]), hi[k] = std::max(hi[k], b[k]);
      }
      box[t] = {a, b};
    }
    const double area = std::max((hi[0] - lo[0]) * (hi[1] - lo[1]), 1e-300);
    const double h = std::sqrt(area / static_cast<double>(S.triangles.size()));
    C.lo = lo;
    C.inv = 1 / h;
    C.nx = std::clamp(static_cast<long>((hi[0] - lo[0]) * C.inv) + 1, 1l, 4096l);
    C.ny = std::clamp(static_cast<long>((hi[1] - lo[1]) * C.inv) + 1, 1l, 4096l);
    auto range = [&](const point2& a, const point2& b, long& x0, long& x1, long& y0, long& y1) {
      x0 = std::clamp(static_cast<long>((a[0] - lo[0]) * C.inv), 0l, C.nx - 1);
      x1 = std::clamp(static_cast<long>((b[0] - lo[0]) * C.inv), 0l, C.nx - 1);
      y0 = std::clamp(static_cast<long>((a[1] - lo[1]) * C.inv), 0l, C.ny - 1);
      y1 = std::clamp(static_cast<long>((b[1] - lo[1]) * C.inv), 0l, C.ny - 1);
    };
    C.start.assign(static_cast<std::size_t>(C.nx * C.ny) + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
      for (std::uint32_t t = 0; t < box.size(); ++t) {
        long x0, x1, y0, y1;
        range(box[t][0], box[t][1], x0, x1, y0, y1);
        for (long y = y0; y <= y1; ++y)
          for (long x = x0; x <= x1; ++x) {
            const auto c = static_cast<std::size_t>(y * C.nx + x);
            if (pass == 0) ++C.start[c + 1];
            else C.items[C.start[c]++] = t;
          }
      }
      if (pass == 0) {
        std::partial_sum(C.start.begin(), C.start.end(), C.start.begin());
        C.items.resize(C.start.back());
      } else {  // the fill advanced each start to the next cell's: shift back
        for (std::size_t c = C.start.size() - 1; c > 0; --c) C.start[c] = C.start[c - 1];
        C.start[0] = 0;
      }
    }
  }

  /// The triangle of facet f containing q (closed), or -1: the hint first (a split point is
  /// usually in its triangle), then the triangles filed in q's cell, in ascending order.
  long locate(std::uint32_t f, const point3& q, std::size_t hint = 0) const {
    const auto& S = facets_[f];
    const auto& C = S.cells;
    const auto& p = out_.points;
    auto inside = [&](std::size_t t) {
      const auto& T = S.triangles[t];
      return geometry::orient_projected(p[T[0]], p[T[1]], q, S.axis) >= 0 &&
             geometry::orient_projected(p[T[1]], p[T[2]], q, S.axis) >= 0 &&
             geometry::orient_projected(p[T[2]], p[T[0]], q, S.axis) >= 0;
    };
    if (hint < S.triangles.size() && inside(hint)) return static_cast<long>(hint);
    if (C.start.empty()) return -1;
    const point2 pq = geometry::project(q, S.axis);
    const double x = (pq[0] - C.lo[0]) * C.inv, y = (pq[1] - C.lo[1]) * C.inv;
    if (!(x >= 0 && y >= 0 && x < static_cast<double>(C.nx) + 1 && y < static_cast<double>(C.ny) + 1)) return -1;
    const auto c = static_cast<std::size_t>(std::min(static_cast<long>(y), C.ny - 1) * C.nx + std::min(static_cast<long>(x), C.nx - 1));
    // the first place holding q, as cells filled now would list it (all triangles holding q are
    // filed under its cell, in order of place)
    long found = -1;
    for (auto k = C.start[c]; k < C.start[c + 1]; ++k)
      if (inside(C.items[k])) {
        found = static_cast<long>(C.items[k]);
        break;
      }
    for (auto t : C.extra) {
      if (found >= 0 && static_cast<long>(t) >= found) break;
      if (inside(t)) {
        found = static_cast<long>(t);
        break;
      }
    }
    return found;
  }

  /// A subsegment of facet f whose diametral ball holds q strictly: (edge, index) or none.
  std::optional<std::pair<std::uint32_t, std::size_t>> encroached_subsegment(std::uint32_t f, const point3& q) const {
    const auto& p = out_.points;
    for (auto [e, fw] : facets_[f].sides) {
        const auto& ch = edges_[e].chain;
        // A closed diametral ball holds q only if q projects into its subsegment, and the chain
        // runs along its edge: only the subsegments about q's projection, found by bisection,
        // are tested. The window's margin is 1e-9 of the edge, far above rounding (a filter:
        // the exact test decides).
        const point3 o = p[ch.front()], d = p[ch.back()] - o;
        const double margin = 1e-9 * dot(d, d), at = dot(q - o, d);
        auto along = [&](std::size_t k) { return dot(p[ch[k]] - o, d); };
        std::size_t first = 0, last = ch.size() - 1;  // first subsegment whose far end is not before q
        while (first < last) {
          const std::size_t mid = (first + last) / 2;
          if (along(mid + 1) < at - margin)
            first = mid + 1;
          else
            last = mid;
        }
        for (std::size_t i = first; i + 1 < ch.size() && along(i) <= at + margin; ++i) {
          const point3 &a = p[ch[i]], &b = p[ch[i + 1]];
          const auto [c, r] = detail::diametral_bound(a, b);
          if (squared_distance(c, q) > r * r) continue;  // double prefilter, padded
          if (geometry::in_diametral(a, b, q) >= 0) return std::pair{e, i};
        }
      }
    return std::nullopt;
  }

  /// True if a point of `g` lies in the closed equatorial ball of subfacet T (exact).
  bool in_closed_ball(const recent_points<3>& g, const std::array<vertex_id, 3>& T) const {
    const auto& p = out_.points;
    const auto [cc, r] = detail::equatorial_bound(p[T[0]], p[T[1]], p[T[2]]);
    return in_closed_ball(g, T, cc, r);
  }
  /// The same with the ball's bound given.
  bool in_closed_ball(const recent_points<3>& g, const std::array<vertex_id, 3>& T, const point3& cc, double r) const {
    const auto& p = out_.points;
    if (!g.near(cc, r)) return false;
    return !g.visit_ball(cc, r, [&](vertex_id w) {
      return squared_distance(cc, p[w]) > r * r || geometry::in_equatorial(p[T[0]], p[T[1]], p[T[2]], p[w]) < 0;
    });
  }

  /// A subfacet to split: facet, triangle, and its encroacher (no_vertex: only too large).
  struct split_candidate {
    std::uint32_t f;
    std::uint32_t t;
    vertex_id y;
    bool flat = false;  // would bound a flat Delaunay tetrahedron (flat_pairs): split off-centre
  };

  /// The subfacets to split at the start of a round, in facet and triangle order: the encroached
  /// ones, and with a size those longer than it. Computed in parallel over pieces of facets. A
  /// subfacet found clean at the last check (the same three corners, whether or not its facet was
  /// triangulated again since) can be encroached only by a point inserted since: it is checked
  /// fully only if one of those lies in its closed ball. A facet not triangulated again since was
  /// wholly clean then: a split changes its vertex set.
  std::vector<split_candidate> encroachers() {
    const auto& p = out_.points;
    recent_points<3> recent(p[0], grid_h_, true);
    // read only for subfacets known clean; before any is (the first check: every point is recent)
    // filling it would be serial work for nothing
    const bool known = std::any_of(facets_.begin(), facets_.end(), [](const facet_state& S) { return S.checked || !S.clean.empty(); });
    for (vertex_id v = static_cast<vertex_id>(checked_upto_); known && v < p.size(); ++v) recent.add(v, p[v]);
    recent.freeze();
    // work in pieces of a facet, so that one large facet does not keep a thread busy alone
    constexpr std::size_t piece = 512;
    struct range {
      std::uint32_t f;
      std::size_t a, b;
    };
    std::vector<range> work;
    for (std::uint32_t f = 0; f < facets_.size(); ++f) {
      facets_[f].was_clean.resize(facets_[f].triangles.size());
      facets_[f].relaxed.resize(facets_[f].triangles.size(), 0);
      facets_[f].held.resize(facets_[f].triangles.size());
      facets_[f].apex.resize(facets_[f].triangles.size(), no_vertex);
      facets_[f].ball.resize(facets_[f].triangles.size());
      facets_[f].ball_known.resize(facets_[f].triangles.size(), 0);
      for (std::size_t a = 0; a < facets_[f].triangles.size(); a += piece)
        work.push_back({f, a, std::min(facets_[f].triangles.size(), a + piece)});
    }
    std::vector<std::vector<split_candidate>> found(work.size());
    std::vector<typename facet_state::piece_summary> summary(work.size());
    // the pad of the pieces' frame boxes (below): far above the rounding of dot products of
    // coordinates this large
    double far = 0;
    for (std::size_t a = 0; a < 3; ++a) far = std::max({far, std::abs(box_lo_[a]), std::abs(box_hi_[a])});
    const double pad = 1e-9 * model_size_ + 1e-12 * far;
    auto check = [&](const range& w) {
      auto& S = facets_[w.f];
      const std::size_t k = static_cast<std::size_t>(&w - work.data());
      // a quiet piece of a facet not triangulated since, with no new point in its box of balls:
      // still quiet (after a local rewrap: a piece with no new triangle, as it was then). The
      // points themselves are asked, not only their bounding box: a round that adds points all
      // over a curved surface has every piece in that box (the torus's 40k one-triangle facets)
      const bool local = S.checked && !S.fresh.empty();
      const std::size_t at = w.a / piece;
      if (S.checked && at < S.pieces.size() && S.pieces[at].quiet &&
          (!local || std::find(S.fresh.begin() + static_cast<long>(w.a), S.fresh.begin() + static_cast<long>(w.b), 1) ==
                         S.fresh.begin() + static_cast<long>(w.b)) &&
          !recent.any_in_box(S.pieces[at].lo, S.pieces[at].hi)) {
        summary[k] = S.pieces[at];
        return;
      }
      std::vector<vertex_id> ties;
      std::vector<split_candidate> mine;
      auto& box = summary[k];
      box.lo = box.hi = p[S.triangles[w.a][0]];
      // and in the facet's own frame (e1, e2, normal): a slanted piece's box of balls is a volume,
      // its frame box a slab as thick as its largest ball (every ball's extent along a unit axis
      // is its centre's coordinate +- r; padded far above the rounding of the dot products)
      const std::array<point3, 3> frame{S.e1, S.e2, S.unit};
      point3 flo, fhi;
      for (std::size_t a = 0; a < 3; ++a) flo[a] = 1e300, fhi[a] = -1e300;
      for (std::size_t t = w.a; t < w.b; ++t) {
        const auto& T = S.triangles[t];
        if (!S.ball_known[t]) S.ball[t] = detail::equatorial_bound(p[T[0]], p[T[1]], p[T[2]]), S.ball_known[t] = 1;
        const auto [cc, r] = S.relaxed[t] ? S.held[t] : S.ball[t];  // a relaxed one's ball holds its equatorial one
        for (std::size_t a = 0; a < 3; ++a) box.lo[a] = std::min(box.lo[a], cc[a] - r), box.hi[a] = std::max(box.hi[a], cc[a] + r);
        const double rp = r * (1 + 1e-9) + pad;
        for (std::size_t a = 0; a < 3; ++a) {
          const double x = dot(cc, frame[a]);
          flo[a] = std::min(flo[a], x - rp), fhi[a] = std::max(fhi[a], x + rp);
        }
      }
      // the points inserted since the last check that lie in the piece's box of balls and in its
      // frame box (every one a triangle's closed ball can hold), asked once for the piece: a known
      // clean triangle is then tested against this short list, not the grid (no list: too many,
      // the grid per triangle). On a slanted facet the frame box keeps the list to the slab about
      // the piece, not the volume of its axis-aligned box (rotated trench: the conformer 3% faster)
      std::vector<vertex_id> near;
      bool listed = true;
      constexpr std::size_t most = 32;
      if (recent.near_box(box.lo, box.hi)) {
        const point3 mid = 0.5 * (box.lo + box.hi);
        const double half = 0.5 * distance(box.lo, box.hi);
        recent.visit_ball(mid, half * (1 + 1e-9), [&](vertex_id v) {
          for (std::size_t a = 0; a < 3; ++a)
            if (p[v][a] < box.lo[a] || p[v][a] > box.hi[a]) return true;
          for (std::size_t a = 0; a < 3; ++a)
            if (const double x = dot(p[v], frame[a]); x < flo[a] || x > fhi[a]) return true;
          near.push_back(v);
          return (listed = near.size() <= most);
        });
      }
      // the listed points' box: a ball that misses it holds none of them
      point3 nlo{}, nhi{};
      for (std::size_t i = 0; i < near.size(); ++i)
        for (std::size_t a = 0; a < 3; ++a) {
          const double x = p[near[i]][a];
          nlo[a] = i == 0 ? x : std::min(nlo[a], x), nhi[a] = i == 0 ? x : std::max(nhi[a], x);
        }
      auto held = [&](const std::array<vertex_id, 3>& T, const point3& cc, double r) {
        if (!listed) return in_closed_ball(recent, T, cc, r);
        if (near.empty()) return false;
        for (std::size_t a = 0; a < 3; ++a)
          if (cc[a] + r < nlo[a] || cc[a] - r > nhi[a]) return false;
        for (vertex_id v : near)
          if (squared_distance(cc, p[v]) <= r * r && geometry::in_equatorial(p[T[0]], p[T[1]], p[T[2]], p[v]) >= 0) return true;
        return false;
      };
      // a relaxed triangle: any point inserted since in its held ball
      auto held_any = [&](const point3& cc, double r) {
        if (!listed) return recent.near(cc, r) && !recent.visit_ball(cc, r, [&](vertex_id v) { return squared_distance(cc, p[v]) > r * r; });
        for (vertex_id v : near)
          if (squared_distance(cc, p[v]) <= r * r) return true;
        return false;
      };
      for (std::size_t t = w.a; t < w.b; ++t) {
        const auto& T = S.triangles[t];
        const auto [cc, r] = S.ball[t];
        auto key = T;
        if (!S.checked) std::sort(key.begin(), key.end());
        // clean at the last check: only a point inserted since can encroach it
        vertex_id y = no_vertex;
        const bool known_clean = local ? !S.fresh[t] && (S.was_clean[t] || S.relaxed[t]) : S.checked || S.clean.contains(key);
        const bool was_relaxed = known_clean && S.relaxed[t];
        bool relaxed = was_relaxed;
        if (!known_clean || (was_relaxed ? held_any(S.held[t].first, S.held[t].second) : held(T, cc, r))) {
          y = facet_encroacher(T[0], T[1], T[2], cc, r, ties);
          // encroached, but a Delaunay face all the same (options::delaunay_faces)
          relaxed = y != no_vertex && opt_.delaunay_faces && delaunay_face(T[0], T[1], T[2], cc, r, S.held[t], S.apex[t]);
          if (relaxed) {
            y = no_vertex;
            const auto& [hc, hr] = S.held[t];
            for (std::size_t a = 0; a < 3; ++a) box.lo[a] = std::min(box.lo[a], hc[a] - hr), box.hi[a] = std::max(box.hi[a], hc[a] + hr);
          }
        }
        S.relaxed[t] = relaxed;
        // too large: circumradius above that of the facet lattice's equilateral triangle
        // (size / sqrt 3), not merely by rounding. An edge test ("longer than the size") cut the
        // near-right triangles where the lattice meets boundary strips and merged facets' seams,
        // a cascade of one row per round (docs/design-decisions.md)
        bool too_big = false;
        if (sized() && !known_clean) {  // clean: was not too large either, and has not changed
          const point3 u = p[T[1]] - p[T[0]], v = p[T[2]] - p[T[0]], z = p[T[2]] - p[T[1]], n = cross(u, v);
          // R^2 = |u|^2 |v|^2 |z|^2 / (4 |n|^2) against size^2 / 3 (graded: the size at the
          // circumcentre, asked only up to a cap a millionth above sqrt 3 R: a size at or above
          // the cap clears the face as h itself would, and the capped search ends far sooner
          // where the face is well below the size)
          const double lhs = 3 * dot(u, u) * dot(v, v) * dot(z, z), nn4 = 4 * dot(n, n);
          const double h = graded() ? size_at(cc, nn4 > 0 ? std::sqrt(lhs / nn4) * (1 + 1e-6) : std::numeric_limits<double>::infinity()) : opt_.size;
          too_big = lhs > nn4 * h * h * (1 + 2e-9);
        }
        S.was_clean[t] = y == no_vertex && !too_big && !relaxed;
        if (y != no_vertex || too_big) mine.push_back({w.f, static_cast<std::uint32_t>(t), y});
      }
      box.quiet = mine.empty();
      found[k] = std::move(mine);
    };
    for_each(execution::par(opt_.threads), work, check,
             [&](const range& w) { return static_cast<double>(w.b - w.a); });
    for (auto& S : facets_) {
      S.checked = true;
      S.fresh.clear();
      S.pieces.clear();
    }
    for (std::size_t k = 0; k < work.size(); ++k) facets_[work[k].f].pieces.push_back(summary[k]);
    checked_upto_ = p.size();
    std::vector<split_candidate> all;
    for (const auto& v : found) all.insert(all.end(), v.begin(), v.end());
    return all;
  }

  /// Which sides of each facet (positive: the side its triangles face) lie in a segment, from the
  /// labelling of the boundary as it is now (every facet triangulated): the sides of a facet
  /// belong to the same regions however it is refined.
  void find_meshed_sides() {
    boundary<3> b;
    b.points = out_.points;
    for (std::uint32_t f = 0; f < facets_.size(); ++f)
      for (const auto& t : facets_[f].triangles) {
        b.faces.push_back(t);
        b.face_source.push_back(facets_[f].source);
      }
    labelling l;
    try {
      l = opt_.sides_from && opt_.sides_labels ? label_refined(b, plc_, *opt_.sides_from, *opt_.sides_labels, opt_.threads)
                                               : label(b, plc_, opt_.threads);
    } catch (const conform_error&) {
      // an open boundary, a misplaced region point...: the labelling stage will report it and
      // nothing gets meshed; no side counts as meshed meanwhile (checking flat pairs on every
      // side would refine the outside of every hull facet for nothing)
      meshed_.assign(facets_.size(), {false, false});
      return;
    }
    meshed_.assign(facets_.size(), {false, false});
    std::size_t k = 0;
    for (std::uint32_t f = 0; f < facets_.size(); ++f) {
      if (!facets_[f].triangles.empty())
        meshed_[f] = {l.side[k][0] != exterior, l.side[k][1] != exterior};
      k += facets_[f].triangles.size();
    }
  }

  /// Whether the tetrahedron abcd (not exactly flat) has a perturbed-empty circumsphere, i.e. is
  /// a cell of the Delaunay tetrahedralization of all points. o = orient3d(a, b, c, d), which
  /// the caller has (exact, and for four nearly coplanar points costly).
  bool delaunay_cell(vertex_id a, vertex_id b, vertex_id c, vertex_id d, std::uint32_t facet, int o) const {
    const auto& p = out_.points;
    if (o == 0) return false;
    // d's side of the plane abc, in doubles, for the search below only: the sphere through four
    // nearly coplanar points bulges to that side (unless they are nearly cocircular)
    const point3 n = cross(p[b] - p[a], p[c] - p[a]);
    const point3 pa = p[a];
    const double nn = std::sqrt(dot(n, n));
    if (o < 0) std::swap(a, b);
    auto outside = [&](vertex_id y) {
      return y == a || y == b || y == c || y == d ||
             geometry::in_sphere_perturbed(p[a], p[b], p[c], p[d], p[y]) < 0;
    };
    // the points about the tetrahedron first, nearest rings of cells first, until 64 points are
    // tested or the first cell and six rings about it are read: a sphere that is not empty nearly
    // always holds one of them (the sphere of a nearly flat tetrahedron is nearly a half-space);
    // only then the exact ball (rational arithmetic) bounds the scan. (The test stops at the 64th
    // point, not at the end of its ring: where the boundary is fine and the grid's cells are not,
    // the first three rings, all read before, held thousands of points; graded rotated MOSFET:
    // 1.97 million tests, 1.78 million of them in 501 checks)
    const point3 g = 0.25 * (p[a] + p[b] + p[c] + p[d]);
    int ring = 0;
    std::size_t seen = 0;
    bool held = false;
    // (skipping the facet's own points: they lie near the sphere's rim, outside it, where the
    // test is least decided and most often exact; the exact scan below reads them too)
    // (only the points clearly on the side the sphere bulges to: one elsewhere, or near the plane
    // (another facet in it, an edge of it), is nearly never inside, and the test of one near the
    // rim is least decided)
    auto worth_testing = [&](vertex_id y) {
      if (out_.homes[y].kind == home::facet && out_.homes[y].id == facet) return false;
      const point3 e = p[y] - pa;
      const double h = dot(n, e);
      return (o > 0 ? h : -h) > 1e-6 * nn * std::sqrt(dot(e, e));
    };
    // (the rings about a point a cell off the facet, on that side: the first cells read hold such
    // points, not the facet's own ones and those across it; which point is found first does not
    // change the answer)
    const point3 start = nn > 0 ? g + ((o > 0 ? grid_h_ : -grid_h_) / nn) * n : g;
    constexpr std::size_t enough = 64;
    grid_.finest().visit_rings(start, box_lo_, box_hi_,
                               [&](vertex_id y) { return !worth_testing(y) || (++seen, !(held = !outside(y)) && seen < enough); },
                               [&] { return ++ring > 6; });
    if (held) return false;
    point3 cc;
    double r;
    geometry::exact_circumball(p[a], p[b], p[c], p[d], cc, r);
    point3 lo, hi;
    ball_box(cc, r, lo, hi);
    for (std::size_t k = 0; k < 3; ++k) lo[k] = std::min(lo[k], g[k]), hi[k] = std::max(hi[k], g[k]);
    // a point outside the double ball, which holds the exact one, is outside the sphere, and
    // |y - cc|^2 in doubles is within 5 eps of its value: a point more than 1e-12 (relative) beyond
    // it is decided in doubles, the others exactly (the ball of a nearly flat tetrahedron spans the
    // model: its box held tens of thousands of points, nearly all far outside)
    const double beyond = r * r * (1 + 1e-12);
    return grid_.for_box(lo, hi).visit_rings(g, lo, hi, [&](vertex_id y) { return squared_distance(p[y], cc) > beyond || outside(y); },
                                             [] { return false; });
  }

  /// The triangle of facet f other than t with the edge uv (found through the triangle cells
  /// about the edge's midpoint, which every triangle on the edge is filed under), or -1.
  long across(std::uint32_t f, std::size_t t, vertex_id u, vertex_id v) const {
    const auto& S = facets_[f];
    const auto& C = S.cells;
    if (C.start.empty()) return -1;
    const point2 m = geometry::project(0.5 * (out_.points[u] + out_.points[v]), S.axis);
    const double x = (m[0] - C.lo[0]) * C.inv, y = (m[1] - C.lo[1]) * C.inv;
    const long cx = std::clamp(static_cast<long>(std::max(x, 0.0)), 0l, C.nx - 1);
    const long cy = std::clamp(static_cast<long>(std::max(y, 0.0)), 0l, C.ny - 1);
    const auto c = static_cast<std::size_t>(cy * C.nx + cx);
    auto on_edge = [&](std::uint32_t t2) {
      if (t2 == t) return false;
      const auto& T = S.triangles[t2];
      return (T[0] == u || T[1] == u || T[2] == u) && (T[0] == v || T[1] == v || T[2] == v);
    };
    for (auto k = C.start[c]; k < C.start[c + 1]; ++k)
      if (on_edge(C.items[k])) return static_cast<long>(C.items[k]);
    for (const auto t2 : C.extra)
      if (on_edge(t2)) return static_cast<long>(t2);
    return -1;
  }

  /// flat_pairs for a facet re-wrapped locally since its last flat check: the new triangles are
  /// the fresh ones, and each one's partners are found across its edges, not by listing every
  /// edge of the facet. The same pairs, tested the same way, as the whole pass.
  std::vector<split_candidate> flat_pairs_local(std::uint32_t f) {
    auto& S = facets_[f];
    std::vector<split_candidate> mine;
    std::vector<std::array<vertex_id, 4>> fresh;
    for (std::size_t t = 0; t < S.triangles.size(); ++t) {
      if (!S.fresh[t]) continue;
      for (std::size_t k = 0; k < 3; ++k) {
        const vertex_id a = S.triangles[t][(k + 1) % 3], b = S.triangles[t][(k + 2) % 3], w = S.triangles[t][k];
        const long t2l = across(f, t, a, b);
        if (t2l < 0) continue;
        const auto t2 = static_cast<std::size_t>(t2l);
        if (S.fresh[t2] && t2 < t) continue;  // the pair once
        const auto& T2 = S.triangles[t2];
        const vertex_id z = T2[0] != a && T2[0] != b ? T2[0] : T2[1] != a && T2[1] != b ? T2[1] : T2[2];
        const auto ti = static_cast<std::uint32_t>(t), t2i = static_cast<std::uint32_t>(t2);
        if (t < t2)
          flat_pair(f, std::min(a, b), std::max(a, b), ti, w, t2i, z, mine, fresh);
        else
          flat_pair(f, std::min(a, b), std::max(a, b), t2i, z, ti, w, mine, fresh);
      }
    }
    end_flat_check(f, mine, fresh);
    return mine;
  }

  /// The pair of facet f's triangles t and t2 > t across edge uv (u < v), with apexes w and z:
  /// the tetrahedron uvwz, on the side of t where z is, if that side gets meshed, is a flat pair
  /// to split (at t2) when it is Delaunay, else it joins `not_flat` (it stays so: points are only
  /// added, so it is checked once).
  void flat_pair(std::uint32_t f, vertex_id u, vertex_id v, std::uint32_t t, vertex_id w, std::uint32_t t2, vertex_id z,
                 std::vector<split_candidate>& mine, std::vector<std::array<vertex_id, 4>>& not_flat) const {
    const auto& S = facets_[f];
    const auto& T = S.triangles[t];
    const int o = geometry::orient3d(out_.points[T[0]], out_.points[T[1]], out_.points[T[2]], out_.points[z]);
    if (o == 0 || !meshed_[f][o > 0 ? 0 : 1]) return;
    std::array<vertex_id, 4> id{u, v, w, z};
    std::sort(id.begin(), id.end());
    if (std::binary_search(S.not_flat.begin(), S.not_flat.end(), id)) return;
    // orient3d(u, v, w, z) from o: (u, v, w) is T's vertices, in T's cyclic order or not
    const std::size_t iu = T[0] == u ? 0 : T[1] == u ? 1 : 2, iv = T[0] == v ? 0 : T[1] == v ? 1 : 2;
    if (delaunay_cell(u, v, w, z, f, (iv + 3 - iu) % 3 == 1 ? o : -o))
      mine.push_back({f, t2, no_vertex, true});
    else
      not_flat.push_back(id);
  }

  /// After facet f's flat check: `mine` (the pairs to split) in triangle order; the facet counts
  /// as checked at its present vertices if there are none; the pairs found not flat are kept.
  void end_flat_check(std::uint32_t f, std::vector<split_candidate>& mine, std::vector<std::array<vertex_id, 4>>& not_flat) {
    auto& S = facets_[f];
    std::sort(mine.begin(), mine.end(), [](const split_candidate& x, const split_candidate& y) { return x.t < y.t; });
    // should a pair found flat not be split (a candidate skipped), the next check is a whole one
    if (mine.empty())
      S.flat_checked = S.wrapped;
    else
      S.flat_checked.clear();
    if (!not_flat.empty()) {
      std::sort(not_flat.begin(), not_flat.end());
      not_flat.erase(std::unique(not_flat.begin(), not_flat.end()), not_flat.end());
      std::vector<std::array<vertex_id, 4>> merged;
      std::merge(S.not_flat.begin(), S.not_flat.end(), not_flat.begin(), not_flat.end(), std::back_inserter(merged));
      S.not_flat = std::move(merged);
    }
  }

  /// Subfacets to split because the front mesher would otherwise build a flat tetrahedron on
  /// them: two subfacets of one slanted facet sharing an edge whose four points are coplanar and
  /// cocircular up to rounding (a rotated rectangle) can form a Delaunay tetrahedron of no volume
  /// that covers the facet twice. Splitting one of them at its circumcentre ends the tie.
  std::vector<split_candidate> flat_pairs(const std::vector<std::uint32_t>& fs) {
    const bool any = std::any_of(fs.begin(), fs.end(), [&](std::uint32_t f) {
      return !facets_[f].constant[static_cast<std::size_t>(facets_[f].axis)];
    });
    if (!any) return {};  // exactly planar facets only
    if (meshed_.empty()) find_meshed_sides();
    std::vector<std::vector<split_candidate>> found(fs.size());
    std::vector<std::size_t> ids(fs.size());
    std::iota(ids.begin(), ids.end(), std::size_t{0});
    for_each(execution::par(opt_.threads), ids, [&](std::size_t i) {
      const std::uint32_t f = fs[i];
      const auto& S = facets_[f];
      if (S.constant[static_cast<std::size_t>(S.axis)]) return;  // exactly planar: no such tetrahedra
      if (S.flat_local && S.fresh.size() == S.triangles.size()) {
        found[i] = flat_pairs_local(f);
        return;
      }
      // Only pairs with a triangle new since this facet's last check: the triangulation is the
      // (constrained, perturbed) Delaunay triangulation of the facet's vertices, so a triangle of
      // vertices all there at the last check was there then (its empty circle is empty in the
      // smaller set) and its pairs were checked then. The new triangles are those with a vertex
      // added since; a partner across an edge has both ends of that edge among their vertices.
      std::vector<vertex_id> added;
      const bool all = S.flat_checked.empty();
      if (!all)
        std::set_difference(S.wrapped.begin(), S.wrapped.end(), S.flat_checked.begin(), S.flat_checked.end(),
                            std::back_inserter(added));
      // per point, this thread's marks (bit 1: added, bit 2: a new triangle's vertex), cleared
      // after use: a lookup per corner instead of a bisection
      thread_local std::vector<std::uint8_t> mark;
      if (mark.size() < out_.points.size()) mark.resize(out_.points.size(), 0);
      auto among = [&](std::uint8_t bit, const std::array<vertex_id, 3>& T) {
        return ((mark[T[0]] | mark[T[1]] | mark[T[2]]) & bit) != 0;
      };
      std::vector<char> fresh_tri;  // per triangle: new since the last check
      std::vector<vertex_id> near;  // the new triangles' vertices
      if (!all) {
        for (vertex_id v : added) mark[v] |= 1;
        fresh_tri.resize(S.triangles.size());
        for (std::uint32_t t = 0; t < S.triangles.size(); ++t)
          if ((fresh_tri[t] = among(1, S.triangles[t])))
            near.insert(near.end(), S.triangles[t].begin(), S.triangles[t].end());
        for (vertex_id v : near) mark[v] |= 2;
      }
      // each interior edge once: (sorted edge, triangle, apex)
      std::vector<std::tuple<std::uint64_t, std::uint32_t, vertex_id>> half;
      for (std::uint32_t t = 0; t < S.triangles.size(); ++t) {
        if (!all && !fresh_tri[t] && !among(2, S.triangles[t])) continue;
        for (std::size_t k = 0; k < 3; ++k) {
          const vertex_id u = S.triangles[t][(k + 1) % 3], v = S.triangles[t][(k + 2) % 3];
          half.push_back({(std::uint64_t{std::min(u, v)} << 32) | std::max(u, v), t, S.triangles[t][k]});
        }
      }
      for (vertex_id v : added) mark[v] = 0;
      for (vertex_id v : near) mark[v] = 0;
      std::sort(half.begin(), half.end());
      std::vector<split_candidate> mine;
      std::vector<std::array<vertex_id, 4>> fresh;
      for (std::size_t k = 0; k + 1 < half.size(); ++k) {
        const auto& [key, t, w] = half[k];
        const auto& [key2, t2, z] = half[k + 1];
        if (key != key2) continue;
        if (!all && !fresh_tri[t] && !fresh_tri[t2]) continue;  // checked before
        const auto u = static_cast<vertex_id>(key >> 32), v = static_cast<vertex_id>(key & 0xffffffffu);
        flat_pair(f, u, v, t, w, t2, z, mine, fresh);
      }
      // only this task writes facet f's state (before, the pairs were moved out first, so a facet
      // with pairs found counted as checked all the same)
      end_flat_check(f, mine, fresh);
      found[i] = std::move(mine);
    }, [&](std::size_t i) { return static_cast<double>(facets_[fs[i]].triangles.size()); });
    std::vector<split_candidate> all;
    for (auto& v : found) all.insert(all.end(), v.begin(), v.end());
    return all;
  }

  /// A subfacet split worked out from the state at the start of phase C's loop (split_plan()),
  /// in parallel; the loop then only applies it, unless the state it read has changed since.
  struct split_plan {
    home h{};                   // the encroacher's home it read
    bool claim = false;         // the encroacher lies exactly in the facet: it becomes a facet vertex
    relation rel = relation::on_carrier;
    std::optional<rules::split_action> fired, fired_sub;  // for GSSE_CONFORM_TRACE
    point3 q{};                 // the split point (subject to the subsegment test)
    point3 at{};                // where it goes if no subsegment intervenes (centroid if q is outside)
    std::optional<std::pair<std::uint32_t, std::size_t>> sub;  // subsegment that q encroaches
    point3 m{};                 // its split point
  };

  split_plan plan_split(const split_candidate& c) const {
    const auto& p = out_.points;
    const auto& S = facets_[c.f];
    const auto& T = S.triangles[c.t];
    split_plan s;
    const std::vector<point3> elem{p[T[0]], p[T[1]], p[T[2]]};
    if (c.flat) {
      // not the circumcentre: a rotated rectangle's is its centre, and splitting the encroached
      // sides there makes rectangles again, each as cocircular as the first. A point at fixed,
      // unremarkable barycentric weights (or its projection on a side it encroaches) ends the tie.
      s.q = 0.4142 * elem[0] + 0.3319 * elem[1] + 0.2539 * elem[2];
    } else if (c.y != no_vertex) {
      s.h = out_.homes[c.y];
      // a free vertex exactly inside the facet becomes a facet vertex
      if (s.h.kind == home::free && geometry::orient3d(p[T[0]], p[T[1]], p[T[2]], p[c.y]) == 0 && locate(c.f, p[c.y], c.t) >= 0) {
        s.claim = true;
        return s;
      }
      std::optional<vertex_id> sv;
      std::optional<std::array<vertex_id, 2>> se;
      s.rel = facet_relation(c.f, s.h, sv, se);
      std::array<point3, 2> edge_pts{};
      if (se) edge_pts = {p[(*se)[0]], p[(*se)[1]]};
      const std::function<bool(const point3&)> in_facet = [&](const point3& q) { return locate(c.f, q, c.t) >= 0; };
      s.q = split_point_of(element_kind::subfacet, s.rel, elem, p[c.y], sv ? &p[*sv] : nullptr, se ? &edge_pts : nullptr, nullptr,
                           s.fired, &in_facet);
      if (s.fired && *s.fired == rules::split_action::project) {
        // the projection of a point across a thin layer, sheared like the lattices (wall_shear):
        // q moves by wall_shear times the encroacher's height above it (q's plane offset minus
        // the encroacher's), so that images of images stay images
        const point3 sq = s.q - wall_shift(S, dot(p[c.y] - s.q, shear_frame(S).second));
        if (in_facet(sq)) s.q = sq;
      }
    } else {
      s.q = split_point_of(element_kind::subfacet, relation::on_carrier, elem, elem[0], nullptr, nullptr, nullptr, s.fired);
    }
    s.q = out_of_balls(c.f, s.q);
    plan_subsegment(c.f, s);
    s.at = s.q;
    if (locate(c.f, s.at, c.t) < 0) s.at = out_of_balls(c.f, (1.0 / 3) * (elem[0] + elem[1] + elem[2]));  // outside: centroid
    if (!S.constant[static_cast<std::size_t>(S.axis)]) {
      // onto the slanted facet's plane (no drift), off the exact construction by a pseudo-random
      // 1e-10 of the subfacet in the plane (detail::jitter); a point on a seam between merged
      // facets (a projection or a circumcentre landing on a diagonal of a triangulated face) stays
      // on it, moved along it only: off it, the faces about it would leave one input facet for
      // its neighbour by a sliver, and a thin facet's coverage by more than rounding
      const auto j = detail::jitter(s.at);
      const double size = std::sqrt(std::max({squared_distance(elem[0], elem[1]), squared_distance(elem[1], elem[2]),
                                              squared_distance(elem[2], elem[0])}));
      if (const auto seam = on_seam(S, s.at, 1e-9 * size)) {
        const point3 &a = p[(*seam)[0]], &b = p[(*seam)[1]], d = b - a;
        const double t = dot(s.at - a, d) / dot(d, d), len = std::sqrt(dot(d, d));
        s.at = a + (t + 1e-10 * size * j[0] / len) * d;
      } else {
        s.at = s.at + (1e-10 * size) * (j[0] * S.e1 + j[1] * S.e2);
        s.at = s.at - dot(s.at - S.centre, S.unit) * S.unit;
      }
    }
    for (std::size_t k = 0; k < 3; ++k)  // exact on axis-aligned facets
      if (S.constant[k]) s.at[k] = S.constant_value[k];
    return s;
  }
  /// The seam of facet S (an edge between two of its merged input facets) within `tol` of q,
  /// strictly between its ends, if any.
  std::optional<std::array<vertex_id, 2>> on_seam(const facet_state& S, const point3& q, double tol) const {
    const auto& p = out_.points;
    for (const auto& e : S.seams) {
      const point3 &a = p[e[0]], d = p[e[1]] - a;
      const double dd = dot(d, d), t = dot(q - a, d) / dd;
      if (!(t > 0 && t < 1)) continue;
      const point3 r = q - a - t * d;
      if (dot(r, r) <= tol * tol) return e;
    }
    return std::nullopt;
  }
  /// A split point encroaching a subsegment of the facet splits that subsegment instead.
  void plan_subsegment(std::uint32_t f, split_plan& s) const {
    s.sub = encroached_subsegment(f, s.q);
    s.fired_sub.reset();
    if (s.sub && protected_subsegment(s.sub->first, s.sub->second)) s.sub.reset();  // see out_of_balls
    if (!s.sub) return;
    s.m = subsegment_split(s.sub->first, s.sub->second, relation::on_incident_edge, s.q, nullptr, s.fired_sub);
  }

  /// Phase C: split encroached (or, with a size, too large) subfacets. Returns the number of splits.
  std::size_t conform_facets(const std::vector<split_candidate>& flat) {
    std::size_t splits = 0;
    const auto& p = out_.points;
    auto todo = encroachers();
    if (!flat.empty()) {  // in facet and triangle order, each subfacet once
      auto before = [](const split_candidate& x, const split_candidate& y) { return std::pair(x.f, x.t) < std::pair(y.f, y.t); };
      std::vector<split_candidate> merged;
      std::merge(flat.begin(), flat.end(), todo.begin(), todo.end(), std::back_inserter(merged), before);
      merged.erase(std::unique(merged.begin(), merged.end(), [](const split_candidate& x, const split_candidate& y) {
                     return x.f == y.f && x.t == y.t;
                   }), merged.end());  // a flat one first: its split point, not the rule's
      todo = std::move(merged);
    }
    // The splits are planned in parallel, then applied in order. A plan is made again if what it
    // read changed meanwhile: the encroacher's home (claimed by an earlier facet) or, for the
    // subsegment test, a chain of the facet (split by an earlier plan).
    std::vector<split_plan> plans(todo.size());
    std::vector<std::size_t> ids(todo.size());
    std::iota(ids.begin(), ids.end(), std::size_t{0});
    for_each(execution::par(opt_.threads), ids, [&](std::size_t k) { plans[k] = plan_split(todo[k]); });
    std::vector<char> chain_changed(facets_.size(), 0);
    // points inserted in this phase, anywhere: a triangle whose circumball holds one is stale
    // until its facet is triangulated again next round
    recent_points<3> fresh(p[0], 2 * grid_h_);  // few points: larger cells, fewer lookups per ball
    auto note = [&](vertex_id v) { fresh.add(v, p[v]); };
    for (std::size_t k = 0; k < todo.size(); ++k) {
      const auto [f, t, y, flat_pair] = todo[k];
      auto& S = facets_[f];
      // not stale: no point inserted in this phase lies in its ball, so the encroacher found at
      // the start of the round stands (triangles change only next round)
      if (in_closed_ball(fresh, S.triangles[t])) continue;
      split_plan& s = plans[k];
      if (y != no_vertex && (out_.homes[y].kind != s.h.kind || out_.homes[y].id != s.h.id))
        s = plan_split(todo[k]);
      else if (chain_changed[f] && !s.claim)
        plan_subsegment(f, s);
      if (s.claim) {
        out_.homes[y] = {home::facet, f};
        S.interior.push_back(y);
        note(y);
        ++splits;
        continue;
      }
      // a point that exists already (an encroacher rotated onto the image an earlier split made
      // of it) would not end the encroachment, and the same split would come back every round:
      // split off-centre instead
      const auto& T = S.triangles[t];
      const double scale = std::sqrt(std::min({squared_distance(p[T[0]], p[T[1]]), squared_distance(p[T[1]], p[T[2]]),
                                               squared_distance(p[T[2]], p[T[0]])}));
      if (occupied(s.sub ? s.m : s.at, scale)) s = plan_split(todo[k]);  // made by a split of this phase
      // a rotation's image beside an existing point (closer than near_ratio of the subfacet's
      // shortest edge, not on it): two encroachers at one place along the shared edge (or in one
      // direction from the shared vertex) but on different shells, or one off the shells (a
      // circumcentre), snap to one image, and the second lands a hair from the first (occ_hammer:
      // edges down to 1e-5 of its shortest input edge; at --quality 1.414 307 below 1e-4 of it).
      // The subfacet is split at its circumcentre instead, as one no vertex encroaches would be,
      // where that point is clear. Projections keep their point: with them too, occ_pump_nut at
      // --quality 1.414 ended with 2.2 times the points (README.md here, Known limitations)
      if (!s.claim && !s.sub && s.fired &&
          (*s.fired == rules::split_action::rotate_edge || *s.fired == rules::split_action::rotate_vertex) &&
          !occupied(s.at, scale) && occupied(s.at, scale, near_ratio)) {
        auto c = todo[k];
        c.y = no_vertex;
        if (split_plan m = plan_split(c); !occupied(m.sub ? m.m : m.at, scale, near_ratio)) s = m;
      }
      if (occupied(s.sub ? s.m : s.at, scale)) {
        auto c = todo[k];
        c.flat = true;
        s = plan_split(c);
        if (occupied(s.sub ? s.m : s.at, scale)) {
          if (y == no_vertex && !flat_pair) continue;  // only too large (a protecting ball's pieces may be)
          throw conform_error(facet_name(f) + ": no new split point for a subfacet near " +
                              std::to_string(S.triangles[t][0] + 1) + " (every candidate is an existing point)");
        }
      }
      if (trace_on_ && (flat_pair || !s.fired)) ++trace_[flat_pair ? "subfacet/flat-pair/off-centre" : "subfacet/off-centre"];
      count_split(element_kind::subfacet, s.rel, s.fired);
      if (s.sub) {
        count_split(element_kind::subsegment, relation::on_incident_edge, s.fired_sub);
        auto& E = edges_[s.sub->first];
        const vertex_id v = add_point(s.m, {home::edge, s.sub->first});
        E.chain.insert(E.chain.begin() + static_cast<long>(s.sub->second) + 1, v);
        for (auto g : E.facets) chain_changed[g] = 1;
        note(v);
        ++splits;
        continue;
      }
      const vertex_id v = add_point(s.at, {home::facet, f});
      S.interior.push_back(v);
      note(v);
      ++splits;
    }
    return splits;
  }

  /// Thin layers between slanted parallel facets: the points of one wall are the other's images
  /// (projections, and lattices that match point for point), so the layer is filled with right
  /// prisms whose six vertices are cospherical. On an axis-aligned wall the images are exact and
  /// the symbolic perturbation triangulates every prism the same way; on a slanted one rounding
  /// (and the 1e-10 jitter) decides each prism by itself, and where two neighbours split their
  /// common side differently a flat tetrahedron joins them (its four vertices a rectangle, a
  /// dihedral angle of 0 degrees). Sliver refinement then split the walls again and again: the
  /// rotated trench ended with 2.5 times the points of the axis-aligned one. So on slanted facets
  /// an image is sheared: moved by `wall_shear` times its distance across the layer along the
  /// plane's canonical in-plane direction (lattice_frame), a linear map, the same for every pair
  /// of parallel planes, so the prisms lean all one way, their sides are parallelograms that are
  /// not cocircular, and no flat tetrahedron is Delaunay. 1e-4 of the thickness is far above
  /// rounding and far below anything a mesh shows; a wall point stays outside the equatorial balls
  /// about its sheared image while the wall's triangles are under 5,000 times the layer's
  /// thickness (beyond that it splits one of them again, as an unsheared point would split a
  /// triangle it encroached).
  static constexpr double wall_shear = 1e-4;
  /// The shear's in-plane direction and the normal of a slanted facet's plane: its class of
  /// parallel planes' (choose_shear_frames), the same for both orientations of a plane and for
  /// every plane parallel to it.
  static std::pair<point3, point3> shear_frame(const facet_state& S) {
    if (S.shear_class >= 0) return {S.shear_u, S.shear_n};
    const auto [u, v] = lattice_frame(S);
    return {u, cross(u, v)};
  }
  /// A layer's rims: where a thin slanted layer ends at a facet across it (its rim facet), the two
  /// walls' edges are parallel and their points are images too (the presplit divides parallel
  /// edges alike, and an edge point encroaching the other edge is projected onto it). An edge
  /// point can move only along its edge, so it cannot follow the walls' shear across the edge:
  /// four points, an edge pair and the wall pair next to it, were then off one plane and off one
  /// circle by the same 1e-6 of the thickness, and the sphere through them was often empty: a
  /// flat tetrahedron of four boundary points (the rotated trench's first mesh: 99 on the liner's
  /// rims, and 72 more at its corners; docs/benchmarks.md, fifty-fourth part). So the edge points
  /// are sheared along their edge by the along-edge part of each slanted plane's shift through
  /// the edge (edge_shear), and each class of parallel slanted planes shears at 45 degrees
  /// between its longest input edge and that edge's in-plane perpendicular: on a box-like layer
  /// (a turned CAD or TCAD structure) every rim edge then takes half the shear, the rest of the
  /// wall pairs' shift runs across the rim, and a rim rectangle whose wall pair lies straight in
  /// from the edge pair is a planar, non-cocircular quadrilateral again. Measured on the rotated
  /// benchmark structures at 1e5 tetrahedra: the rounds' cavity cells trench 232,549 -> 211,477,
  /// MOSFET 23,450 -> 17,355, FinFET 41,716 -> 27,571 (either half alone did less, and the
  /// direction alone doubled the MOSFET's work). Rim rectangles whose wall pair lies diagonally,
  /// and a layer's corners (two walls at 90 degrees), are left.
  void choose_shear_frames() {
    const auto& p = out_.points;
    // a direction's sign made canonical: its largest component positive
    auto canonical = [](point3 x) {
      std::size_t big = 0;
      for (std::size_t k = 1; k < 3; ++k)
        if (std::abs(x[k]) > std::abs(x[big])) big = k;
      return x[big] < 0 ? -1.0 * x : x;
    };
    // classes of parallel slanted planes: normals (largest component made positive) within 1e-9
    // radians of a class's first, found through bins of 1e-6 of the components and their
    // neighbours (a placement choice, not topology). Walls parallel only to more than that get
    // classes of their own and may shear different ways. (Grouping within 1e-6 radians changed 11
    // of the 48 corpus_quality inputs, mostly by a few points, scad_example021 by 6.8% more
    // points and 6 more rounds, and improved none: docs/benchmarks.md, fifty-fifth part)
    struct klass {
      point3 n;
      std::vector<std::uint32_t> facets;
    };
    std::vector<klass> classes;
    std::map<std::array<long, 3>, std::vector<std::size_t>> bins;
    auto bin_of = [](const point3& n) {
      std::array<long, 3> b{};
      for (std::size_t k = 0; k < 3; ++k) b[k] = static_cast<long>(std::floor(n[k] * 1e6));
      return b;
    };
    for (std::uint32_t f = 0; f < facets_.size(); ++f) {
      const auto& S = facets_[f];
      if (S.constant[static_cast<std::size_t>(S.axis)] || S.sides.empty()) continue;
      const point3 n = canonical(S.unit);
      const auto b = bin_of(n);
      std::size_t found = classes.size();
      for (long dx = -1; dx <= 1 && found == classes.size(); ++dx)
        for (long dy = -1; dy <= 1 && found == classes.size(); ++dy)
          for (long dz = -1; dz <= 1 && found == classes.size(); ++dz) {
            const auto it = bins.find({b[0] + dx, b[1] + dy, b[2] + dz});
            if (it == bins.end()) continue;
            for (std::size_t c : it->second) {
              const point3 x = cross(classes[c].n, n);
              if (dot(x, x) < 1e-18) {
                found = c;
                break;
              }
            }
          }
      if (found == classes.size()) {
        classes.push_back({n, {}});
        bins[b].push_back(found);
      }
      classes[found].facets.push_back(f);
    }
    for (std::size_t c = 0; c < classes.size(); ++c) {
      const point3 n = classes[c].n;
      // the longest input edge of the class's facets, in the plane, its largest component positive
      double longest = 0;
      point3 d{};
      for (std::uint32_t f : classes[c].facets)
        for (const auto& side : facets_[f].sides) {
          const point3 x = p[edges_[side.first].v] - p[edges_[side.first].u];
          if (dot(x, x) > longest) longest = dot(x, x), d = x;
        }
      d = d - dot(d, n) * n;
      if (!(dot(d, d) > 0)) continue;
      d = canonical((1.0 / std::sqrt(dot(d, d))) * d);
      point3 u = d + cross(n, d);
      u = (1.0 / std::sqrt(dot(u, u))) * u;
      for (std::uint32_t f : classes[c].facets) {
        facets_[f].shear_u = u, facets_[f].shear_n = n;
        facets_[f].shear_class = static_cast<int>(c);
      }
    }
  }
  /// An edge point's shear (the rims above): along the edge, the along-edge part of the wall
  /// shift of each class of slanted planes through the edge, once per class (two coplanar facets
  /// of one plane through an edge would count it twice).
  point3 edge_shear(std::uint32_t e) const override {
    const auto& E = edges_[e];
    const auto& p = out_.points;
    point3 d = p[E.v] - p[E.u];
    d = (1.0 / std::sqrt(dot(d, d))) * d;
    point3 c{};
    std::vector<int> seen;
    for (std::uint32_t f : E.facets) {
      const auto& S = facets_[f];
      if (S.shear_class < 0 || std::find(seen.begin(), seen.end(), S.shear_class) != seen.end()) continue;
      seen.push_back(S.shear_class);
      c = c + dot(wall_shift(S, dot(p[E.u] - box_lo_, S.shear_n)), d) * d;
    }
    return c;
  }
  /// The shift of a point of facet S whose plane lies `offset` along the canonical normal from the
  /// lattices' origin (nothing on an axis-aligned facet, whose images are exact). The class's
  /// direction lies in its first facet's plane; it is projected into S's own, so that a facet of
  /// the class that is parallel only within the class's tolerance keeps its points in its plane
  /// (unprojected, the 1e-6 radian grouping moved scad_example007's lattice points up to about
  /// 4e-9 off their facets, and its graded mesh failed --verify: 275 hull faces on no input facet)
  static point3 wall_shift(const facet_state& S, double offset) {
    if (S.constant[static_cast<std::size_t>(S.axis)]) return {};
    const point3 d = (wall_shear * offset) * shear_frame(S).first;
    return d - dot(d, S.unit) * S.unit;
  }

  /// A facet's in-plane orthonormal frame for its lattices, from the normal only: e1 = unit x
  /// (least axis), flipped with the normal so that the two orientations of a plane get the same
  /// frame (parallel facets then get the same lattice).
  static std::pair<point3, point3> lattice_frame(const facet_state& S) {
    double sign = 1;
    for (std::size_t k = 0; k < 3; ++k)
      if (S.unit[k] != 0) {
        sign = S.unit[k] > 0 ? 1.0 : -1.0;
        break;
      }
    return {sign * S.e1, S.e2};
  }

  /// options::thin_layer: per facet, the spacing of its lattice (and of its PLC edges' splits):
  /// thin_layer x the least gap to a facet it faces across a thin layer, where that is below the
  /// size; the size elsewhere. Computed once, before the edges are split.
  void find_thin_layers() {
    spacing_.assign(facets_.size(), opt_.size);
    if (!(opt_.thin_layer > 0) || !(opt_.size > 0) || graded()) return;
    std::vector<thin::facet> fs(facets_.size());
    for (std::uint32_t f = 0; f < facets_.size(); ++f) {
      const auto& S = facets_[f];
      auto& F = fs[f];
      F.unit = S.unit, F.e1 = S.e1, F.e2 = S.e2;
      for (vertex_id v : S.corners) F.corners.push_back(out_.points[v]), F.corner_ids.push_back(v);
      for (auto [e, fw] : S.sides) F.sides.push_back({out_.points[edges_[e].u], out_.points[edges_[e].v]});
    }
    const auto gap = thin::layer_gaps(fs, model_size_, opt_.size / opt_.thin_layer);
    for (std::uint32_t f = 0; f < facets_.size(); ++f)
      if (std::isfinite(gap[f])) spacing_[f] = std::min(opt_.size, opt_.thin_layer * gap[f]);
  }
  double edge_size(std::uint32_t e) const override {
    double h = opt_.size;
    for (std::uint32_t f : edges_[e].facets)
      if (f < spacing_.size()) h = std::min(h, spacing_[f]);
    return h;
  }

  /// Sizing: a triangular lattice of spacing `size` (spacing_[f]: finer on a thin layer's wall) in each facet's plane, clipped to the facet
  /// and kept size/2 away from its boundary vertices. Exact on axis-aligned facets (the constant
  /// coordinate is copied), within rounding on slanted ones. The lattice is global: its frame
  /// comes from the plane's normal alone (sign made canonical) and its origin is one point for
  /// all facets, so parallel facets get the same lattice, point opposite point. Across a layer
  /// thinner than the size (an oxide, a liner) a point then projects onto a vertex of the other
  /// side, not into a triangle whose equatorial ball it would encroach: lattices anchored at each
  /// facet's own corner were offset by the layer's step and refined the layer's both walls 70%
  /// beyond the size (the trench liner).
  void seed_facets() {
    const point3 origin = box_lo_;
    // each facet's lattice is computed in parallel (it reads only its own facet), then the points
    // are added facet by facet, so ids are the same for any thread count
    std::vector<std::vector<point3>> seeds(facets_.size());
    std::vector<std::uint32_t> ids(facets_.size());
    std::iota(ids.begin(), ids.end(), 0u);
    const auto base = static_cast<vertex_id>(out_.points.size());
    for_each(execution::par(opt_.threads), ids, [&](std::uint32_t f) {
      const auto& S = facets_[f];
      if (S.sides.empty()) return;
      const double h = spacing_[f];  // run() found them first
      const auto vs = facet_vertices(f);
      const point3 o = out_.points[vs[0]];
      const auto [u, v] = lattice_frame(S);
      const double ao = dot(o - origin, u), bo = dot(o - origin, v);
      const point3 shift = wall_shift(S, dot(o - origin, shear_frame(S).second));
      double ulo = 1e300, uhi = -1e300, vlo = 1e300, vhi = -1e300;
      for (vertex_id w : vs) {
        const point3 d = out_.points[w] - origin;
        ulo = std::min(ulo, dot(d, u)), uhi = std::max(uhi, dot(d, u));
        vlo = std::min(vlo, dot(d, v)), vhi = std::max(vhi, dot(d, v));
      }
      std::vector<point3> mine;  // moved into seeds[f] at the end: no shared cache lines meanwhile
      auto at = [&](vertex_id w) -> const point3& { return w < base ? out_.points[w] : mine[w - base]; };
      hash_grid<3> near(o, 0.5 * h);
      for (vertex_id w : vs) near.insert(w, out_.points[w]);
      // lattice point (i, j) at ((i + 0.0137 + (j odd) / 2) h, (j + 0.0271) row) from the origin:
      // the offsets keep rows and columns off axis-aligned boundary edges through round numbers
      const double row = h * std::sqrt(3.0) / 2;
      const long j0 = static_cast<long>(std::floor(vlo / row - 0.0271)), i0 = static_cast<long>(std::floor(ulo / h - 0.5137));
      for (long j = j0; row * (static_cast<double>(j) + 0.0271) <= vhi; ++j)
        for (long i = i0; h * (static_cast<double>(i) + 0.0137) <= uhi; ++i) {
          const double a = h * (static_cast<double>(i) + 0.0137 + 0.5 * static_cast<double>(j & 1));
          const double b = row * (static_cast<double>(j) + 0.0271);
          if (a < ulo || a > uhi || b < vlo) continue;
          point3 q = o + (a - ao) * u + (b - bo) * v + shift;
          for (std::size_t k = 0; k < 3; ++k)
            if (S.constant[k]) q[k] = S.constant_value[k];
          bool clear = true;
          point3 lo, hi;
          for (std::size_t k = 0; k < 3; ++k) lo[k] = q[k] - 0.5 * h, hi[k] = q[k] + 0.5 * h;
          near.visit(lo, hi, [&](vertex_id w) { clear = clear && squared_distance(at(w), q) >= 0.25 * h * h; });
          if (!clear || locate(f, q) < 0) continue;
          near.insert(static_cast<vertex_id>(base + mine.size()), q);
          mine.push_back(q);
        }
      seeds[f] = std::move(mine);
    }, [&](std::uint32_t f) { return static_cast<double>(boundary_size(f)); });
    for (std::uint32_t f = 0; f < facets_.size(); ++f)
      for (const auto& q : seeds[f]) facets_[f].interior.push_back(add_point(q, {home::facet, f}));
  }

  /// Graded sizing: each facet seeded with the size field's points in its plane (the dyadic
  /// lattices of sizing::place_points, triangular, in the same global frame as seed_facets), kept
  /// half their spacing from the facet's edges (their subsegments) and interior points. Without it the facets would be
  /// refined from their corners by circumcentres, a few rows per round.
  void seed_facets_graded() {
    const point3 origin = box_lo_;
    std::vector<std::vector<point3>> seeds(facets_.size());
    std::vector<std::uint32_t> ids(facets_.size());
    std::iota(ids.begin(), ids.end(), 0u);
    for_each(execution::par(opt_.threads), ids, [&](std::uint32_t f) {
      const auto& S = facets_[f];
      if (S.sides.empty()) return;
      const auto vs = facet_vertices(f);
      const auto [u, v] = lattice_frame(S);
      const point3 o = out_.points[vs[0]];
      const double ao = dot(o - origin, u), bo = dot(o - origin, v);
      const point3 shift = wall_shift(S, dot(o - origin, shear_frame(S).second));
      auto lift = [&](const point2& x) {
        point3 q = o + (x[0] - ao) * u + (x[1] - bo) * v + shift;
        for (std::size_t k = 0; k < 3; ++k)
          if (S.constant[k]) q[k] = S.constant_value[k];
        return q;
      };
      // what a seed keeps `keep` (half its spacing) from: the subsegments of the facet's edges,
      // not only their points. A seed that kept off the chain's points only could lie on an edge
      // between two of them that the size field had left far apart, and the edge's split for it
      // (its projection) then landed a hair from it: gmsh_fillet with --grade alone had boundary
      // points 3.6e-7 apart, 7e-6 of its shortest input edge (docs/benchmarks.md)
      auto in_frame = [&](vertex_id w) {
        const point3 d = out_.points[w] - origin;
        return point2{dot(d, u), dot(d, v)};
      };
      sizing::aabb<2> box = sizing::aabb<2>::empty();
      for (vertex_id w : vs) box.add(in_frame(w));
      std::vector<std::array<point2, 2>> pieces;
      std::vector<sizing::aabb<2>> at;
      for (auto [e, fw] : S.sides) {
        const auto& C = edges_[e].chain;
        for (std::size_t i = 0; i + 1 < C.size(); ++i) pieces.push_back({in_frame(C[i]), in_frame(C[i + 1])});
      }
      for (vertex_id w : S.interior) pieces.push_back({in_frame(w), in_frame(w)});
      for (const auto& [a, b] : pieces) {
        sizing::aabb<2> pb = sizing::aabb<2>::empty();
        pb.add(a);
        pb.add(b);
        at.push_back(pb);
      }
      const sizing::box_tree<2> near(std::move(at), std::vector<double>(pieces.size(), 0.0));
      sizing::placement<2> where;
      where.segment_of = [&](const point2& x) { return locate(f, lift(x)) >= 0 ? 1 : sizing::no_segment; };
      where.clear = [&](const point2& x, double keep) {
        // and off the protecting balls of the facet's corners by `keep`: a seed inside one is an
        // encroacher no split ends (its image is pushed out to the sphere, onto the image before it)
        if (!S.balls.empty()) {
          const point3 q = lift(x);
          for (vertex_id b : S.balls)
            if (const double r = ball(b) + keep; squared_distance(q, out_.points[b]) < r * r) return false;
        }
        return near.visit([&](const sizing::aabb<2>& b) { return b.distance2(x) < keep * keep; },
                          [&](std::uint32_t g) { return sizing::segment_distance2(pieces[g][0], pieces[g][1], x) >= keep * keep; });
      };
      const double extent = std::sqrt(squared_distance(box.lo, box.hi));
      // lift shifts a point by the wall shear, in the plane; clear measures in the unshifted frame
      where.slack = 2 * std::sqrt(dot(shift, shift)) + 1e-9 * extent;
      const double d0 = opt_.size > 0 ? std::min(opt_.size, extent) : 0.5 * extent;
      const auto pts = sizing::place_points<2>([&](const point2& x, int, double cap) { return size_at(lift(x), cap); }, d0, box,
                                               where, 1, 1.0, false, sizing::unbounded, opt_.local_slope);
      std::vector<point3> mine;
      mine.reserve(pts.size());
      for (const auto& x : pts) mine.push_back(lift(x));
      seeds[f] = std::move(mine);
    }, [&](std::uint32_t f) { return static_cast<double>(boundary_size(f)); });
    for (std::uint32_t f = 0; f < facets_.size(); ++f)
      for (const auto& q : seeds[f]) facets_[f].interior.push_back(add_point(q, {home::facet, f}));
  }

  std::size_t vertex_count(std::uint32_t f) const { return boundary_size(f) + facets_[f].interior.size(); }

  /// conform(): the whole run. keep: the state stays for continue_run() (session::start()).
  boundary<3> run(bool keep = false) {
    if (sized()) find_thin_layers();
    presplit_edges();
    if (sized()) {
      conform_segments();
      std::vector<std::uint32_t> all(facets_.size());
      std::iota(all.begin(), all.end(), 0u);
      triangulate_all(all);
      if (graded())
        seed_facets_graded();
      else
        seed_facets();
    }
    return rounds({}, keep);
  }

  void on_facet(std::uint32_t f, vertex_id v) override { facets_.at(f).interior.push_back(v); }

  /// The subfacets `split` of `prev` (indices into prev.faces) by facet, as sorted corner triples:
  /// rounds() splits those still there in its first round.
  using wanted_faces = std::map<std::uint32_t, std::vector<std::array<vertex_id, 3>>>;
  wanted_faces wanted_of(const boundary<3>& prev, const std::vector<std::size_t>& split) const {
    // (input facet naming a facet, facet), sorted: built on the first call and kept, as the
    // facets are fixed once the constructor has set them up (a map of every facet built for each
    // call was 2.6 ms of each refinement round on the Gmsh torus's 38,974 facets); not in the
    // constructor, so a run without refinement rounds does not pay for it
    if (facet_of_.size() != facets_.size()) {
      facet_of_.clear();
      for (std::uint32_t f = 0; f < facets_.size(); ++f) facet_of_.push_back({facets_[f].source, f});
      std::sort(facet_of_.begin(), facet_of_.end());
    }
    wanted_faces wanted;
    for (auto k : split) {
      // the last facet of that name, as a map assigned in facet order would keep
      const std::uint32_t src = prev.face_source.at(k);
      auto it = std::upper_bound(facet_of_.begin(), facet_of_.end(), std::pair{src, ~std::uint32_t{0}});
      if (it == facet_of_.begin() || std::prev(it)->first != src) continue;
      auto T = prev.faces[k];
      std::sort(T.begin(), T.end());
      wanted[std::prev(it)->second].push_back(T);
    }
    return wanted;
  }

  /// resume(): after restore(), the subfacets `split` of `prev` (by index) are split in the first
  /// round as too large ones are (circumcentre, or the subsegment it encroaches), then rounds.
  boundary<3> resume_run(const boundary<3>& prev, const std::vector<std::size_t>& split, bool keep = false) {
    auto wanted = wanted_of(prev, split);
    conform_segments();
    // a facet whose vertices are those `prev` triangulated keeps prev's triangles (the
    // triangulation is a function of the vertex set) and its pairs are known not flat (prev's
    // run ended with none, and added points only empty fewer spheres): only the facets the
    // subsegment splits above changed are triangulated and checked again, in the first round
    std::map<std::uint32_t, std::vector<std::array<vertex_id, 3>>> had;  // by input facet, in prev's order
    for (std::size_t k = 0; k < prev.faces.size(); ++k) had[prev.face_source[k]].push_back(prev.faces[k]);
    // the faces prev kept with an apex (options::delaunay_faces) were not clean: checked afresh
    std::set<std::array<vertex_id, 3>> kept;
    for (std::size_t k = 0; k < prev.face_apex.size(); ++k)
      if (prev.face_apex[k] != no_vertex) {
        auto T = prev.faces[k];
        std::sort(T.begin(), T.end());
        kept.insert(T);
      }
    if (prev.meshed_sides.size() == facets_.size()) meshed_ = prev.meshed_sides;
    seen_.assign(facets_.size(), 0);
    for (std::uint32_t f = 0; f < facets_.size(); ++f) {
      auto it = had.find(facets_[f].source);
      std::vector<vertex_id> vs;
      if (it != had.end())
        for (const auto& T : it->second) vs.insert(vs.end(), T.begin(), T.end());
      std::sort(vs.begin(), vs.end());
      vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
      if (!vs.empty() && vs == facet_vertices(f)) {
        adopt(f, it->second, std::move(vs));
        seen_[f] = vertex_count(f);
      }
    }
    // every subfacet `prev` had was clean (neither encroached nor too large) against its points:
    // only the points added since are checked against those (encroachers()), as within a run
    for (auto& [src, Ts] : had)
      for (auto& T : Ts) std::sort(T.begin(), T.end());
    for (auto& S : facets_) {
      auto it = had.find(S.source);
      if (it == had.end() || S.checked) continue;
      if (kept.empty()) {
        S.clean = key_set<3>(it->second);
      } else {
        std::vector<std::array<vertex_id, 3>> clean;
        for (const auto& T : it->second)
          if (!kept.count(T)) clean.push_back(T);
        S.clean = key_set<3>(clean);
      }
    }
    checked_upto_ = prev.points.size();
    return rounds(std::move(wanted), keep);
  }

  /// session::next(): goes on from where the last rounds() ended (`prev` is what it returned):
  /// the `added` free points, then the subfacets `split` of `prev` in the first round, as
  /// resume_run() does after rebuilding all of this. Nothing is rebuilt: the grids, chains, facet
  /// triangulations and what the last check found clean carry over, and the checks of this round
  /// read only the points added since, as the rounds of one run do.
  boundary<3> continue_run(const boundary<3>& prev, const std::vector<point3>& added, const std::vector<std::size_t>& split) {
    auto wanted = wanted_of(prev, split);
    for (const auto& q : added) add_free(q);
    return rounds(std::move(wanted), true);
  }

  /// Facet f takes the triangles `ts` of an earlier triangulation of its present vertices `vs`
  /// (facet_vertices(f)), as triangulate(f) would have made them.
  void adopt(std::uint32_t f, const std::vector<std::array<vertex_id, 3>>& ts, std::vector<vertex_id> vs) {
    auto& S = facets_[f];
    S.checked = false;
    S.triangles = ts;
    S.boundary_size = boundary_size(f);
    S.wrapped = std::move(vs);
    S.wrapped_boundary.clear();  // the next triangulation wraps the whole facet
    S.fresh.clear();
    S.ball.assign(ts.size(), {});
    S.ball_known.assign(ts.size(), 0);
    S.circles.assign(ts.size(), {0, 0, std::numeric_limits<double>::quiet_NaN()});
    index_triangles(f);
  }

  /// Rounds until no subfacet is split; the subfacets `wanted` (by facet, sorted corners) that
  /// the first round's triangulations still have are split in it. seen_: per facet, its vertex
  /// count when last triangulated and checked for flat pairs (0: never). keep: the state stays
  /// for continue_run() (the result is a copy), else the result is moved out of it.
  boundary<3> rounds(wanted_faces wanted = {}, bool keep = false) {
    seen_.resize(facets_.size(), 0);
    const bool trace = trace_on_;
    for (;;) {
      ++out_.rounds;
      const std::size_t seg_splits = conform_segments();
      std::vector<std::uint32_t> changed;  // only facets whose vertex set changed
      for (std::uint32_t f = 0; f < facets_.size(); ++f)
        if (vertex_count(f) != seen_[f]) changed.push_back(f);
      triangulate_all(changed);
      for (auto f : changed) seen_[f] = vertex_count(f);
      auto extra = flat_pairs(changed);
      if (!wanted.empty()) {
        // a triangle is looked up only if its three corners are corners of wanted ones (a mark
        // per point): a pass over a large facet for a few wanted triangles was a serial 0.5-1 ms
        // a refinement round
        std::vector<char> corner(out_.points.size(), 0);
        for (auto& [f, Ts] : wanted) {
          std::sort(Ts.begin(), Ts.end());
          for (const auto& T : Ts)
            for (auto v : T) corner[v] = 1;
          const auto& tri = facets_[f].triangles;
          for (std::uint32_t t = 0; t < tri.size(); ++t) {
            auto T = tri[t];
            if (!(corner[T[0]] && corner[T[1]] && corner[T[2]])) continue;
            std::sort(T.begin(), T.end());
            if (std::binary_search(Ts.begin(), Ts.end(), T)) extra.push_back({f, t, no_vertex});
          }
          for (const auto& T : Ts)
            for (auto v : T) corner[v] = 0;
        }
        std::sort(extra.begin(), extra.end(), [](const split_candidate& x, const split_candidate& y) {
          return std::tuple(x.f, x.t, !x.flat) < std::tuple(y.f, y.t, !y.flat);
        });
        wanted.clear();
      }
      const std::size_t facet_splits = conform_facets(extra);
      if (trace) {
        opt_.trace("conform round " + std::to_string(out_.rounds) + ": " + std::to_string(seg_splits) +
                   " subsegment splits, " + std::to_string(facet_splits) + " subfacet splits, " +
                   std::to_string(out_.points.size()) + " points");
        for (auto& [k, n] : trace_) opt_.trace("   " + k + " " + std::to_string(n));
        trace_.clear();
      }
      if (facet_splits == 0) break;
    }
    out_.faces.clear();
    out_.face_source.clear();
    out_.face_apex.clear();
    for (std::uint32_t f = 0; f < facets_.size(); ++f) {
      const auto& S = facets_[f];
      for (std::size_t t = 0; t < S.triangles.size(); ++t) {
        out_.faces.push_back(S.triangles[t]);
        out_.face_source.push_back(S.source);
        // the last check's verdict holds: the rounds end with a check that split nothing
        if (opt_.delaunay_faces) out_.face_apex.push_back(t < S.relaxed.size() && S.relaxed[t] ? S.apex[t] : no_vertex);
      }
    }
    out_.protect = ball_;
    for (std::size_t v = 0; v < guard_.size() && v < out_.protect.size(); ++v)
      if (guard_[v] > 0) out_.protect[v] = guard_[v];
    out_.meshed_sides = meshed_;
    if (keep) return out_;
    return std::move(out_);
  }

 private:
  std::vector<facet_state> facets_;
  std::vector<double> spacing_;  // per facet, its lattice's spacing (find_thin_layers; empty: the size)
  std::vector<std::uint32_t> edge_of_;
  std::vector<std::array<vertex_id, 2>> ends_;
  std::vector<std::array<bool, 2>> meshed_;  // per facet: is its positive / negative side in a segment
  front::facet_lines lines_;
  std::size_t checked_upto_ = 0;  // points that existed at the last check of every facet
  std::vector<std::size_t> seen_;  // per facet: vertex count when last triangulated (rounds())
  mutable std::vector<std::pair<std::uint32_t, std::uint32_t>> facet_of_;  // wanted_of()
};

}  // namespace

namespace {
boundary<2> finish2(state<2>& s) {
  auto& out = s.out();
  for (std::uint32_t e = 0; e < s.edges().size(); ++e) {
    const auto& ch = s.edges()[e].chain;
    for (std::size_t i = 0; i + 1 < ch.size(); ++i) {
      out.faces.push_back({ch[i], ch[i + 1]});
      out.face_source.push_back(e);
    }
  }
  return std::move(out);
}
}  // namespace

boundary<2> conform(const plc<2>& p, const std::vector<point2>& volume, const options& o) {
  state<2> s(p, volume, o);
  for (const auto& e : p.edges) s.edge_id(e[0], e[1], 0);
  s.find_acute();
  s.presplit_edges();
  ++s.out().rounds;
  s.conform_segments();
  return finish2(s);
}


boundary<3> conform(const plc<3>& p, const std::vector<point3>& volume, const options& o) {
  state3 s(p, volume, o);
  return s.run();
}

namespace {
template <std::size_t D>
std::vector<point<D>> original_volume(const boundary<D>& prev) {
  const auto first = prev.points.begin() + static_cast<long>(std::min(prev.points.size(), prev.plc_points));
  return {first, first + static_cast<long>(std::min(prev.volume_points, prev.points.size() - prev.plc_points))};
}
}  // namespace

boundary<2> resume(const plc<2>& p, const boundary<2>& prev, const std::vector<point2>& added,
                   const std::vector<std::size_t>& split, const options& o) {
  state<2> s(p, original_volume(prev), o);
  for (const auto& e : p.edges) s.edge_id(e[0], e[1], 0);
  s.find_acute();
  s.restore(prev, added);
  ++s.out().rounds;
  for (auto k : split) {
    const auto& F = prev.faces.at(k);
    s.split_requested(prev.face_source.at(k), F[0], F[1]);
  }
  s.conform_segments();
  return finish2(s);
}

boundary<3> resume(const plc<3>& p, const boundary<3>& prev, const std::vector<point3>& added,
                   const std::vector<std::size_t>& split, const options& o) {
  state3 s(p, original_volume(prev), o);
  s.restore(prev, added);
  return s.resume_run(prev, split);
}

template <>
struct session<2>::impl {
  const plc<2>& p;
  options o;
};
template <>
struct session<3>::impl {
  const plc<3>& p;
  options o;
  std::unique_ptr<state3> s{};  // as the last next() left it (its out() is what it returned)
};
template <std::size_t D>
session<D>::session(const plc<D>& p, const options& o) : impl_(new impl{p, o}) {}
template <std::size_t D>
session<D>::~session() = default;

template <>
boundary<2> session<2>::start(const std::vector<point2>& volume) {
  return conform(impl_->p, volume, impl_->o);
}
template <>
boundary<3> session<3>::start(const std::vector<point3>& volume) {
  auto& m = *impl_;
  m.s.reset();
  auto s = std::make_unique<state3>(m.p, volume, m.o);
  auto b = s->run(true);
  m.s = std::move(s);
  return b;
}
template <>
boundary<2> session<2>::next(const boundary<2>& previous, const std::vector<point2>& added, const std::vector<std::size_t>& split) {
  return resume(impl_->p, previous, added, split, impl_->o);
}
double thin_layer_ratio(double bound) { return bound >= 1.4 ? 0.96 * std::sqrt(3 * bound * bound - 0.75) : 0.0; }

bool face_encroached(const boundary<3>& b, std::size_t f, const point3& q) {
  const auto& p = b.points;
  const auto& F = b.faces[f];
  if (f >= b.face_apex.size() || b.face_apex[f] == no_vertex) return geometry::in_equatorial(p[F[0]], p[F[1]], p[F[2]], q) >= 0;
  return geometry::breaks_face_with_apex(p[F[0]], p[F[1]], p[F[2]], p[b.face_apex[f]], q);
}

namespace {
/// Whether free points `added` leave boundary `b` (conforming) as it is: none lies in the closed
/// equatorial ball of a subfacet or the closed diametral ball of an edge of one whose ends both
/// lie on the PLC's edges or vertices (every subsegment among them), decided exactly; a point on
/// such a sphere counts as inside (the conformer's tie rule is not asked: a tie goes to a resume).
/// Nothing else in a round of the conformer reacts to a free point: it splits only encroached
/// subsegments and subfacets, faces too large for the size (b's were not) and flat pairs (a free
/// point joins no facet: one on a facet lies in a subfacet's closed ball).
bool leaves_unchanged(const boundary<3>& b, const std::vector<point3>& added, unsigned threads) {
  if (added.empty()) return true;
  // the added points sorted by x: a face's ball asks a range of them
  std::vector<std::uint32_t> by_x(added.size());
  std::iota(by_x.begin(), by_x.end(), 0u);
  std::sort(by_x.begin(), by_x.end(), [&](std::uint32_t i, std::uint32_t j) { return added[i][0] < added[j][0] || (added[i][0] == added[j][0] && i < j); });
  std::vector<double> xs(by_x.size());
  for (std::size_t i = 0; i < by_x.size(); ++i) xs[i] = added[by_x[i]][0];
  const auto& p = b.points;
  auto on_edges = [&](vertex_id v) { return v < b.homes.size() && (b.homes[v].kind == home::vertex || b.homes[v].kind == home::edge); };
  // visits the added points within the box of ball (c, r); false as soon as f says so
  auto any_in = [&](const point3& c, double r, auto&& f) {
    auto it = std::lower_bound(xs.begin(), xs.end(), c[0] - r);
    for (auto i = static_cast<std::size_t>(it - xs.begin()); i < xs.size() && xs[i] <= c[0] + r; ++i) {
      const point3& q = added[by_x[i]];
      if (std::abs(q[1] - c[1]) <= r && std::abs(q[2] - c[2]) <= r && squared_distance(q, c) <= r * r && f(q)) return true;
    }
    return false;
  };
  constexpr std::size_t piece = 4096;
  std::vector<std::size_t> pieces((b.faces.size() + piece - 1) / piece);
  std::iota(pieces.begin(), pieces.end(), std::size_t{0});
  std::vector<char> hit(pieces.size(), 0);
  for_each(execution::par(threads), pieces, [&](std::size_t k) {
    for (std::size_t f = k * piece; f < std::min(b.faces.size(), (k + 1) * piece) && !hit[k]; ++f) {
      const auto& F = b.faces[f];
      const auto [c, r] = detail::equatorial_bound(p[F[0]], p[F[1]], p[F[2]]);
      if (any_in(c, r, [&](const point3& q) { return geometry::in_equatorial(p[F[0]], p[F[1]], p[F[2]], q) >= 0; })) {
        hit[k] = 1;
        break;
      }
      // a face kept with an apex: also the sphere through it and the apex (face_encroached)
      if (f < b.face_apex.size() && b.face_apex[f] != no_vertex) {
        point3 sc;
        double sr = 0;
        if (!geometry::circumball_bound(p[F[0]], p[F[1]], p[F[2]], p[b.face_apex[f]], sc, sr) ||
            any_in(sc, sr, [&](const point3& q) { return face_encroached(b, f, q); })) {
          hit[k] = 1;
          break;
        }
      }
      for (std::size_t i = 0; i < 3 && !hit[k]; ++i) {
        const vertex_id u = F[i], v = F[(i + 1) % 3];
        // from every face that has it: the faces of two facets on a subsegment may both list it
        // the same way round, and a facet's edge with no facet beyond it is in one face only
        if (!on_edges(u) || !on_edges(v)) continue;
        const auto [m, h] = detail::diametral_bound(p[u], p[v]);
        if (any_in(m, h, [&](const point3& q) { return geometry::in_diametral(p[u], p[v], q) >= 0; })) hit[k] = 1;
      }
    }
  });
  return std::find(hit.begin(), hit.end(), 1) == hit.end();
}
}  // namespace

template <>
boundary<3> session<3>::next(const boundary<3>& previous, const std::vector<point3>& added, const std::vector<std::size_t>& split) {
  auto& m = *impl_;
  // handed what the last call returned (compared in full: a copy of the points and faces)
  const bool same = m.s && previous.points == m.s->out().points && previous.faces == m.s->out().faces &&
                    previous.face_source == m.s->out().face_source;
  std::unique_ptr<state3> s = same ? std::move(m.s) : nullptr;  // a throw below leaves none
  // nothing to split and no added point encroaching: the boundary with the points appended, as a
  // resume would return it, without rebuilding the conformer's state for it (a graded run's size
  // round: one point, a resume of 0.96 s on the graded trench). The session stays empty, so a
  // later call resumes
  if (!s && split.empty() && leaves_unchanged(previous, added, m.o.threads)) {
    boundary<3> b = previous;
    b.points.insert(b.points.end(), added.begin(), added.end());
    b.homes.insert(b.homes.end(), added.size(), home{home::free, 0});
    ++b.rounds;
    return b;
  }
  boundary<3> b;
  if (s) {
    b = s->continue_run(previous, added, split);
  } else {
    s = std::make_unique<state3>(m.p, original_volume(previous), m.o);
    s->restore(previous, added);
    b = s->resume_run(previous, split, true);
  }
  m.s = std::move(s);
  return b;
}
template <>
void session<2>::end() {}
template <>
void session<3>::end() {
  impl_->s.reset();
}
template class session<2>;
template class session<3>;

namespace {
template <std::size_t D>
std::vector<std::pair<std::size_t, vertex_id>> check(const boundary<D>& b) {
  std::vector<std::pair<std::size_t, vertex_id>> bad;
  const auto& p = b.points;
  hash_grid<D> grid(p[0], cell_size_for(p, 0));
  for (vertex_id v = 0; v < p.size(); ++v) grid.insert(v, p[v]);
  std::vector<vertex_id> ties;
  for (std::size_t f = 0; f < b.faces.size(); ++f) {
    const auto& F = b.faces[f];
    point<D> c{};
    double r = 0;
    if constexpr (D == 2)
      std::tie(c, r) = detail::diametral_bound(p[F[0]], p[F[1]]);
    else
      std::tie(c, r) = detail::equatorial_bound(p[F[0]], p[F[1]], p[F[2]]);
    point<D> lo, hi;
    for (std::size_t k = 0; k < D; ++k) lo[k] = c[k] - r, hi[k] = c[k] + r;
    ties.clear();
    vertex_id strict = no_vertex;
    grid.visit(lo, hi, [&](vertex_id y) {
      if (std::find(F.begin(), F.end(), y) != F.end()) return;
      if (squared_distance(c, p[y]) > r * r) return;  // double prefilter, padded
      int s;
      if constexpr (D == 2)
        s = geometry::in_diametral(p[F[0]], p[F[1]], p[y]);
      else
        s = geometry::in_equatorial(p[F[0]], p[F[1]], p[F[2]], p[y]);
      if (s > 0 && (strict == no_vertex || y < strict)) strict = y;
      if (s == 0) ties.push_back(y);
    });
    if (strict == no_vertex && !ties.empty()) {
      std::sort(ties.begin(), ties.end());
      bool ok;
      if constexpr (D == 2)
        ok = detail::edge_in_cocircular_dt(p, F[0], F[1], ties);
      else
        ok = detail::triangle_in_cospherical_dt(p, F[0], F[1], F[2], ties);
      if (!ok) strict = ties.front();
    }
    if (strict != no_vertex) bad.push_back({f, strict});
  }
  return bad;
}
}  // namespace

std::vector<std::pair<std::size_t, vertex_id>> encroached(const boundary<2>& b) { return check(b); }
std::vector<std::pair<std::size_t, vertex_id>> encroached(const boundary<3>& b) { return check(b); }

}  // namespace gsse::conformer
