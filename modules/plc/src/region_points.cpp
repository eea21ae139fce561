#include "gsse/plc/region_points.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "gsse/container/union_find.hpp"
#include "gsse/geometry/predicates.hpp"
#include "gsse/geometry/ray_tilts.hpp"
#include "gsse/traversal/for_each.hpp"

namespace gsse::plc_tools {
namespace {

struct triangle {
  std::array<point3, 3> v;
  std::size_t facet;
};

using geometry::ray_tilts;

point3 unit(const point3& d) {
  const double n = std::sqrt(dot(d, d));
  return n > 0 ? (1.0 / n) * d : d;
}

bool collinear(const point3& a, const point3& b, const point3& c) {
  for (int axis = 0; axis < 3; ++axis)
    if (geometry::orient_projected(a, b, c, axis) != 0) return false;
  return true;
}

enum class crossing { none, through, touch, on };

// Where the segment o-far meets triangle t, exactly: `through` its interior (not at an edge or
// vertex, far not in its plane), `touch` (edge, vertex, or far in its plane), `on` (o lies on the
// closed triangle), or `none`. `t_out`: parameter of the crossing along o-far, in doubles (only to
// rank crossings).
crossing meet(const triangle& t, const point3& o, const point3& far, double* t_out = nullptr) {
  const auto& [a, b, c] = t.v;
  const int so = geometry::orient3d(a, b, c, o), sf = geometry::orient3d(a, b, c, far);
  if (so == sf && so != 0) return crossing::none;
  int s[3];
  for (std::size_t k = 0; k < 3; ++k) s[k] = geometry::orient3d(o, far, t.v[k], t.v[(k + 1) % 3]);
  const bool inside = (s[0] >= 0 && s[1] >= 0 && s[2] >= 0) || (s[0] <= 0 && s[1] <= 0 && s[2] <= 0);
  if (!inside) return crossing::none;
  if (so == 0) return crossing::on;
  if (sf == 0 || s[0] == 0 || s[1] == 0 || s[2] == 0) return crossing::touch;
  if (t_out) {
    const point3 n = cross(b - a, c - a);
    *t_out = dot(a - o, n) / dot(far - o, n);
  }
  return crossing::through;
}

class locator {
 public:
  explicit locator(const plc<3>& p) {
    for (std::size_t f = 0; f < p.facets.size(); ++f)
      for (const auto& poly : p.facets[f].polygons)
        for (std::size_t k = 2; k < poly.size(); ++k) {
          triangle t{{p.points[poly[0]], p.points[poly[k - 1]], p.points[poly[k]]}, f};
          if (!collinear(t.v[0], t.v[1], t.v[2])) tris_.push_back(t);
        }
    point3 lo = p.points.empty() ? point3{} : p.points[0], hi = lo;
    for (const auto& q : p.points)
      for (std::size_t k = 0; k < 3; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
    len_ = 4 * (distance(lo, hi) + 1);
  }

  std::optional<point3> inside(const std::vector<std::size_t>& facets, std::size_t facet_count) const {
    std::vector<char> mine(facet_count, 0);
    for (const auto f : facets) mine[f] = 1;
    std::vector<std::size_t> own;  // this volume's triangles, largest first
    std::vector<double> area(tris_.size(), 0);
    for (std::size_t i = 0; i < tris_.size(); ++i)
      if (mine[tris_[i].facet]) {
        const auto& v = tris_[i].v;
        const point3 n = cross(v[1] - v[0], v[2] - v[0]);
        area[i] = dot(n, n);
        own.push_back(i);
      }
    std::stable_sort(own.begin(), own.end(), [&](std::size_t a, std::size_t b) { return area[a] > area[b]; });
    // a volume that cannot take a point from its 64 largest triangles is not worth more tries
    for (std::size_t k = 0; k < own.size() && k < 64; ++k) {
      const auto& T = tris_[own[k]];
      const point3 c = (1.0 / 3) * (T.v[0] + T.v[1] + T.v[2]);
      const point3 n = unit(cross(T.v[1] - T.v[0], T.v[2] - T.v[0]));
      for (const double side : {1.0, -1.0}) {
        const auto m = midpoint_to_first_hit(c, side * n, own[k]);
        if (m && odd_and_clear(*m, mine)) return m;
      }
    }
    return std::nullopt;
  }

 private:
  // Midpoint between c and the first facet a ray from c along `dir` (a unit vector) crosses; the
  // ray is tilted slightly when it touches an edge or vertex. nullopt: no hit (the unbounded
  // side), c on another facet, or every direction touched.
  std::optional<point3> midpoint_to_first_hit(const point3& c, const point3& dir, std::size_t skip) const {
    for (std::size_t d = 0; d <= 4; ++d) {
      const point3 u = d == 0 ? dir : unit(dir + ray_tilts[d - 1]);
      const point3 far = c + len_ * u;
      double best = std::numeric_limits<double>::infinity();
      bool retry = false;
      for (std::size_t i = 0; i < tris_.size() && !retry; ++i) {
        if (i == skip) continue;
        double t = 0;
        switch (meet(tris_[i], c, far, &t)) {
          case crossing::none: break;
          case crossing::on: return std::nullopt;
          case crossing::touch: retry = true; break;
          case crossing::through: best = std::min(best, t); break;
        }
      }
      if (retry) continue;
      if (!(best > 0 && best <= 1)) return std::nullopt;
      return c + (0.5 * best * len_) * u;
    }
    return std::nullopt;
  }

  // Whether m is inside the volume (a ray crosses its boundary an odd number of times) and on no
  // facet. Rays that touch an edge or vertex of any facet are cast again in another direction.
  bool odd_and_clear(const point3& m, const std::vector<char>& mine) const {
    for (const auto& tilt : ray_tilts) {
      const point3 far = m + len_ * unit(tilt);
      std::size_t count = 0;
      bool retry = false;
      for (std::size_t i = 0; i < tris_.size() && !retry; ++i) switch (meet(tris_[i], m, far)) {
          case crossing::none: break;
          case crossing::on: return false;
          case crossing::touch: retry = true; break;
          case crossing::through: count += mine[tris_[i].facet] ? 1 : 0; break;
        }
      if (!retry) return count % 2 == 1;
    }
    return false;
  }

  std::vector<triangle> tris_;
  double len_ = 1;

 public:
  /// The volume strictly holding m (odd crossings of its boundary), -1 for none, -2 when m lies on
  /// a facet of a volume or every direction touched an edge or vertex.
  long holder(const point3& m, const std::vector<std::vector<std::uint32_t>>& of, std::size_t volumes) const {
    std::vector<std::size_t> count(volumes);
    for (const auto& tilt : ray_tilts) {
      const point3 far = m + len_ * unit(tilt);
      std::fill(count.begin(), count.end(), 0);
      bool retry = false;
      for (std::size_t i = 0; i < tris_.size() && !retry; ++i) {
        if (of[tris_[i].facet].empty()) continue;
        switch (meet(tris_[i], m, far)) {
          case crossing::none: break;
          case crossing::on: return -2;
          case crossing::touch: retry = true; break;
          case crossing::through:
            for (auto v : of[tris_[i].facet]) ++count[v];
            break;
        }
      }
      if (retry) continue;
      for (std::size_t v = 0; v < volumes; ++v)
        if (count[v] % 2 == 1) return static_cast<long>(v);
      return -1;
    }
    return -2;
  }
  /// Points just off facet f on either side (the midpoints to the first facet a ray along its
  /// normal crosses), for the cells on its two sides.
  std::vector<point3> beside(std::size_t f) const {
    std::vector<point3> out;
    for (std::size_t i = 0; i < tris_.size(); ++i) {
      if (tris_[i].facet != f) continue;
      const auto& T = tris_[i];
      const point3 c = (1.0 / 3) * (T.v[0] + T.v[1] + T.v[2]);
      const point3 n = unit(cross(T.v[1] - T.v[0], T.v[2] - T.v[0]));
      for (const double side : {1.0, -1.0})
        if (const auto m = midpoint_to_first_hit(c, side * n, i)) out.push_back(*m);
      break;
    }
    return out;
  }

  /// Whether m is strictly outside every volume (facets of no volume are ignored); a point on a
  /// volume facet or undecided counts as not outside.
  bool outside_all(const point3& m, const std::vector<std::vector<std::uint32_t>>& of, std::size_t volumes) const {
    return holder(m, of, volumes) == -1;
  }
};

// The facets bounding no volume (of[f] empty), in pieces connected through shared edges, not
// across an edge of a volume's boundary: a surface crossing a wall is cut there into a part
// inside (embedded, kept) and a part outside. Each piece's facets ascending, pieces by first facet.
std::vector<std::vector<std::size_t>> loose_pieces(const plc<3>& p, const std::vector<std::vector<std::uint32_t>>& of) {
  const std::size_t n = p.facets.size();
  gsse::union_find<std::size_t> pieces_of(n);
  std::map<std::pair<vertex_id, vertex_id>, std::size_t> first;
  for (std::size_t f = 0; f < n; ++f) {
    if (of[f].empty()) continue;
    for (const auto& poly : p.facets[f].polygons)
      for (std::size_t k = 0; poly.size() >= 2 && k < poly.size(); ++k) {
        const vertex_id a = poly[k], b = poly[(k + 1) % poly.size()];
        first.try_emplace({std::min(a, b), std::max(a, b)}, n);
      }
  }
  for (std::size_t f = 0; f < n; ++f) {
    if (!of[f].empty()) continue;
    for (const auto& poly : p.facets[f].polygons)
      for (std::size_t k = 0; poly.size() >= 2 && k < poly.size(); ++k) {
        const vertex_id a = poly[k], b = poly[(k + 1) % poly.size()];
        const auto [it, fresh] = first.try_emplace({std::min(a, b), std::max(a, b)}, f);
        if (!fresh && it->second < n) pieces_of.unite(f, it->second);
      }
  }
  std::map<std::size_t, std::vector<std::size_t>> pieces;  // root -> facets, ascending
  for (std::size_t f = 0; f < n; ++f)
    if (of[f].empty()) pieces[pieces_of.find(f)].push_back(f);
  std::vector<std::vector<std::size_t>> list;
  for (auto& [r, fs] : pieces) list.push_back(std::move(fs));
  std::sort(list.begin(), list.end());
  return list;
}

std::vector<std::vector<std::uint32_t>> volumes_of(const plc<3>& p, const std::vector<std::vector<std::size_t>>& volumes) {
  std::vector<std::vector<std::uint32_t>> of(p.facets.size());
  for (std::size_t v = 0; v < volumes.size(); ++v)
    for (auto f : volumes[v]) of[f].push_back(static_cast<std::uint32_t>(v));
  return of;
}

}  // namespace

std::vector<std::optional<point3>> interior_points(const plc<3>& p, const std::vector<std::vector<std::size_t>>& volumes,
                                                   unsigned threads) {
  const locator where(p);
  std::vector<std::optional<point3>> out(volumes.size());
  std::vector<std::size_t> order(volumes.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  for_each(execution::par(threads), order, [&](std::size_t k) { out[k] = where.inside(volumes[k], p.facets.size()); });
  return out;
}

std::vector<std::pair<std::size_t, point3>> embedded_region_points(const plc<3>& p,
                                                                   const std::vector<std::vector<std::size_t>>& volumes,
                                                                   unsigned threads) {
  const auto of = volumes_of(p, volumes);
  std::vector<std::size_t> loose;  // the first facet of each loose piece
  for (const auto& piece : loose_pieces(p, of)) loose.push_back(piece.front());
  if (loose.empty()) return {};
  const locator where(p);
  std::vector<std::vector<std::pair<std::size_t, point3>>> found(loose.size());
  std::vector<std::size_t> order(loose.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  for_each(execution::par(threads), order, [&](std::size_t k) {
    for (const auto& m : where.beside(loose[k]))
      if (const long v = where.holder(m, of, volumes.size()); v >= 0) found[k].emplace_back(static_cast<std::size_t>(v), m);
  });
  std::vector<std::pair<std::size_t, point3>> out;
  for (auto& l : found) out.insert(out.end(), l.begin(), l.end());
  return out;
}

std::vector<stray_piece> drop_stray_facets(plc<3>& p, std::vector<std::vector<std::size_t>>& volumes, unsigned threads) {
  const std::size_t n = p.facets.size();
  const auto of = volumes_of(p, volumes);
  auto list = loose_pieces(p, of);
  if (list.empty()) return {};
  // a piece is stray if the centroids of its first, middle and last facets' first triangles are
  // all strictly outside every volume; a piece partly inside stays (the mesher names its edge)
  const locator where(p);
  std::vector<char> stray(list.size(), 0);
  std::vector<std::size_t> order(list.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  for_each(execution::par(threads), order, [&](std::size_t k) {
    const auto& fs = list[k];
    bool out = true;
    for (const std::size_t f : {fs.front(), fs[fs.size() / 2], fs.back()}) {
      const auto& poly = p.facets[f].polygons.front();
      if (poly.size() < 3) continue;
      const point3 c = (1.0 / 3) * (p.points[poly[0]] + p.points[poly[1]] + p.points[poly[2]]);
      out = out && where.outside_all(c, of, volumes.size());
      if (!out) break;
    }
    stray[k] = out;
  });
  std::vector<stray_piece> dropped;
  std::vector<char> drop(n, 0);
  for (std::size_t k = 0; k < list.size(); ++k)
    if (stray[k]) {
      dropped.push_back({list[k].front(), list[k].size()});
      for (auto f : list[k]) drop[f] = 1;
    }
  if (dropped.empty()) return dropped;
  for (auto& d : dropped) d.line = p.facets[d.facet].line;
  // keep the other facets and the points they use, renumbered in order
  std::vector<std::size_t> new_facet(n, 0);
  std::vector<plc_facet> facets;
  std::vector<vertex_id> new_point(p.points.size(), no_vertex);
  for (std::size_t f = 0; f < n; ++f) {
    if (drop[f]) continue;
    new_facet[f] = facets.size();
    facets.push_back(std::move(p.facets[f]));
    for (const auto& poly : facets.back().polygons)
      for (auto v : poly) new_point[v] = 0;
  }
  std::vector<point3> points;
  std::vector<int> markers;
  for (std::size_t v = 0; v < p.points.size(); ++v)
    if (new_point[v] == 0) {
      new_point[v] = static_cast<vertex_id>(points.size());
      points.push_back(p.points[v]);
      if (v < p.point_markers.size()) markers.push_back(p.point_markers[v]);
    }
  for (auto& f : facets)
    for (auto& poly : f.polygons)
      for (auto& v : poly) v = new_point[v];
  p.facets = std::move(facets);
  p.points = std::move(points);
  if (!p.point_markers.empty()) p.point_markers = std::move(markers);
  for (auto& vol : volumes)
    for (auto& f : vol) f = new_facet[f];
  return dropped;
}

}  // namespace gsse::plc_tools
