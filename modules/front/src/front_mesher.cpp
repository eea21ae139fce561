#include "gsse/front/front_mesher.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <iterator>
#include <type_traits>

#include "gsse/front/gift_wrap.hpp"
#include "gsse/front/kernels.hpp"

namespace gsse::front {

point_grid<3> make_grid(std::span<const point3> pts) { return point_grid<3>(pts); }
point_grid<2> make_grid(std::span<const point2> pts) { return point_grid<2>(pts); }

namespace {
/// Calls go(wrapper, boundary, local) and returns its cells. Kernels whose points are the grid
/// coordinates (not the projected facet kernel), on a grid over all the points, work on positions
/// in the grid's point array, which is in grid order: the points a search reads then lie near the
/// cells it scans (about 10% faster on 1e6 points). Ids are mapped in and out; the result is the
/// same either way.
template <class K, class Face, class Go>
auto run_on(const K& k, const point_grid<K::grid_dim>& grid, const std::vector<Face>& boundary, Go&& go) {
  if constexpr (std::is_same_v<typename decltype(k.p)::element_type, const std::array<double, K::grid_dim>>) {
    if (grid.dense() && grid.size() == k.p.size()) {
      const K local{grid.coords()};
      std::vector<Face> b(boundary);
      for (auto& f : b)
        for (auto& v : f) v = grid.position(v);
      gift_wrapper<K, true> w(local, grid);
      auto cells = go(w, b, true);
      for (auto& c : cells)
        for (auto& v : c) v = grid.id_at(v);
      return cells;
    }
  }
  gift_wrapper<K> w(k, grid);
  return go(w, boundary, false);
}

/// One front, or (block > 0) pieces of at most about `block` points (gift_wrapper::run_blocked).
template <class K, class Face>
auto run(const K& k, const point_grid<K::grid_dim>& grid, const std::vector<Face>& boundary, const std::string& label,
         wrap_stats* stats, std::size_t max_cells, std::size_t block) {
  return run_on(k, grid, boundary, [&](auto& w, const std::vector<Face>& b, bool) {
    auto cells = block ? w.run_blocked(b, label, max_cells, block) : w.run(b, label, max_cells);
    if (stats) *stats += w.stats();
    return cells;
  });
}

/// wrap_cavity(): one front on global ids (not run_on's positions: the old/added test reads them),
/// faces of old vertices searching `added` only.
template <class K, class Face>
auto run_cavity(const K& k, const point_grid<K::grid_dim>& grid, const point_grid<K::grid_dim>& added, vertex_id first_added,
                const std::vector<Face>& boundary, const std::string& label) {
  gift_wrapper<K> w(k, grid);  // keeps a reference to k, which outlives it here
  w.old_faces_from(&added, first_added);
  return w.run_blocked(boundary, label, 0, block_points);
}

template <class K, class Face>
auto run_wall(const K& k, const point_grid<K::grid_dim>& grid, const std::vector<Face>& boundary,
              const std::string& label, std::size_t axis, double x0, std::array<std::vector<Face>, 2>& sides) {
  return run_on(k, grid, boundary, [&](auto& w, const std::vector<Face>& b, bool local) {
    auto cells = w.run_wall(b, label, axis, x0, sides);
    if (local)  // the sides come back in positions
      for (auto& side : sides)
        for (auto& f : side)
          for (auto& v : f) v = grid.id_at(v);
    return cells;
  });
}

}  // namespace

point_grid<2> make_grid(std::span<const point3> pts, int axis, std::span<const vertex_id> subset) {
  std::vector<std::array<double, 2>> c;
  c.reserve(subset.size());
  for (vertex_id v : subset) c.push_back(geometry::project(pts[v], axis));
  return point_grid<2>(c, subset);
}

std::vector<std::array<vertex_id, 4>> wrap(std::span<const point3> pts, const point_grid<3>& grid,
                                           const std::vector<std::array<vertex_id, 3>>& boundary,
                                           const std::string& label, wrap_stats* stats, std::size_t max_cells) {
  return run(volume_kernel{pts}, grid, boundary, label, stats, max_cells, block_points);
}
std::vector<std::array<vertex_id, 4>> wrap_cavity(std::span<const point3> pts, const point_grid<3>& grid,
                                                  const point_grid<3>& added, vertex_id first_added,
                                                  const std::vector<std::array<vertex_id, 3>>& boundary,
                                                  const std::string& label) {
  return run_cavity(volume_kernel{pts}, grid, added, first_added, boundary, label);
}
std::vector<std::array<vertex_id, 3>> wrap_cavity(std::span<const point2> pts, const point_grid<2>& grid,
                                                  const point_grid<2>& added, vertex_id first_added,
                                                  const std::vector<std::array<vertex_id, 2>>& boundary,
                                                  const std::string& label) {
  return run_cavity(plane_kernel{pts}, grid, added, first_added, boundary, label);
}
std::vector<std::array<vertex_id, 3>> wrap(std::span<const point2> pts, const point_grid<2>& grid,
                                           const std::vector<std::array<vertex_id, 2>>& boundary,
                                           const std::string& label, wrap_stats* stats, std::size_t max_cells) {
  return run(plane_kernel{pts}, grid, boundary, label, stats, max_cells, block_points);
}
std::vector<std::array<vertex_id, 4>> wrap_wall(std::span<const point3> pts, const point_grid<3>& grid,
                                                const std::vector<std::array<vertex_id, 3>>& boundary,
                                                const std::string& label, std::size_t axis, double x0,
                                                std::array<std::vector<std::array<vertex_id, 3>>, 2>& sides) {
  return run_wall(volume_kernel{pts}, grid, boundary, label, axis, x0, sides);
}
std::vector<std::array<vertex_id, 3>> wrap_wall(std::span<const point2> pts, const point_grid<2>& grid,
                                                const std::vector<std::array<vertex_id, 2>>& boundary,
                                                const std::string& label, std::size_t axis, double x0,
                                                std::array<std::vector<std::array<vertex_id, 2>>, 2>& sides) {
  return run_wall(plane_kernel{pts}, grid, boundary, label, axis, x0, sides);
}
std::vector<std::array<vertex_id, 3>> wrap_facet(std::span<const point3> pts, int axis, const point_grid<2>& grid,
                                                 const std::vector<std::array<vertex_id, 2>>& boundary,
                                                 const std::string& label, wrap_stats* stats, std::size_t max_cells,
                                                 bool coplanar, const facet_rewrap* again, const facet_lines* lines) {
  const facet_kernel k{pts, axis, coplanar, lines};
  gift_wrapper<facet_kernel> w(k, grid);
  if (again) w.reuse(again->previous, again->added);
  auto cells = w.run(boundary, label, max_cells);
  if (stats) *stats += w.stats();
  return cells;
}

std::vector<std::array<vertex_id, 3>> wrap_frame(std::span<const vertex_id> ids, std::span<const point2> uv,
                                                 const std::vector<std::array<vertex_id, 2>>& boundary,
                                                 const std::string& label, const facet_lines* lines,
                                                 const facet_rewrap* again) {
  const point_grid<2> grid(uv, ids);
  // id -> position in the grid's order: a table indexed by id, kept per thread and never cleared
  // (a facet's rewrap looks up every triangle it had; bisection in a sorted table of pairs was a
  // fifth of the rotated trench's conformer). An entry is trusted only if the grid's point at that
  // position has that id, so what earlier calls left in it is harmless. The table is used while
  // the ids stay below 2^20 or 16 times the facet's points (at most 4 MB, or 64 bytes a point, per
  // thread); beyond, bisection in a sorted table of (id, position) as before.
  thread_local std::vector<vertex_id> table;
  vertex_id top = 0;
  for (std::size_t k = 0; k < grid.size(); ++k) top = std::max(top, grid.id_at(k));
  const bool direct = top < std::max<std::size_t>(std::size_t{1} << 20, 16 * grid.size());
  std::vector<std::pair<vertex_id, vertex_id>> sorted;
  if (direct) {
    if (table.size() <= top) table.resize(static_cast<std::size_t>(top) + 1);
    for (std::size_t k = 0; k < grid.size(); ++k) table[grid.id_at(k)] = static_cast<vertex_id>(k);
  } else {
    sorted.resize(grid.size());
    for (std::size_t k = 0; k < grid.size(); ++k) sorted[k] = {grid.id_at(k), static_cast<vertex_id>(k)};
    std::sort(sorted.begin(), sorted.end());
  }
  auto pos = [&](vertex_id v) {
    if (direct && v < table.size()) {
      const vertex_id k = table[v];
      if (k < grid.size() && grid.id_at(k) == v) return k;
    } else if (!direct) {
      const auto it = std::lower_bound(sorted.begin(), sorted.end(), std::pair<vertex_id, vertex_id>{v, 0});
      if (it != sorted.end() && it->first == v) return it->second;
    }
    throw front_error(label + ": boundary vertex " + std::to_string(v + 1) + " is not a point of the facet");
  };
  frame_kernel k;
  k.p = grid.coords();
  k.grid = &grid;
  k.lines = lines;
  gift_wrapper<frame_kernel, true> w(k, grid);
  std::vector<std::array<vertex_id, 3>> previous;
  std::vector<vertex_id> added;
  if (again) {
    for (const auto& t : again->previous) previous.push_back({pos(t[0]), pos(t[1]), pos(t[2])});
    for (vertex_id v : again->added) added.push_back(pos(v));
    w.reuse(previous, added);
  }
  std::vector<std::array<vertex_id, 2>> b(boundary);
  for (auto& e : b) e = {pos(e[0]), pos(e[1])};
  auto cells = w.run(b, label, 0);
  for (auto& c : cells)
    for (auto& v : c) v = grid.id_at(v);
  return cells;
}

namespace {
/// A slanted facet's kernel on vertex ids (uv indexed by id), for a grid over some of its points.
struct id_frame_kernel : plane_kernel {
  const facet_lines* lines = nullptr;
  int side(const face& f, vertex_id y) const {
    if (lines && lines->collinear(f[0], f[1], y)) return 0;
    return plane_kernel::side(f, y);
  }
};

/// rewrap_facet_local / rewrap_frame_local on a kernel K over vertex ids below `id_bound`.
template <class K>
std::optional<std::vector<std::array<vertex_id, 3>>> rewrap_cavity(const K& k, std::size_t id_bound,
                                                                   const std::vector<std::array<vertex_id, 2>>& boundary,
                                                                   const facet_change& change, const std::string& label) {
  using tri = std::array<vertex_id, 3>;
  using edge = std::array<vertex_id, 2>;
  using coord = std::array<double, 2>;
  const auto& prev = change.previous;
  if (prev.empty() || !k.strict()) return std::nullopt;
  auto key = [](vertex_id a, vertex_id b) { return (std::uint64_t{a} << 32) | b; };
  std::vector<std::uint64_t> now, before, split;
  now.reserve(boundary.size());
  before.reserve(change.old_boundary.size());
  for (const auto& e : boundary) now.push_back(key(e[0], e[1]));
  for (const auto& e : change.old_boundary) before.push_back(key(e[0], e[1]));
  std::sort(now.begin(), now.end());
  std::sort(before.begin(), before.end());
  std::set_difference(before.begin(), before.end(), now.begin(), now.end(), std::back_inserter(split));  // split since
  std::vector<edge> front;  // the new boundary edges (pieces of split ones) first
  for (const auto& e : boundary)
    if (!std::binary_search(before.begin(), before.end(), key(e[0], e[1]))) front.push_back(e);
  // per vertex id, this thread's marks, cleared after use: 1 an end of a split edge, 2 a vertex of
  // a dead triangle, 4 a vertex of a new triangle
  thread_local std::vector<std::uint8_t> mark;
  if (mark.size() < id_bound) mark.resize(id_bound, 0);
  for (auto s : split) mark[s >> 32] |= 1, mark[s & 0xffffffffu] |= 1;
  std::vector<coord> at;
  at.reserve(change.added.size());
  for (vertex_id v : change.added) at.push_back(k.grid_coord(v));
  const point_grid<2> added(at, change.added);
  coord added_lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  coord added_hi{-added_lo[0], -added_lo[1]};
  for (const auto& q : at)
    for (std::size_t a = 0; a < 2; ++a) added_lo[a] = std::min(added_lo[a], q[a]), added_hi[a] = std::max(added_hi[a], q[a]);
  // the circles, kept by the caller across calls where it gives a cache of the right size
  auto* circles = change.circles && change.circles->size() == prev.size() ? change.circles : nullptr;
  // dead: resting on a split edge, or an added point beats the apex of one of its faces (lies in
  // its perturbed circle, seen from inside), as gift_wrapper::reusable decides per face
  std::vector<char> dead(prev.size(), 0);
  std::size_t dead_count = 0;
  for (std::size_t t = 0; t < prev.size(); ++t) {
    const tri& c = prev[t];
    bool d = false;
    if (!split.empty() && (mark[c[0]] & 1) + (mark[c[1]] & 1) + (mark[c[2]] & 1) >= 2)
      for (std::size_t i = 0; i < 3 && !d; ++i) d = std::binary_search(split.begin(), split.end(), key(c[(i + 1) % 3], c[(i + 2) % 3]));
    if (!d && !change.added.empty()) {
      coord cc;
      double r = 0;
      bool round = true;
      if (circles && !std::isnan((*circles)[t][2])) {
        cc = {(*circles)[t][0], (*circles)[t][1]}, r = (*circles)[t][2];
        round = r >= 0;
      } else {
        round = k.ball({c[1], c[2]}, c[0], cc, r);
        if (circles) (*circles)[t] = round ? std::array<double, 3>{cc[0], cc[1], r} : std::array<double, 3>{0, 0, -1};
      }
      if (!round) {
        d = true;
      } else if (cc[0] + r < added_lo[0] || cc[0] - r > added_hi[0] || cc[1] + r < added_lo[1] || cc[1] - r > added_hi[1]) {
        // no added point near: the box of the added points misses the circle's
      } else {
        const coord lo{cc[0] - r, cc[1] - r}, hi{cc[0] + r, cc[1] + r};
        const double r2 = r * r;
        added.visit_box(lo, hi, [&](vertex_id y, const coord& q) {
          if ((q[0] - cc[0]) * (q[0] - cc[0]) + (q[1] - cc[1]) * (q[1] - cc[1]) > r2) return true;
          if (y == c[0] || y == c[1] || y == c[2]) return true;
          for (std::size_t i = 0; i < 3; ++i) {
            const edge f{c[(i + 1) % 3], c[(i + 2) % 3]};
            if (k.side(f, y) > 0 && k.beats(f, c[i], y)) {
              d = true;
              return false;
            }
          }
          return true;
        });
      }
    }
    if (d) dead[t] = 1, ++dead_count;
  }
  for (auto s : split) mark[s >> 32] = 0, mark[s & 0xffffffffu] = 0;
  if (dead_count == 0 && front.empty() && change.added.empty()) return std::vector<tri>(prev.begin(), prev.end());
  // a cavity of a large part of the facet: the whole wrap costs about the same
  if (4 * dead_count > prev.size()) return std::nullopt;
  // the cavity's boundary: the dead triangles' faces met once (into them), less the split edges
  std::vector<std::pair<std::uint64_t, edge>> met;
  std::vector<vertex_id> cand(change.added.begin(), change.added.end());
  for (std::size_t t = 0; t < prev.size(); ++t) {
    if (!dead[t]) continue;
    const tri& c = prev[t];
    for (std::size_t i = 0; i < 3; ++i) {
      const edge f{c[(i + 1) % 3], c[(i + 2) % 3]};
      met.push_back({key(std::min(f[0], f[1]), std::max(f[0], f[1])), f});
      if (!(mark[c[i]] & 2)) mark[c[i]] |= 2, cand.push_back(c[i]);
    }
  }
  for (vertex_id v : cand) mark[v] = 0;
  std::sort(met.begin(), met.end());
  for (std::size_t i = 0; i < met.size();) {
    std::size_t j = i + 1;
    while (j < met.size() && met[j].first == met[i].first) ++j;
    if (j - i > 2 || (j - i == 2 && met[i].second == met[i + 1].second)) return std::nullopt;
    if (j - i == 1 && !std::binary_search(split.begin(), split.end(), key(met[i].second[0], met[i].second[1])))
      front.push_back(met[i].second);
    i = j;
  }
  for (const auto& e : front)
    for (vertex_id v : e) cand.push_back(v);
  std::sort(cand.begin(), cand.end());
  cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
  std::vector<coord> cc(cand.size());
  for (std::size_t i = 0; i < cand.size(); ++i) cc[i] = k.grid_coord(cand[i]);
  const point_grid<2> grid(cc, cand);
  gift_wrapper<K> w(k, grid);
  std::vector<tri> made;
  try {
    made = w.run(front, label, 0);
  } catch (const front_error&) {
    return std::nullopt;  // the whole wrap reports it
  }
  // every added point is a vertex of a new triangle, and the new triangles fill what the front
  // encloses (doubles, relative 1e-8: a safety net, the whole wrap is the fallback)
  for (const auto& c : made)
    for (vertex_id v : c) mark[v] |= 4;
  bool used = true;
  for (vertex_id v : change.added) used = used && (mark[v] & 4);
  for (const auto& c : made)
    for (vertex_id v : c) mark[v] = 0;
  if (!used) return std::nullopt;
  auto cross = [&](vertex_id a, vertex_id b, const coord& o) {
    const coord x = k.grid_coord(a), y = k.grid_coord(b);
    return (x[0] - o[0]) * (y[1] - o[1]) - (x[1] - o[1]) * (y[0] - o[0]);
  };
  const coord o = k.grid_coord(front[0][0]);
  double enclosed = 0, filled = 0, scale = 0;
  for (const auto& e : front) {
    const double v = cross(e[0], e[1], o);
    enclosed += v, scale += std::abs(v);
  }
  for (const auto& c : made) filled += std::abs(cross(c[1], c[2], k.grid_coord(c[0])));
  if (!(std::abs(std::abs(enclosed) - filled) <= 1e-8 * std::max(scale, filled) + 1e-300)) return std::nullopt;
  // the new triangles take the dead ones' places, in order, the rest at the end (a cavity of k
  // points has at least as many new triangles as dead ones); fewer: the kept ones close up
  std::vector<tri> out(prev.begin(), prev.end());
  std::size_t m = 0;
  for (std::size_t t = 0; t < prev.size(); ++t)
    if (dead[t] && m < made.size()) out[t] = made[m++], dead[t] = 0;
  out.insert(out.end(), made.begin() + static_cast<long>(m), made.end());
  if (m < dead_count) {
    std::size_t kept = 0;
    for (std::size_t t = 0; t < out.size(); ++t)
      if (t >= prev.size() || !dead[t]) out[kept++] = out[t];
    out.resize(kept);
  }
  return out;
}
}  // namespace

std::optional<std::vector<std::array<vertex_id, 3>>> rewrap_facet_local(std::span<const point3> pts, int axis,
                                                                        const std::vector<std::array<vertex_id, 2>>& boundary,
                                                                        const facet_change& change, const std::string& label,
                                                                        const facet_lines* lines) {
  const facet_kernel k{pts, axis, true, lines};
  return rewrap_cavity(k, pts.size(), boundary, change, label);
}

std::optional<std::vector<std::array<vertex_id, 3>>> rewrap_frame_local(std::span<const vertex_id> ids, std::span<const point2> uv,
                                                                        const std::vector<std::array<vertex_id, 2>>& boundary,
                                                                        const facet_change& change, const std::string& label,
                                                                        const facet_lines* lines) {
  if (ids.empty()) return std::nullopt;
  // uv by vertex id, per thread, never cleared: only the facet's own entries are read
  thread_local std::vector<point2> by_id;
  const std::size_t bound = static_cast<std::size_t>(*std::max_element(ids.begin(), ids.end())) + 1;
  if (by_id.size() < bound) by_id.resize(bound);
  for (std::size_t i = 0; i < ids.size(); ++i) by_id[ids[i]] = uv[i];
  id_frame_kernel k;
  k.p = std::span<const point2>(by_id.data(), bound);
  k.lines = lines;
  return rewrap_cavity(k, bound, boundary, change, label);
}

}  // namespace gsse::front
