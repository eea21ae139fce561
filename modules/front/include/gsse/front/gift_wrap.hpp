#pragma once
// Gift-wrapping advancing front (header template, instantiated for each kernel in kernels.hpp).
//
// The front starts as the boundary faces of one segment, oriented so that the segment lies on
// their positive side. Each step takes an open face f and finds the vertex x on its positive side
// whose circumball with f holds no other vertex on that side, under the project's perturbation
// (a unique choice); it creates the cell f+x and updates the front: a new face that matches an
// open face closes it, any other new face opens. When the boundary is a subcomplex of the global
// (perturbed) Delaunay triangulation, every cell is a Delaunay cell and the candidates may be all
// points of the domain: x never lies outside the segment. The loop ends when no face is open.
//
// Search: points live in a uniform grid. Phase 1 scans growing boxes around the face until some
// vertex on the positive side is found; phase 2 scans the grid cells overlapping the current
// best ball and switches to any vertex inside it. Within the pencil of balls through f, on the
// positive side, a better ball is contained in the worse one, so the scan may shrink as it goes
// and never misses a vertex. Decisions are exact; the double ball only bounds the scan region.
#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "gsse/front/face_table.hpp"
#include "gsse/geometry/point_grid.hpp"
#include "gsse/front/point_overlay.hpp"

namespace gsse::front {

using geometry::point_grid;  // the candidate index (gsse/geometry/point_grid.hpp)

class front_error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct wrap_stats {
  std::size_t cells = 0;
  std::size_t candidate_tests = 0;  // exact in-ball tests
  std::size_t side_tests = 0;       // exact orientation tests
  std::size_t visits = 0;           // grid points looked at
  std::size_t max_front = 0;        // largest number of open faces
  std::size_t reused = 0;           // apexes kept from a previous wrap (gift_wrapper::reuse)
  wrap_stats& operator+=(const wrap_stats& o) {
    cells += o.cells;
    candidate_tests += o.candidate_tests;
    side_tests += o.side_tests;
    visits += o.visits;
    max_front = std::max(max_front, o.max_front);
    reused += o.reused;
    return *this;
  }
};

/// K: the geometry kernel (kernels.hpp). Local: vertex ids are positions in the grid's coords()
/// (and the kernel's points are those coords): see wrap() in front_mesher.cpp.
template <class K, bool Local = false>
class gift_wrapper {
 public:
  static constexpr std::size_t D = K::dim;
  static constexpr std::size_t G = K::grid_dim;
  using face = typename K::face;
  using cell = std::array<vertex_id, D + 1>;
  using coord = std::array<double, G>;

  gift_wrapper(const K& k, const point_grid<G>& grid) : k_(k), grid_(grid), cur_(&grid) {
    for (std::size_t a = 0; a < G; ++a)
      diagonal_ += (grid_.upper()[a] - grid_.lower()[a]) * (grid_.upper()[a] - grid_.lower()[a]);
    diagonal_ = std::sqrt(diagonal_);
  }

  /// Rule-driven point creation (point_creation.hpp): after the apex x of face f is found,
  /// `create(f, x, cells)` may insert points (into the kernel's point array and `overlay`).
  /// It returns created (the apex of f is then searched again), fine (x is close enough) or
  /// declined (x is too far but no point could be placed): the face then goes to the back of the
  /// queue, up to `max_defer` times, so that points created for its neighbours can serve it.
  enum class creation { fine, created, declined };
  using creator = std::function<creation(const face&, vertex_id, const std::vector<cell>&)>;
  void enable_creation(const point_overlay<G>* overlay, creator create, unsigned max_defer = 2) {
    overlay_ = overlay;
    create_ = std::move(create);
    max_defer_ = max_defer;
  }

  /// Re-filling a cavity of a Delaunay mesh (strict order: perturbed balls) after points were
  /// added: the vertices below `first_added` are the mesh's old ones, those from it on the added
  /// points (the only others `added` holds). A cell of the new Delaunay mesh whose four (three)
  /// vertices are old has an empty ball among the old points, so it was a cell of the old mesh,
  /// which lies outside every cavity: every cell made has an added vertex, and a face of old
  /// vertices only takes its apex among the added points. Its search reads `added`, not the
  /// grid of all the cavity's points: the same apex, found among a few points.
  void old_faces_from(const point_grid<G>* added, vertex_id first_added) {
    static_assert(!Local, "old_faces_from: global ids");
    added_grid_ = added && added->size() > 0 && k_.strict() ? added : nullptr;
    first_added_ = first_added;
  }

  /// Re-wrapping a region after points were added (edge fronts with a strict order only; else
  /// ignored): `previous` are the cells of its last wrap, whose points are all still candidates,
  /// and `added` every candidate since. An open face that was a face of a previous cell f + x
  /// takes x again unless an added point beats x: x was beaten by no old point, and "beats" is
  /// a strict order, so x is still the one apex. Only the few added points near its ball are
  /// tested, instead of a search; the cells, and their order, are exactly those of a full wrap.
  void reuse(std::span<const cell> previous, std::span<const vertex_id> added) {
    static_assert(D == 2, "reuse: edge fronts (planar facets) only");
    if (!k_.strict() || previous.empty()) return;
    // open addressing, at most half full (a sort of the entries cost more than the wrap saved)
    std::size_t size = 16;
    while (size < 6 * previous.size()) size *= 2;
    reused_.assign(size, {empty_key, no_vertex});
    for (const cell& c : previous)  // faces into c (add_cell's convention), each with its apex
      for (std::size_t i = 0; i <= D; ++i) {
        const std::uint64_t k = key(c[(i + 1) % 3], c[(i + 2) % 3]);
        std::size_t h = slot(k);
        while (reused_[h].first != empty_key) h = (h + 1) & (reused_.size() - 1);
        reused_[h] = {k, c[i]};
      }
    std::vector<coord> at;
    at.reserve(added.size());
    for (vertex_id v : added) at.push_back(k_.grid_coord(v));
    added_.build(at, added);
  }

  /// Meshes the region bounded by `boundary` (faces oriented inward). `label` names the region in
  /// errors. `max_cells` turns a runaway (possible only if the boundary is not a subcomplex of the
  /// Delaunay triangulation) into an error; 0 means 64 cells per grid point plus the boundary.
  std::vector<cell> run(const std::vector<face>& boundary, const std::string& label, std::size_t max_cells = 0) {
    const bool auto_limit = max_cells == 0;
    std::vector<cell> cells;
    face_table<D> table(boundary.size());
    // FIFO order keeps the front (open faces) at the surface of the unmeshed region: small, so the
    // face table stays in cache. Depth-first order was measured to grow it to ~40% of the faces.
    std::deque<face> queue;
    for (const face& f : boundary) {
      auto* at = table.probe(f);
      if (!at->empty()) throw front_error(label + ": boundary face " + describe(f) + " appears twice");
      table.fill(at, f);
    }
    for (const face& f : boundary) queue.push_back(f);
    const auto limit = [&] {
      return auto_limit ? 64 * (grid_.size() + (overlay_ ? overlay_->size() : 0)) + boundary.size() : max_cells;
    };
    // the open face's entry `at` (from find) stays valid through apex(), which leaves the table alone
    auto build = [&](typename face_table<D>::entry* at, const face& f, vertex_id x) {
      add_cell(table, cells, at, f, x, label, [&](const face& r) { queue.push_back(r); });
      check_limit(cells, limit(), label);
    };
    if (!create_) {
      while (!queue.empty()) {
        const face f = queue.front();
        queue.pop_front();
        if (queue.size() > 8) {  // the probe and the search of a face soon popped then hit the cache
          table.prefetch(queue[8]);
          for (auto v : queue[8]) __builtin_prefetch(&k_.grid_coord_ref(v));
        }
        if (auto* at = table.find(f)) build(at, f, apex(f, label));  // else closed since it was pushed
      }
    } else {
      // Point creation works by generations (the faces open at one time): first every face of
      // the generation proposes its points, then the cells are built. A point proposed before its
      // neighbours' cells exist is tested against fewer circumspheres, so far fewer proposals
      // fail than when each face builds its cell at once.
      std::vector<face> gen;
      std::vector<vertex_id> first;
      std::vector<char> declined;
      while (!queue.empty()) {
        gen.assign(queue.begin(), queue.end());
        queue.clear();
        first.assign(gen.size(), no_vertex);
        declined.assign(gen.size(), 0);
        for (std::size_t i = 0; i < gen.size(); ++i) {
          if (!table.find(gen[i])) continue;
          first[i] = apex(gen[i], label);
          declined[i] = create_(gen[i], first[i], cells) == creation::declined;
        }
        for (std::size_t i = 0; i < gen.size(); ++i) {
          auto* at = table.find(gen[i]);
          if (!at) continue;
          const vertex_id x = apex(gen[i], label);
          // still the far apex for which no point could be placed: wait for the neighbours
          if (declined[i] && x == first[i] && defer(gen[i])) {
            queue.push_back(gen[i]);
            continue;
          }
          build(at, gen[i], x);
        }
      }
    }
    stats_.cells += cells.size();
    return cells;
  }

  /// run(), cache-blocked: a region whose bounding box holds more than `block` grid points is
  /// first split by a wall (run_wall) at the middle of the box's longest side, and each side is
  /// blocked in turn, depth first. The cells are run()'s (wall cells plus side cells are the
  /// region's cells), in the order wall, side 0, side 1. A piece's open faces and points then stay
  /// in the processor's cache, where one front over the whole region probes a face table of
  /// megabytes (1e6 points: 2e5 open faces) at a cache miss per probe.
  std::vector<cell> run_blocked(const std::vector<face>& boundary, const std::string& label, std::size_t max_cells,
                                std::size_t block) {
    std::vector<cell> cells;
    blocked(boundary, label, max_cells, block, 0, cells);
    return cells;
  }

  /// The wall of a split (DeWall): every cell of the region with vertices on both sides of the
  /// plane coordinate[axis] = x0 (a vertex with coordinate < x0 is on side 0, else on side 1),
  /// built by wrapping only faces that cross the plane. The open faces left, which lie entirely
  /// on one side, go to `sides[0]` and `sides[1]` (oriented as a boundary, unmeshed side
  /// positive): each side is then a region of its own that can be meshed independently.
  std::vector<cell> run_wall(const std::vector<face>& boundary, const std::string& label, std::size_t axis, double x0,
                             std::array<std::vector<face>, 2>& sides) {
    std::vector<cell> cells;
    face_table<D> table(boundary.size());
    auto side_of = [&](vertex_id v) { return k_.grid_coord(v)[axis] < x0 ? 0 : 1; };
    auto crosses = [&](const face& f) {
      int n = 0;
      for (auto v : f) n += side_of(v);
      return n != 0 && n != static_cast<int>(D);
    };
    std::deque<face> queue;
    std::vector<face> parked;  // open faces not crossing the plane, in the order they appeared
    for (const face& f : boundary) {
      auto* at = table.probe(f);
      if (!at->empty()) throw front_error(label + ": boundary face " + describe(f) + " appears twice");
      table.fill(at, f);
      (crosses(f) ? queue.push_back(f) : parked.push_back(f));
    }
    while (!queue.empty()) {
      const face f = queue.front();
      queue.pop_front();
      auto* at = table.find(f);
      if (!at) continue;
      const vertex_id x = apex(f, label);
      add_cell(table, cells, at, f, x, label,
               [&](const face& r) { (crosses(r) ? queue.push_back(r) : parked.push_back(r)); });
      check_limit(cells, 64 * grid_.size() + boundary.size(), label);
    }
    for (const face& f : parked)
      if (table.find(f)) sides[static_cast<std::size_t>(side_of(f[0]))].push_back(f);
    stats_.cells += cells.size();
    return cells;
  }

  const wrap_stats& stats() const { return stats_; }

 private:
  void blocked(const std::vector<face>& b, const std::string& label, std::size_t max_cells, std::size_t block, int depth,
               std::vector<cell>& out) {
    if (b.empty()) return;
    coord lo = k_.grid_coord(b[0][0]), hi = lo;
    for (const face& f : b)
      for (auto v : f) {
        const coord x = k_.grid_coord(v);
        for (std::size_t a = 0; a < G; ++a) lo[a] = std::min(lo[a], x[a]), hi[a] = std::max(hi[a], x[a]);
      }
    std::size_t axis = 0;
    for (std::size_t a = 1; a < G; ++a)
      if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
    const double x0 = 0.5 * (lo[axis] + hi[axis]);
    // depth 40: a wall halves the box, far below any grid cell by then
    const bool leaf = depth >= 40 || !(lo[axis] < x0 && x0 < hi[axis]) || grid_.count_box(lo, hi) <= block;
    std::array<std::vector<face>, 2> sides;
    const auto part = leaf ? run(b, label, max_cells) : run_wall(b, label, axis, x0, sides);
    out.insert(out.end(), part.begin(), part.end());
    for (const auto& side : sides) blocked(side, label, max_cells, block, depth + 1, out);
    if (max_cells != 0) check_limit(out, max_cells, label);
  }

  bool defer(const face& f) {
    auto key = f;
    std::sort(key.begin(), key.end());
    auto& n = deferred_[key];
    if (n >= max_defer_) return false;
    ++n;
    return true;
  }

  void check_limit(const std::vector<cell>& cells, std::size_t limit, const std::string& label) const {
    if (cells.size() > limit) throw front_error(label + ": more than " + std::to_string(limit) + " cells; giving up");
  }

  /// Builds the cell f + x: its other facets close matching open faces or open new ones (passed
  /// to `opened`), each oriented to face into the cell (reference_simplex convention).
  template <class Opened>
  void add_cell(face_table<D>& table, std::vector<cell>& cells, typename face_table<D>::entry* at, const face& f,
                vertex_id x, const std::string& label,
                Opened&& opened) {
    table.erase(at);
    cell c;
    for (std::size_t i = 0; i < D; ++i) c[i] = f[i];
    c[D] = x;
    for (std::size_t i = 0; i < D; ++i) {
      face g;
      std::size_t m = 0;
      for (std::size_t j = 0; j <= D; ++j)
        if (j != i) g[m++] = c[j];
      if ((D - i) % 2 == 1) std::swap(g[0], g[1]);
      // g faces into the cell: it closes the open face it equals; else its reverse opens,
      // unless that is open already (the cell lies on the meshed side of it)
      if (auto* h = table.probe(g); !h->empty()) {
        table.erase(h);
      } else {
        face r = g;
        std::swap(r[0], r[1]);
        auto* o = table.probe(r);
        if (!o->empty())
          throw front_error(label + ": cell " + describe_cell(c) + " overlaps the mesh across face " + describe(g));
        table.fill(o, r);
        opened(r);
      }
    }
    cells.push_back(c);
    stats_.max_front = std::max(stats_.max_front, table.size());
  }

  template <class F>
  bool visit_box(const coord& lo, const coord& hi, F&& f) const {
    if (!cur_->template visit_box<Local>(lo, hi, f)) return false;
    return !overlay_ || overlay_->visit_box(lo, hi, f);
  }
  /// The points of the grid cells meeting the ball (c, r) and the half-space dot(n, x) >= d.
  template <class F>
  bool visit_cap(const coord& c, double r, const coord& n, double d, F&& f) const {
    if (!cur_->template visit_ball<Local>(c, r, n, d, f)) return false;
    return !overlay_ || overlay_->visit_ball(c, r, n, d, f);
  }

  bool in_face(const face& f, vertex_id v) const {
    for (auto u : f)
      if (u == v) return true;
    return false;
  }

  /// A point seen by the cap search: id, grid coordinates and ranking hint.
  struct seen {
    vertex_id id;
    double t;
    coord q;
  };

  /// The half-space {x : dot(n, x) >= d} holding the positive side of the face of probe pr, its
  /// plane moved back by a margin that covers the double plane's error for points within
  /// distance `reach` of the face (no half-space, n = 0, if the plane is ill-conditioned).
  static void positive_side(const typename K::probe& pr, double reach, coord& n, double& d) {
    n = coord{};
    d = -1;
    if (pr.tilt < 1e-4) {
      n = pr.n;
      double m = 0;  // rounding of dot(n, x) for points of this magnitude (a thin layer far from 0)
      for (double x : pr.cc) m = std::max(m, std::abs(x));
      d = dot(n, pr.cc) - 4 * pr.tilt * (2 * reach + 2 * pr.l) - 1e-12 * (reach + pr.l) - 16 * std::numeric_limits<double>::epsilon() * (m + reach);
    }
  }

  /// True if every point of the ball (c1, r1) in the half-space {dot(n, x) >= d} lies in the ball
  /// (c2, r2): the farthest such point from c2 is the far end of the ball along c1 - c2 if that
  /// end lies in the half-space, else on the circle where the sphere meets the plane.
  static bool covered(const coord& c1, double r1, const coord& n, double d, const coord& c2, double r2) {
    const coord e = c1 - c2;
    const double le = std::sqrt(dot(e, e));
    double far = le + r1;
    const coord tip = le > 0 ? c1 + (r1 / le) * e : c1;
    if (dot(n, n) > 0 && dot(n, tip) < d) {
      const double s = d - dot(n, c1);  // signed offset of the plane from c1 along n
      if (s * s >= r1 * r1) return s <= 0;  // plane misses the ball: all in (s < 0) or all out
      const double rho = std::sqrt(r1 * r1 - s * s);
      const coord o = c1 + s * n;  // centre of the circle
      const coord w0 = c2 - o;
      const double a = dot(w0, n);
      const double w = std::sqrt(std::max(0.0, dot(w0, w0) - a * a));
      far = std::sqrt((rho + w) * (rho + w) + a * a);
    }
    return far * (1 + 1e-12) <= r2;
  }

  static constexpr std::uint64_t empty_key = ~std::uint64_t{0};
  static std::uint64_t key(vertex_id a, vertex_id b) { return (static_cast<std::uint64_t>(a) << 32) | b; }
  std::size_t slot(std::uint64_t k) const {
    return static_cast<std::size_t>((k * 0x9E3779B97F4A7C15ull) >> 20) & (reused_.size() - 1);
  }

  /// The apex of f in the previous wrap if no added point beats it (see reuse()), else no_vertex.
  vertex_id reusable(const face& f) {
    if constexpr (D == 2) {
      const std::uint64_t k = key(f[0], f[1]);
      std::size_t h = slot(k);
      while (reused_[h].first != k) {
        if (reused_[h].first == empty_key) return no_vertex;
        h = (h + 1) & (reused_.size() - 1);
      }
      const vertex_id x = reused_[h].second;
      coord c;
      double r = 0;
      if (!k_.ball(f, x, c, r)) return no_vertex;
      coord lo, hi;
      for (std::size_t a = 0; a < G; ++a) lo[a] = c[a] - r, hi[a] = c[a] + r;
      const double r2 = r * r;
      const bool kept = added_.visit_box(lo, hi, [&](vertex_id y, const coord& q) {
        double d2 = 0;
        for (std::size_t a = 0; a < G; ++a) d2 += (q[a] - c[a]) * (q[a] - c[a]);
        if (d2 > r2 || in_face(f, y)) return true;  // outside the padded ball: cannot beat x
        ++stats_.side_tests;
        return !(k_.side(f, y) > 0 && (++stats_.candidate_tests, k_.beats(f, x, y)));
      });
      if (kept) ++stats_.reused;
      return kept ? x : no_vertex;
    } else {
      return no_vertex;
    }
  }

  vertex_id apex(const face& f, const std::string& label) {
    if (!reused_.empty())
      if (const vertex_id x = reusable(f); x != no_vertex) return x;
    // a face of old vertices only: its apex is one of the added points (see old_faces_from)
    cur_ = &grid_;
    if (added_grid_) {
      bool old = true;
      for (auto v : f) old = old && v < first_added_;
      if (old) cur_ = added_grid_;
    }
    const auto pr = k_.prepare(f);
    // Caps: the balls through the face's circumcircle, by height h above its plane; a vertex's
    // hint t is the centre offset of its ball, so the vertices in the cap of height h are those
    // with t <= (h^2 - r^2) / 2h. Growing caps from a low one find the best-ranked vertex while
    // scanning little beyond its ball: a face whose empty ball is a thin lens (beside a large
    // boundary face) scans only the lens.
    vertex_id best = no_vertex;
    double best_t = std::numeric_limits<double>::infinity();
    coord ct{}, n{};
    double Rt = 0, d = 0;
    // beyond a cap 256 times as high as the grid is wide, what is left lies nearly in the face's
    // plane, outside its circumcircle: rank it all (a lower bound, 4x, sent the faces of thin
    // lenses near the hull of the benchmark cube to that scan: 20% of all visits at 1e6 points)
    const double top = 256 * diagonal_;
    // A strict kernel's apex does not depend on the caps scanned, so the next cap may be the
    // smallest one holding the best-ranked vertex a scan met beyond its cap (the points of the
    // rows it reads just outside the ball), when that is below the doubled one: where the empty
    // balls are large and the points lie near their spheres (the tube of a torus meshed from its
    // surface alone), the doubled cap held hundreds of points its apex's ball does not
    const bool peek = k_.strict();
    double next = 0;
    for (double h = std::min(2 * std::sqrt(pr.r2), 2 * cur_->mean_step());; h = next) {
      next = 2 * h;
      const double t = (h * h - pr.r2) / (2 * h);
      Rt = h - t;
      if (h > top || !std::isfinite(Rt)) {
        best = far_apex(f, pr, label);
        return settle(f, pr, best, K::estimate(pr, k_.grid_coord(best)));
      }
      for (std::size_t a = 0; a < G; ++a) ct[a] = pr.cc[a] + t * pr.n[a];
      positive_side(pr, Rt, n, d);
      // all balls of the pencil meet on the face's circumcircle: scan a little wider than the cap
      // so that the ball of a vertex inside it, padded and cut by the moved-back plane, fits in
      Rt = Rt * (1 + 1e-6) + 4 * (dot(n, pr.cc) - d);
      seen_.clear();
      const double R2 = Rt * Rt;
      std::size_t visits = 0;
      // the cap's terms by value: kept in registers through the scan (push_back may alias them)
      auto in_cap = [&, ct = ct, n = n, d = d, R2 = R2, f = f](vertex_id y, const coord& q) {
        ++visits;
        double d2 = 0;
        for (std::size_t a = 0; a < G; ++a) d2 += (q[a] - ct[a]) * (q[a] - ct[a]);
        if (d2 > R2 || dot(n, q) < d || in_face(f, y)) return true;
        seen_.push_back({y, K::estimate(pr, q), q});
        return true;
      };
      // a large cap's scan also keeps the points it meets beyond the ball, ranked below only if
      // the cap holds no apex (the first caps of a lattice's faces nearly always hold it; the
      // scan of a small cap keeps the plain loop)
      beyond_.clear();
      if (peek && h >= 4 * cur_->mean_step())
        visit_cap(ct, Rt, n, d, [&, ct = ct, n = n, d = d, R2 = R2](vertex_id y, const coord& q) {
          double d2 = 0;
          for (std::size_t a = 0; a < G; ++a) d2 += (q[a] - ct[a]) * (q[a] - ct[a]);
          if (d2 > R2) {
            if (dot(n, q) >= d) beyond_.push_back(&q);
            ++visits;
            return true;
          }
          return in_cap(y, q);
        });
      else
        visit_cap(ct, Rt, n, d, in_cap);
      stats_.visits += visits;
      // the best-ranked vertex is nearly always exactly positive; sort only when it is not
      auto by_rank = [](const seen& x, const seen& y) { return x.t < y.t || (x.t == y.t && x.id < y.id); };
      const auto first = std::min_element(seen_.begin(), seen_.end(), by_rank);
      if (first != seen_.end() && first->t <= t) {
        ++stats_.side_tests;
        if (k_.side(f, first->id) > 0) {
          best = first->id;
          best_t = first->t;
          break;
        }
        std::sort(seen_.begin(), seen_.end(), by_rank);
        for (const seen& s : seen_) {
          if (!(s.t <= t)) break;
          ++stats_.side_tests;
          if (k_.side(f, s.id) > 0) {
            best = s.id;
            best_t = s.t;
            break;
          }
        }
        if (best != no_vertex) break;
      }
      // no apex in this cap: the next is the one of height ho, which holds the points ranked up
      // to `beyond`, the best rank met beyond this cap among points clearly on the face's inner
      // side (one just across the plane ranks finitely but is never an apex), if that is at
      // least 0.1% above this cap (the caps still grow to `top`) and below the doubled one
      double beyond = std::numeric_limits<double>::infinity();
      const double clear = 1e-6 * pr.l;
      for (const coord* q : beyond_) {
        double above = 0;
        for (std::size_t a = 0; a < G; ++a) above += ((*q)[a] - pr.cc[a]) * pr.n[a];
        if (!(above > clear)) continue;
        if (const double u = K::estimate(pr, *q); u > t && u < beyond) beyond = u;
      }
      if (std::isfinite(beyond)) {
        const double ho = (beyond + std::sqrt(beyond * beyond + pr.r2)) * (1 + 1e-6);
        if (ho > h * (1 + 1e-3) && ho < next) next = ho;
      }
    }
    // The exact choice. If the (padded) ball of the best-ranked vertex, on the positive side, lies
    // in the cap just scanned, every vertex that can beat it exactly was seen: one exact pass over
    // those in its ball settles it (the perturbed order is strict, so a vertex that does not beat
    // the current best cannot beat a later one: their caps are nested).
    if (k_.strict()) {
      coord c;
      double r = 0;
      if (k_.ball(f, best, c, r) && covered(c, r, n, d, ct, Rt)) {
        const double r2 = r * r;
        for (const seen& s : seen_) {
          if (s.id == best) continue;
          double d2 = 0;
          for (std::size_t a = 0; a < G; ++a) d2 += (s.q[a] - c[a]) * (s.q[a] - c[a]);
          if (d2 > r2) continue;
          ++stats_.side_tests;
          if (k_.side(f, s.id) <= 0) continue;
          ++stats_.candidate_tests;
          if (k_.beats(f, best, s.id)) best = s.id;
        }
        return best;
      }
    }
    return settle(f, pr, best, best_t);
  }

  /// The apex when no cap finds one (the remaining vertices lie nearly in the face's plane, far
  /// from the face): the best-ranked vertex exactly on the positive side, or if none ranks finite
  /// any vertex exactly on the positive side.
  vertex_id far_apex(const face& f, const typename K::probe& pr, const std::string& label) {
    vertex_id best = no_vertex;
    double best_t = std::numeric_limits<double>::infinity();
    // the whole grid on the positive side
    coord c, n;
    double d = 0;
    for (std::size_t a = 0; a < G; ++a) c[a] = 0.5 * (cur_->lower()[a] + cur_->upper()[a]);
    const double r = diagonal_ + pr.l;
    positive_side(pr, r + std::sqrt(dot(c - pr.cc, c - pr.cc)), n, d);
    auto consider = [&](vertex_id y, const coord& q) {
      ++stats_.visits;
      const double t = K::estimate(pr, q);
      if ((best != no_vertex && !(t < best_t)) || in_face(f, y)) return true;
      ++stats_.side_tests;
      if (k_.side(f, y) <= 0) return true;
      best = y;
      best_t = t;
      return true;
    };
    visit_cap(c, r, n, d, consider);
    // the cap's half-space is a floating-point bound: before giving up, every vertex, exactly
    if (best == no_vertex) visit_box(cur_->lower(), cur_->upper(), consider);
    if (best == no_vertex) throw front_error(label + ": no vertex on the inner side of face " + describe(f));
    return best;
  }

  /// The exact choice by scanning balls: scan the current best ball (double, padded so it
  /// contains the exact one). While some vertex in it ranks clearly better by the double hint,
  /// jump to the best-ranked one (exactly on the positive side): the ball shrinks fast without
  /// exact in-ball tests. When none does, the vertices left in the padded ball (near ties and
  /// rounding cases) are decided exactly; an exact improvement restarts the loop. The hint only
  /// orders the search: the result is the vertex no other beats exactly.
  vertex_id settle(const face& f, const typename K::probe& pr, vertex_id best, double best_t) {
    std::vector<vertex_id> near;
    // Points of a slanted facet are coplanar only up to rounding; there "beats" need not be a
    // strict order, so a walk could cycle. It never returns to an earlier best: it terminates, and
    // the conformer's exact post-check judges the result.
    visited_.clear();
    visited_.push_back(best);
    auto fresh = [&](vertex_id y) { return std::find(visited_.begin(), visited_.end(), y) == visited_.end(); };
    for (;;) {
      coord c, n;
      double r = 0, d = 0;
      const bool reliable = k_.ball(f, best, c, r);
      const double r2 = r * r;
      const double margin = 1e-9 * (std::abs(best_t) + pr.l);
      vertex_id jump = no_vertex;
      double jump_t = best_t - margin;
      near.clear();
      auto consider = [&](vertex_id y, const coord& q) {
        ++stats_.visits;
        if (reliable) {
          double d2 = 0;
          for (std::size_t a = 0; a < G; ++a) d2 += (q[a] - c[a]) * (q[a] - c[a]);
          if (d2 > r2) return true;
        }
        if (y == best || in_face(f, y)) return true;
        const double t = K::estimate(pr, q);
        if (t < jump_t) {
          ++stats_.side_tests;
          if (k_.side(f, y) > 0) {
            if (jump != no_vertex) near.push_back(jump);
            jump = y;
            jump_t = t;
            return true;
          }
        }
        near.push_back(y);
        return true;
      };
      positive_side(pr, r, n, d);
      if (reliable)
        visit_cap(c, r, n, d, consider);
      else
        visit_box(cur_->lower(), cur_->upper(), consider);
      // every move is an exact improvement, so the walk cannot cycle
      if (jump != no_vertex) {
        ++stats_.candidate_tests;
        if (fresh(jump) && k_.beats(f, best, jump)) {
          best = jump;
          best_t = jump_t;
          visited_.push_back(best);
          continue;
        }
        near.push_back(jump);
      }
      bool changed = false;
      for (vertex_id y : near) {
        ++stats_.side_tests;
        if (k_.side(f, y) <= 0) continue;
        ++stats_.candidate_tests;
        if (fresh(y) && k_.beats(f, best, y)) {
          best = y;
          visited_.push_back(best);
          changed = true;
        }
      }
      // With a strict order (perturbed balls in 3D and 2D) one exact pass over the ball is final:
      // the new best's cap lies inside the old one, and y not beating the old best cannot beat
      // the new one. Slanted facets (rounded coplanarity) rescan.
      if (!changed || k_.strict()) break;
      best_t = K::estimate(pr, k_.grid_coord(best));
    }
    return best;
  }

  vertex_id global(vertex_id v) const { return Local ? grid_.id_at(v) : v; }
  std::string describe(const face& f) const {
    std::string s = "(";
    for (std::size_t i = 0; i < D; ++i) {
      if (i) s += ", ";
      s += std::to_string(global(f[i]) + 1);
      s += " at [";
      const auto c = k_.grid_coord(f[i]);
      for (std::size_t a = 0; a < G; ++a) s += (a ? " " : "") + std::to_string(c[a]);
      s += "]";
    }
    return s + ")";
  }
  std::string describe_cell(const cell& c) const {
    std::string s = "(";
    for (std::size_t i = 0; i <= D; ++i) s += (i ? ", " : "") + std::to_string(global(c[i]) + 1);
    return s + ")";
  }

  const K& k_;
  const point_grid<G>& grid_;
  const point_grid<G>* cur_;                  // the grid apex() searches: grid_, or added_grid_
  const point_grid<G>* added_grid_ = nullptr;  // old_faces_from()
  vertex_id first_added_ = 0;
  double diagonal_ = 0;  // of the grid's box
  const point_overlay<G>* overlay_ = nullptr;
  creator create_;
  unsigned max_defer_ = 0;
  std::map<face, unsigned> deferred_;
  wrap_stats stats_;
  std::vector<vertex_id> visited_;
  std::vector<seen> seen_;
  std::vector<const coord*> beyond_;  // apex(): the points a cap's scan met beyond its ball
  std::vector<std::pair<std::uint64_t, vertex_id>> reused_;  // (face key, apex) of the previous wrap, hashed
  point_grid<G> added_;                                      // points added since it
};

}  // namespace gsse::front
