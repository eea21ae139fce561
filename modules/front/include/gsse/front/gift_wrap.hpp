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
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "gsse/front/face_table.hpp"
#include "gsse/front/point_grid.hpp"
#include "gsse/front/point_overlay.hpp"

namespace gsse::front {

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
  wrap_stats& operator+=(const wrap_stats& o) {
    cells += o.cells;
    candidate_tests += o.candidate_tests;
    side_tests += o.side_tests;
    visits += o.visits;
    max_front = std::max(max_front, o.max_front);
    return *this;
  }
};

template <class K>
class gift_wrapper {
 public:
  static constexpr std::size_t D = K::dim;
  static constexpr std::size_t G = K::grid_dim;
  using face = typename K::face;
  using cell = std::array<vertex_id, D + 1>;
  using coord = std::array<double, G>;

  gift_wrapper(const K& k, const point_grid<G>& grid) : k_(k), grid_(grid) {}

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

  /// Meshes the region bounded by `boundary` (faces oriented inward). `label` names the region in
  /// errors. `max_cells` turns a runaway (possible only if the boundary is not a subcomplex of the
  /// Delaunay triangulation) into an error; 0 means 64 cells per grid point plus the boundary.
  std::vector<cell> run(const std::vector<face>& boundary, const std::string& label, std::size_t max_cells = 0) {
    const bool auto_limit = max_cells == 0;
    std::vector<cell> cells;
    face_table<D> table(boundary.size() * 8);
    // FIFO order keeps the front (open faces) at the surface of the unmeshed region: small, so the
    // face table stays in cache. Depth-first order was measured to grow it to ~40% of the faces.
    std::deque<face> queue;
    for (const face& f : boundary) {
      if (table.find(f)) throw front_error(label + ": boundary face " + describe(f) + " appears twice");
      table.insert(f);
    }
    for (const face& f : boundary) queue.push_back(f);
    auto build = [&](const face& f, vertex_id x) {
      table.erase(table.find(f));
      cell c;
      for (std::size_t i = 0; i < D; ++i) c[i] = f[i];
      c[D] = x;
      // the other facets of c, each oriented to face into c (reference_simplex convention)
      for (std::size_t i = 0; i < D; ++i) {
        face g;
        std::size_t m = 0;
        for (std::size_t j = 0; j <= D; ++j)
          if (j != i) g[m++] = c[j];
        if ((D - i) % 2 == 1) std::swap(g[0], g[1]);
        if (auto* h = table.find(g)) {
          if (!same_orientation(h->oriented, g))
            throw front_error(label + ": cell " + describe_cell(c) + " overlaps the mesh across face " + describe(g));
          table.erase(h);
        } else {
          face r = g;
          std::swap(r[0], r[1]);
          table.insert(r);
          queue.push_back(r);
        }
      }
      cells.push_back(c);
      stats_.max_front = std::max(stats_.max_front, table.size());
      if (auto_limit) max_cells = 64 * (grid_.size() + (overlay_ ? overlay_->size() : 0)) + boundary.size();
      if (cells.size() > max_cells)
        throw front_error(label + ": more than " + std::to_string(max_cells) + " cells; giving up");
    };
    if (!create_) {
      while (!queue.empty()) {
        const face f = queue.front();
        queue.pop_front();
        if (table.find(f)) build(f, apex(f, label));  // else closed since it was pushed
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
          if (!table.find(gen[i])) continue;
          const vertex_id x = apex(gen[i], label);
          // still the far apex for which no point could be placed: wait for the neighbours
          if (declined[i] && x == first[i] && defer(gen[i])) {
            queue.push_back(gen[i]);
            continue;
          }
          build(gen[i], x);
        }
      }
    }
    stats_.cells += cells.size();
    return cells;
  }

  const wrap_stats& stats() const { return stats_; }

 private:
  bool defer(const face& f) {
    auto key = f;
    std::sort(key.begin(), key.end());
    auto& n = deferred_[key];
    if (n >= max_defer_) return false;
    ++n;
    return true;
  }

  template <class F>
  bool visit_box(const coord& lo, const coord& hi, F&& f) const {
    if (!grid_.visit_box(lo, hi, f)) return false;
    return !overlay_ || overlay_->visit_box(lo, hi, f);
  }

  bool in_face(const face& f, vertex_id v) const {
    for (auto u : f)
      if (u == v) return true;
    return false;
  }

  vertex_id apex(const face& f, const std::string& label) {
    vertex_id best = no_vertex;
    const auto pr = k_.prepare(f);
    coord lo, hi;
    k_.seed(pr, lo, hi);
    // phase 1: the best-ranked vertex (double hint only) of a growing box that is exactly on the
    // positive side; any such vertex will do, phase 2 makes the exact choice
    double best_t = std::numeric_limits<double>::infinity();
    for (;;) {
      visit_box(lo, hi, [&](vertex_id y, const coord& q) {
        const double t = K::estimate(pr, q);
        if (!(t < best_t) || in_face(f, y)) return true;
        ++stats_.side_tests;
        if (k_.side(f, y) <= 0) return true;
        best = y;
        best_t = t;
        return true;
      });
      if (best != no_vertex) break;
      bool covers = true;
      for (std::size_t a = 0; a < G; ++a) covers &= lo[a] <= grid_.lower()[a] && hi[a] >= grid_.upper()[a];
      if (covers) {
        // no vertex ranks finite (all nearly in the face's plane): take any exactly positive one
        visit_box(lo, hi, [&](vertex_id y, const coord&) {
          if (in_face(f, y)) return true;
          ++stats_.side_tests;
          if (k_.side(f, y) <= 0) return true;
          best = y;
          return false;
        });
        if (best == no_vertex) throw front_error(label + ": no vertex on the inner side of face " + describe(f));
        break;
      }
      for (std::size_t a = 0; a < G; ++a) {
        const double w = 0.5 * (hi[a] - lo[a]);  // double the box width
        lo[a] -= w;
        hi[a] += w;
      }
    }
    // phase 2: scan the current best ball (double, padded so it contains the exact one).
    // While some vertex in it ranks clearly better by the double hint, jump to the best-ranked
    // one (exactly on the positive side): the ball shrinks fast without exact in-ball tests.
    // When none does, the vertices left in the padded ball (near ties and rounding cases) are
    // decided exactly; an exact improvement restarts the loop. The hint only orders the search:
    // the result is the vertex no other beats exactly.
    best_t = K::estimate(pr, k_.grid_coord(best));
    std::vector<vertex_id> near;
    // Points of a slanted facet are coplanar only up to rounding; there "beats" need not be a
    // strict order, so a walk could cycle. It never returns to an earlier best: it terminates, and
    // the conformer's exact post-check judges the result.
    visited_.clear();
    visited_.push_back(best);
    auto fresh = [&](vertex_id y) { return std::find(visited_.begin(), visited_.end(), y) == visited_.end(); };
    for (;;) {
      coord c;
      double r = 0;
      const bool reliable = k_.ball(f, best, c, r);
      if (reliable) {
        for (std::size_t a = 0; a < G; ++a) {
          lo[a] = c[a] - r;
          hi[a] = c[a] + r;
        }
      } else {
        lo = grid_.lower();
        hi = grid_.upper();
      }
      const double r2 = r * r;
      const double margin = 1e-9 * (std::abs(best_t) + pr.l);
      vertex_id jump = no_vertex;
      double jump_t = best_t - margin;
      near.clear();
      visit_box(lo, hi, [&](vertex_id y, const coord& q) {
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
      });
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
      if (!changed) break;
      best_t = K::estimate(pr, k_.grid_coord(best));
    }
    return best;
  }

  std::string describe(const face& f) const {
    std::string s = "(";
    for (std::size_t i = 0; i < D; ++i) {
      if (i) s += ", ";
      s += std::to_string(f[i] + 1);
      s += " at [";
      const auto c = k_.grid_coord(f[i]);
      for (std::size_t a = 0; a < G; ++a) s += (a ? " " : "") + std::to_string(c[a]);
      s += "]";
    }
    return s + ")";
  }
  std::string describe_cell(const cell& c) const {
    std::string s = "(";
    for (std::size_t i = 0; i <= D; ++i) s += (i ? ", " : "") + std::to_string(c[i] + 1);
    return s + ")";
  }

  const K& k_;
  const point_grid<G>& grid_;
  const point_overlay<G>* overlay_ = nullptr;
  creator create_;
  unsigned max_defer_ = 0;
  std::map<face, unsigned> deferred_;
  wrap_stats stats_;
  std::vector<vertex_id> visited_;
};

}  // namespace gsse::front
