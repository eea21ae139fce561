// Bowyer-Watson insertion into one cavity of a round (3D): the dead cells of a segment that touch
// one another, their neighbours across shared faces, the faces where they meet the rest (walls),
// and the round's new points inserted one at a time. Internal to modules/refinement.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "gsse/geometry/predicates.hpp"
#include "gsse/refinement/refinement.hpp"

namespace gsse::refinement::insertion {

using cell = std::array<vertex_id, 4>;
using face = std::array<vertex_id, 3>;

/// Face i of c (the vertex c[i] left out), ordered to face into c: the front mesher's convention
/// (a positive cell is (f, x) for f facing into it and x its fourth vertex).
inline face face_of(const cell& c, int i) {
  face f;
  int m = 0;
  for (int j = 0; j < 4; ++j)
    if (j != i) f[static_cast<std::size_t>(m++)] = c[static_cast<std::size_t>(j)];
  if ((3 - i) % 2 == 1) std::swap(f[0], f[1]);
  return f;
}

/// What a wall is across a face: a neighbour (>= 0), a wall that stays (fixed), or a boundary
/// face a new point on its source may remove (droppable(s)).
constexpr std::int32_t fixed = -1;
constexpr std::int32_t droppable(std::uint32_t source) { return -2 - static_cast<std::int32_t>(source); }
constexpr bool is_droppable(std::int32_t n) { return n <= -2; }
constexpr std::uint32_t source_of(std::int32_t n) { return static_cast<std::uint32_t>(-2 - n); }

/// One cavity, filled by inserting points one at a time (Bowyer and Watson). Every cell is
/// positive; neighbour i lies across face i (CGAL's convention). The region it fills is bounded by
/// its walls: faces of surviving cells and boundary faces. A new point on a facet (the boundary
/// points of a round) removes the droppable walls of its sources that its conflict region meets
/// and walls the star off with faces through it: the facet's new faces. The cells made are the
/// region's constrained Delaunay triangulation (the perturbed in-sphere test of the front mesher),
/// which is what the front mesher makes from the same walls; the caller checks the walls left
/// against the ones the conformer made.
class cavity {
 public:
  cavity(std::span<const point3> p, std::vector<cell> cells, std::vector<std::array<std::int32_t, 4>> next)
      : p_(p), c_(std::move(cells)), nb_(std::move(next)), mark_(c_.size(), 0), spare_(c_.size(), 0) {}

  /// Inserts q. `hints`: places of cells whose balls held q when the cavity was made (the search
  /// starts there); `free`: q is a free point, which belongs to this cavity only if a cell holds
  /// it (else `outside` is set); `on_source(s)`: q lies on source s (a facet) and may remove its
  /// droppable walls. Returns false, changing no cell, if q cannot be inserted here: no cell
  /// holds it in its ball, a face of its conflict region does not see it strictly, or a face
  /// through it meets neither another new cell nor a removed wall.
  template <class OnSource>
  bool insert(vertex_id q, std::span<const std::uint32_t> hints, bool free, OnSource&& on_source, bool shrink = false) {
    outside = false;
    std::uint32_t seed = none;
    if (free) {
      // a free point: the cell holding it, by walks from the hints (cells whose balls held it
      // before the round). Every walk meeting a wall with q beyond: q lies in another segment
      std::uint32_t end = none;
      for (std::size_t k = 0; k < hints.size() && k < 4 && seed == none; ++k) {
        std::uint32_t from = hints[k];
        if (from >= c_.size() || spare_[from]) from = last_;
        const std::uint32_t at = locate(q, from);
        if (at != none && walk_inside_) seed = at;
        if (end == none) end = at;
      }
      // the walks met walls (a cavity need not be convex): breadth first from where the first
      // ended, the nearest cells, for one holding q
      if (seed == none && end != none) seed = nearest(end, [&](std::uint32_t a) { return holds(a, q); });
      if (seed == none) return outside = true, false;
      if (!in_ball(seed, q)) return false;
    }
    // a point on a facet: the first hint whose cell (the one there now) holds q in its ball, else
    // a walk from the first
    for (std::size_t k = 0; k < hints.size() && seed == none; ++k) {
      const auto h = hints[k];
      if (h < c_.size() && !spare_[h] && in_ball(h, q)) seed = h;
    }
    if (seed == none) {
      std::uint32_t from = hints.empty() ? last_ : hints[0];
      if (from >= c_.size() || spare_[from]) from = last_;
      seed = locate(q, from);
      if (seed != none && !in_ball(seed, q)) {
        // the walk met a wall (the cavity need not be convex, a point on a slanted facet may lie
        // a rounding beyond it): the nearest cell, breadth first, whose ball holds q
        const std::uint32_t start = seed;
        seed = nearest(start, [&](std::uint32_t a) { return a != start && in_ball(a, q); });
      }
      if (seed == none) return false;
    }
    if (stamp_ > 0xFFFFFFF0u) std::fill(mark_.begin(), mark_.end(), 0), stamp_ = 0;
    // marks: in conflict, or tested and not
    const std::uint32_t in = ++stamp_, out = ++stamp_;
    dead_.clear();
    rim_.clear();
    dropped_.clear();
    dead_.push_back(seed);
    mark_[seed] = in;
    for (std::size_t k = 0; k < dead_.size(); ++k) {
      const std::uint32_t a = dead_[k];
      for (int i = 0; i < 4; ++i) {
        const std::int32_t n = nb_[a][static_cast<std::size_t>(i)];
        if (n >= 0) {
          const auto b = static_cast<std::uint32_t>(n);
          if (mark_[b] == in) continue;
          if (mark_[b] != out) {
            if (in_ball(b, q)) {
              mark_[b] = in;
              dead_.push_back(b);
              continue;
            }
            mark_[b] = out;
          }
        }
        rim_.push_back({a, i});
      }
    }
    if (shrink) {
      // the conflict region cut back to what q sees (as TetGen's cavity is): a cell with a rim
      // face q does not see strictly, other than a droppable wall of q's, leaves it, until none
      // has; the seed must stay. What stays in conflict outside it is checked by the caller
      // (locally_delaunay) once every point is in
      for (bool cut = true; cut;) {
        cut = false;
        for (const auto& [a, i] : rim_) {
          if (mark_[a] != in) continue;
          const std::int32_t n = nb_[a][static_cast<std::size_t>(i)];
          if (is_droppable(n) && on_source(source_of(n))) continue;
          const face f = face_of(c_[a], i);
          if (geometry::orient3d(p_[f[0]], p_[f[1]], p_[f[2]], p_[q]) > 0) continue;
          if (a == seed) return false;
          mark_[a] = out;
          cut = true;
        }
        if (!cut) break;
        std::erase_if(dead_, [&](std::uint32_t a) { return mark_[a] != in; });
        rim_.clear();
        for (const std::uint32_t a : dead_)
          for (int i = 0; i < 4; ++i) {
            const std::int32_t n = nb_[a][static_cast<std::size_t>(i)];
            if (n >= 0 && mark_[static_cast<std::size_t>(n)] == in) continue;
            rim_.push_back({a, i});
          }
      }
    }
    // the star: every rim face q sees strictly, or a droppable wall of one of q's sources
    made_.clear();
    for (const auto& [a, i] : rim_) {
      const std::int32_t n = nb_[a][static_cast<std::size_t>(i)];
      const face f = face_of(c_[a], i);
      if (is_droppable(n) && on_source(source_of(n))) {
        dropped_.push_back({f, source_of(n)});
        continue;
      }
      if (geometry::orient3d(p_[f[0]], p_[f[1]], p_[f[2]], p_[q]) <= 0) return false;
      const std::int32_t back = n >= 0 ? back_of(static_cast<std::uint32_t>(n), a) : -1;  // the place of a in its neighbour's list
      made_.push_back({{f[0], f[1], f[2], q}, n, back, {}});
    }
    if (made_.empty()) return false;
    // the faces through q: new cells meet across them, or (opposite a dropped wall) they become
    // walls of the dropped wall's source. Keyed by the edge they hold
    edges_.clear();
    for (std::uint32_t t = 0; t < made_.size(); ++t)
      for (int j = 0; j < 3; ++j) {
        const cell& c = made_[t].c;
        vertex_id u = c[static_cast<std::size_t>((j + 1) % 3)], v = c[static_cast<std::size_t>((j + 2) % 3)];
        if (u > v) std::swap(u, v);
        edges_.push_back({(static_cast<std::uint64_t>(u) << 32) | v, t * 4 + static_cast<std::uint32_t>(j)});
      }
    std::sort(edges_.begin(), edges_.end());
    for (std::size_t k = 0; k < edges_.size();) {
      std::size_t e = k;
      while (e < edges_.size() && edges_[e].first == edges_[k].first) ++e;
      const std::uint32_t t0 = edges_[k].second / 4, j0 = edges_[k].second % 4;
      if (e - k == 2) {
        const std::uint32_t t1 = edges_[k + 1].second / 4, j1 = edges_[k + 1].second % 4;
        made_[t0].link[j0] = static_cast<std::int32_t>(t1);
        made_[t1].link[j1] = static_cast<std::int32_t>(t0);
      } else if (e - k == 1) {
        // opposite a dropped wall holding this edge: a wall of that wall's source
        const std::uint64_t key = edges_[k].first;
        bool found = false;
        for (std::size_t d = 0; d < dropped_.size() && !found; ++d)
          for (int m = 0; m < 3 && !found; ++m) {
            const face& f = dropped_[d].first;
            vertex_id u = f[static_cast<std::size_t>(m)], v = f[static_cast<std::size_t>((m + 1) % 3)];
            if (u > v) std::swap(u, v);
            if (((static_cast<std::uint64_t>(u) << 32) | v) == key) found = true, made_[t0].link[j0] = droppable(dropped_[d].second);
          }
        if (!found) return false;
      } else {
        return false;
      }
      k = e;
    }
    // committed: the cells' places (the dead ones', spare ones, then new ones)
    take_places(dead_, made_.size());
    for (std::size_t t = 0; t < made_.size(); ++t) {
      const std::uint32_t at = places_[t];
      c_[at] = made_[t].c;
      for (int j = 0; j < 3; ++j) {
        const std::int32_t l = made_[t].link[static_cast<std::size_t>(j)];
        nb_[at][static_cast<std::size_t>(j)] = l >= 0 ? static_cast<std::int32_t>(places_[static_cast<std::size_t>(l)]) : l;
      }
      nb_[at][3] = made_[t].outside;
      mark_[at] = 0;
      if (made_[t].outside >= 0)
        nb_[static_cast<std::size_t>(made_[t].outside)][static_cast<std::size_t>(made_[t].back)] = static_cast<std::int32_t>(at);
    }
    last_ = places_[0];
    return true;
  }

  /// Is q inside the closed cell a (every face sees it or holds it)?
  bool holds(std::uint32_t a, vertex_id q) const {
    for (int i = 0; i < 4; ++i) {
      const face f = face_of(c_[a], i);
      if (geometry::orient3d(p_[f[0]], p_[f[1]], p_[f[2]], p_[q]) < 0) return false;
    }
    return true;
  }

  /// The cells, each place in use once (places freed by an insertion that made fewer cells
  /// than it removed are left out), in place order.
  std::vector<cell> cells() const {
    std::vector<cell> out;
    out.reserve(c_.size());
    for (std::size_t a = 0; a < c_.size(); ++a)
      if (!spare_[a]) out.push_back(c_[a]);
    return out;
  }
  /// Whether every cell is locally Delaunay: across each face between two cells, the far cell's
  /// vertex lies outside the near one's ball (perturbed). With its walls, the region's constrained
  /// Delaunay triangulation then; what insert(..., shrink) left needs this checked.
  bool locally_delaunay() const {
    for (std::size_t a = 0; a < c_.size(); ++a) {
      if (spare_[a]) continue;
      for (int i = 0; i < 4; ++i) {
        const std::int32_t n = nb_[a][static_cast<std::size_t>(i)];
        if (n < 0 || static_cast<std::size_t>(n) < a) continue;  // each pair once
        if (const int j = back_of(static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(a));
            j >= 0 && in_ball(static_cast<std::uint32_t>(a), c_[static_cast<std::size_t>(n)][static_cast<std::size_t>(j)]))
          return false;
      }
    }
    return true;
  }
  /// Lawson's flips across the faces between cells that are not locally Delaunay (perturbed, as
  /// in_ball), the walls untouched: a 2-3 flip where the two cells' union is convex across the
  /// face, a 3-2 flip where one edge of it is reflex and has exactly three cells about it. Until
  /// no such face is left, or none left can be flipped either way (four points coplanar, or more
  /// cells about the reflex edge). What insert(..., shrink) left can need them: a cell a point cut
  /// back did not take may hold a later point in its ball. Returns locally_delaunay().
  bool flip_to_delaunay() {
    std::vector<std::pair<std::uint32_t, int>> todo;
    for (std::uint32_t a = 0; a < c_.size(); ++a)
      if (!spare_[a])
        for (int i = 0; i < 4; ++i)
          if (nb_[a][static_cast<std::size_t>(i)] > static_cast<std::int32_t>(a)) todo.push_back({a, i});
    // each flip lowers the lifted triangulation (the perturbed in-sphere is one lifting), so the
    // flips end; the budget only bounds a bug
    for (std::size_t budget = 64 * c_.size() + 1024; !todo.empty() && budget > 0; --budget) {
      const auto [a, i] = todo.back();
      todo.pop_back();
      if (a >= c_.size() || spare_[a]) continue;
      const std::int32_t n = nb_[a][static_cast<std::size_t>(i)];
      if (n < 0) continue;
      const auto b = static_cast<std::uint32_t>(n);
      const int j = back_of(b, a);
      if (j < 0) continue;
      const vertex_id u = c_[a][static_cast<std::size_t>(i)], v = c_[b][static_cast<std::size_t>(j)];
      if (!in_ball(a, v)) continue;
      const face f = face_of(c_[a], i);  // (f, u) positive
      std::array<int, 3> o{};
      for (int k = 0; k < 3; ++k)
        o[static_cast<std::size_t>(k)] = geometry::orient3d(p_[f[static_cast<std::size_t>(k)]], p_[f[static_cast<std::size_t>((k + 1) % 3)]], p_[v], p_[u]);
      std::array<cell, 3> made{};
      std::array<std::uint32_t, 3> olds{a, b, 0};
      std::size_t old_count = 2, made_count = 0;
      if (o[0] > 0 && o[1] > 0 && o[2] > 0) {  // 2-3: the edge uv through the face
        for (std::size_t k = 0; k < 3; ++k) made[k] = {f[k], f[(k + 1) % 3], v, u};
        made_count = 3;
      } else {
        int reflex = -1, negative = 0;
        for (int k = 0; k < 3; ++k)
          if (o[static_cast<std::size_t>(k)] < 0) reflex = k, ++negative;
        if (negative != 1 || std::find(o.begin(), o.end(), 0) != o.end()) continue;
        const auto k = static_cast<std::size_t>(reflex);
        const vertex_id e0 = f[k], e1 = f[(k + 1) % 3], w = f[(k + 2) % 3];
        // the third cell about the edge e0 e1: a's neighbour opposite w, holding v
        const int wi = index_of(c_[a], w);
        const std::int32_t t = nb_[a][static_cast<std::size_t>(wi)];
        if (t < 0 || index_of(c_[static_cast<std::size_t>(t)], v) < 0) continue;
        const cell c0{e0, v, w, u}, c1{v, e1, w, u};  // (e0 e1 w u) with e1, then e0, replaced by v
        if (geometry::orient3d(p_[c0[0]], p_[c0[1]], p_[c0[2]], p_[c0[3]]) <= 0 ||
            geometry::orient3d(p_[c1[0]], p_[c1[1]], p_[c1[2]], p_[c1[3]]) <= 0)
          continue;
        olds[2] = static_cast<std::uint32_t>(t), old_count = 3;
        made[0] = c0, made[1] = c1, made_count = 2;
      }
      if (!replace(std::span<const std::uint32_t>(olds.data(), old_count), std::span<const cell>(made.data(), made_count))) continue;
      for (const std::uint32_t at : places_)
        for (int m = 0; m < 4; ++m)
          if (nb_[at][static_cast<std::size_t>(m)] >= 0) todo.push_back({at, m});
    }
    return locally_delaunay();
  }
  /// Every face across which a cell has a droppable wall, facing into its cell, in place order.
  std::vector<face> droppable_walls() const {
    std::vector<face> out;
    for (std::size_t a = 0; a < c_.size(); ++a)
      if (!spare_[a])
        for (int i = 0; i < 4; ++i)
          if (is_droppable(nb_[a][static_cast<std::size_t>(i)])) out.push_back(face_of(c_[a], i));
    return out;
  }
  bool outside = false;  // the last insert of a free point failed because no cell holds it

 private:
  static constexpr std::uint32_t none = ~std::uint32_t{0};
  struct star_cell {
    cell c;
    std::int32_t outside, back;
    std::array<std::int32_t, 3> link;  // across faces 0-2: another star cell (>= 0) or a wall
  };

  // places_: `count` places for new cells, those of `reuse` first, then spare ones, then new
  // ones; the places of `reuse` left over become spare
  void take_places(std::span<const std::uint32_t> reuse, std::size_t count) {
    places_.clear();
    for (std::size_t t = 0; t < count; ++t) {
      std::uint32_t at;
      if (t < reuse.size()) {
        at = reuse[t];
      } else if (!free_.empty()) {
        at = free_.back();
        free_.pop_back();
        spare_[at] = 0;
      } else {
        at = static_cast<std::uint32_t>(c_.size());
        c_.push_back({});
        nb_.push_back({});
        mark_.push_back(0);
        spare_.push_back(0);
      }
      places_.push_back(at);
    }
    for (std::size_t t = count; t < reuse.size(); ++t) free_.push_back(reuse[t]), spare_[reuse[t]] = 1;
  }
  static int index_of(const cell& c, vertex_id v) {
    for (int k = 0; k < 4; ++k)
      if (c[static_cast<std::size_t>(k)] == v) return k;
    return -1;
  }
  // the place of a in b's neighbours, or -1
  int back_of(std::uint32_t b, std::uint32_t a) const {
    for (int k = 0; k < 4; ++k)
      if (nb_[b][static_cast<std::size_t>(k)] == static_cast<std::int32_t>(a)) return k;
    return -1;
  }
  // the cells at `olds` (neighbours of one another) replaced by `made`, which fill the same
  // polyhedron: each face of a made cell meets another made cell or an outer face of the olds
  // (a neighbour or a wall, kept). Nothing changes and false comes back if one does not. The made
  // cells' places in places_
  bool replace(std::span<const std::uint32_t> olds, std::span<const cell> made) {
    auto key = [](face g) {
      std::sort(g.begin(), g.end());
      return g;
    };
    struct outer {
      face k;
      std::int32_t n;
      int back;  // n's place of the old cell, when n >= 0
    };
    std::vector<outer> outs;
    for (const std::uint32_t a : olds)
      for (int i = 0; i < 4; ++i) {
        const std::int32_t n = nb_[a][static_cast<std::size_t>(i)];
        if (n >= 0 && std::find(olds.begin(), olds.end(), static_cast<std::uint32_t>(n)) != olds.end()) continue;
        outs.push_back({key(face_of(c_[a], i)), n, n >= 0 ? back_of(static_cast<std::uint32_t>(n), a) : -1});
      }
    // per made cell and face: another made cell (t * 4 + j) or an outer face (-1 - index)
    std::vector<std::array<std::int64_t, 4>> link(made.size());
    std::vector<char> used(outs.size(), 0);
    for (std::size_t t = 0; t < made.size(); ++t)
      for (int i = 0; i < 4; ++i) {
        const face g = key(face_of(made[t], i));
        std::int64_t to = std::numeric_limits<std::int64_t>::min();
        for (std::size_t s = 0; s < made.size() && to == std::numeric_limits<std::int64_t>::min(); ++s)
          for (int m = 0; m < 4 && s != t; ++m)
            if (key(face_of(made[s], m)) == g) to = static_cast<std::int64_t>(s * 4 + static_cast<std::size_t>(m));
        for (std::size_t x = 0; x < outs.size() && to == std::numeric_limits<std::int64_t>::min(); ++x)
          if (!used[x] && outs[x].k == g) to = -1 - static_cast<std::int64_t>(x), used[x] = 1;
        if (to == std::numeric_limits<std::int64_t>::min()) return false;
        link[t][static_cast<std::size_t>(i)] = to;
      }
    if (std::find(used.begin(), used.end(), 0) != used.end()) return false;
    take_places(olds, made.size());
    for (std::size_t t = 0; t < made.size(); ++t) {
      const std::uint32_t at = places_[t];
      c_[at] = made[t];
      mark_[at] = 0;
      for (int i = 0; i < 4; ++i) {
        const std::int64_t to = link[t][static_cast<std::size_t>(i)];
        if (to >= 0) {
          nb_[at][static_cast<std::size_t>(i)] = static_cast<std::int32_t>(places_[static_cast<std::size_t>(to / 4)]);
          continue;
        }
        const outer& x = outs[static_cast<std::size_t>(-1 - to)];
        nb_[at][static_cast<std::size_t>(i)] = x.n;
        if (x.n >= 0) nb_[static_cast<std::size_t>(x.n)][static_cast<std::size_t>(x.back)] = static_cast<std::int32_t>(at);
      }
    }
    last_ = places_[0];
    return true;
  }
  bool in_ball(std::uint32_t a, vertex_id q) const {
    const cell& c = c_[a];
    return geometry::in_sphere_perturbed(p_[c[0]], p_[c[1]], p_[c[2]], p_[c[3]], p_[q]) > 0;
  }
  // the first cell, breadth first from `from` (itself after), for which good(cell), among 4096
  template <class Good>
  std::uint32_t nearest(std::uint32_t from, Good&& good) {
    if (stamp_ > 0xFFFFFFF0u) std::fill(mark_.begin(), mark_.end(), 0), stamp_ = 0;
    const std::uint32_t seen = ++stamp_;
    dead_.clear();
    dead_.push_back(from);
    mark_[from] = seen;
    for (std::size_t k = 0; k < dead_.size() && k < 4096; ++k) {
      const std::uint32_t a = dead_[k];
      if (good(a)) return a;
      for (int i = 0; i < 4; ++i) {
        const std::int32_t n = nb_[a][static_cast<std::size_t>(i)];
        if (n >= 0 && mark_[static_cast<std::size_t>(n)] != seen) mark_[static_cast<std::size_t>(n)] = seen, dead_.push_back(static_cast<std::uint32_t>(n));
      }
    }
    return none;
  }
  // a visibility walk from `from` towards q: the cell holding q, or the cell at the wall it met
  std::uint32_t locate(vertex_id q, std::uint32_t from) {
    std::uint32_t a = from;
    const std::size_t limit = 4 * c_.size() + 64;
    for (std::size_t step = 0; step < limit; ++step) {
      int beyond = -1;
      for (int k = 0; k < 4 && beyond < 0; ++k) {
        const int i = static_cast<int>((static_cast<std::size_t>(k) + step) % 4);  // turning start: no cycles
        const face f = face_of(c_[a], i);
        if (geometry::orient3d(p_[f[0]], p_[f[1]], p_[f[2]], p_[q]) < 0) beyond = i;
      }
      walk_inside_ = beyond < 0;
      if (beyond < 0) return a;
      const std::int32_t n = nb_[a][static_cast<std::size_t>(beyond)];
      if (n < 0) return a;
      a = static_cast<std::uint32_t>(n);
    }
    return none;
  }

  std::span<const point3> p_;
  std::vector<cell> c_;
  std::vector<std::array<std::int32_t, 4>> nb_;
  std::vector<std::uint32_t> mark_;
  std::uint32_t stamp_ = 0;
  std::vector<std::uint32_t> dead_, places_, free_;
  std::vector<std::pair<std::uint32_t, int>> rim_;
  std::vector<std::pair<face, std::uint32_t>> dropped_;
  std::vector<star_cell> made_;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> edges_;
  std::vector<char> spare_;   // per place: no cell holds it (it is in free_)
  bool walk_inside_ = false;  // the last walk ended in a cell holding its point
  std::uint32_t last_ = 0;
};

}  // namespace gsse::refinement::insertion
