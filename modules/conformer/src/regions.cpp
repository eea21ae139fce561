#include "gsse/conformer/regions.hpp"

#include <algorithm>
#include <filesystem>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <numeric>
#include <optional>

#include "gsse/container/union_find.hpp"
#include "gsse/geometry/predicates.hpp"
#include "gsse/geometry/ray_tilts.hpp"
#include "gsse/sizing/box_tree.hpp"
#include "gsse/traversal/for_each.hpp"
#include "gsse/traversal/parallel_sort.hpp"

namespace gsse::conformer {
namespace {


using geometry::ray_tilts;

template <std::size_t D>
double diameter(const std::vector<point<D>>& p) {
  point<D> lo = p[0], hi = p[0];
  for (const auto& q : p)
    for (std::size_t k = 0; k < D; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
  return distance(lo, hi) + 1;
}

/// Does the segment o -> o + d meet the box (padded)? Doubles, a filter only: the faces it keeps
/// are decided by cast()'s exact predicates, in ascending order as if every face were tried.
template <std::size_t D>
bool segment_meets(const sizing::aabb<D>& box, const point<D>& o, const point<D>& d) {
  double t0 = 0, t1 = 1;
  for (std::size_t k = 0; k < D; ++k) {
    const double pad = 1e-9 * (box.hi[k] - box.lo[k]) + 1e-12 * (std::abs(box.lo[k]) + std::abs(box.hi[k])) + 1e-300;
    const double lo = box.lo[k] - pad, hi = box.hi[k] + pad;
    if (d[k] == 0) {
      if (o[k] < lo || o[k] > hi) return false;
      continue;
    }
    double a = (lo - o[k]) / d[k], c = (hi - o[k]) / d[k];
    if (a > c) std::swap(a, c);
    t0 = std::max(t0, a - 1e-9), t1 = std::min(t1, c + 1e-9);
    if (t0 > t1) return false;
  }
  return true;
}

/// Casts a ray from o towards o + dir. Returns the nearest hit (face, side facing o), or
/// {-1,0} for no hit; sets `degenerate` if the ray touched an edge or vertex of a face or o lies
/// on a face plane inside a face.
template <std::size_t D>
std::pair<long, int> cast(const boundary<D>& b, const point<D>& o, const point<D>& dir, long skip, bool& degenerate,
                          bool& on_face, vertex_id skip_vertex = no_vertex, const std::vector<std::uint32_t>* only = nullptr) {
  const auto& p = b.points;
  const point<D> far = o + dir;
  long best = -1;
  int best_side = 0;
  double best_t = std::numeric_limits<double>::infinity();
  degenerate = on_face = false;
  const std::size_t count = only ? only->size() : b.faces.size();
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t f = only ? (*only)[i] : i;
    if (static_cast<long>(f) == skip) continue;
    const auto& F = b.faces[f];
    if (skip_vertex != no_vertex && std::find(F.begin(), F.end(), skip_vertex) != F.end()) continue;
    // without a list of faces: a face whose box the segment misses is skipped before the exact
    // tests (the filter face_index applies). The late rounds' few located points (circumcentres
    // of nearly flat cells) cast against every face, and two exact orientations a face were a
    // tenth of a long run's time
    if (!only) {
      auto box = sizing::aabb<D>::empty();
      for (auto v : F) box.add(p[v]);
      if (!segment_meets(box, o, dir)) continue;
    }
    int so, sf;
    if constexpr (D == 2) {
      so = geometry::orient2d(p[F[0]], p[F[1]], o);
      sf = geometry::orient2d(p[F[0]], p[F[1]], far);
    } else {
      so = geometry::orient3d(p[F[0]], p[F[1]], p[F[2]], o);
      sf = geometry::orient3d(p[F[0]], p[F[1]], p[F[2]], far);
    }
    if (so == sf && so != 0) continue;  // both on one side
    // does the segment o-far pass through the face's interior?
    bool inside = true, touch = false;
    if constexpr (D == 2) {
      const int s0 = geometry::orient2d(o, far, p[F[0]]), s1 = geometry::orient2d(o, far, p[F[1]]);
      if (s0 == 0 || s1 == 0) touch = s0 != s1 || s0 != 0;
      inside = s0 != s1;
      if (s0 == 0 && s1 == 0) inside = false, touch = true;  // collinear with the ray
    } else {
      int s[3];
      for (int k = 0; k < 3; ++k) s[k] = geometry::orient3d(o, far, p[F[static_cast<std::size_t>(k)]], p[F[static_cast<std::size_t>((k + 1) % 3)]]);
      const bool pos = s[0] >= 0 && s[1] >= 0 && s[2] >= 0, neg = s[0] <= 0 && s[1] <= 0 && s[2] <= 0;
      inside = pos || neg;
      touch = inside && (s[0] == 0 || s[1] == 0 || s[2] == 0);
    }
    if (!inside) continue;
    if (so == 0) {
      on_face = true;  // o on the face (or in its plane inside the crossing): no side to tell
      return {-1, 0};
    }
    if (sf == 0 || touch) {
      degenerate = true;
      return {-1, 0};
    }
    // parameter of the crossing along the ray, in double: ranking only
    double t;
    if constexpr (D == 2) {
      const point2 a = p[F[0]], e = p[F[1]] - a, d = far - o;
      const double den = d[0] * e[1] - d[1] * e[0];
      t = ((a[0] - o[0]) * e[1] - (a[1] - o[1]) * e[0]) / den;
    } else {
      const point3 n = cross(p[F[1]] - p[F[0]], p[F[2]] - p[F[0]]);
      t = dot(p[F[0]] - o, n) / dot(far - o, n);
    }
    if (t < best_t) {
      best_t = t;
      best = static_cast<long>(f);
      best_side = so > 0 ? 0 : 1;
    }
  }
  return {best, best_side};
}

template <std::size_t D>
point<D> tilt_dir(const point<D>& base, std::size_t k, double len) {
  point<D> d{};
  for (std::size_t i = 0; i < D; ++i) d[i] = base[i] + ray_tilts[k][i];
  double n = std::sqrt(dot(d, d));
  if (n == 0) n = 1;
  return (len / n) * d;
}

template <std::size_t D>
point<D> face_normal(const boundary<D>& b, std::size_t f) {
  const auto& p = b.points;
  const auto& F = b.faces[f];
  if constexpr (D == 2) {
    const point2 e = p[F[1]] - p[F[0]];
    return {-e[1], e[0]};
  } else {
    return cross(p[F[1]] - p[F[0]], p[F[2]] - p[F[0]]);
  }
}

template <std::size_t D>
point<D> face_centre(const boundary<D>& b, std::size_t f) {
  point<D> c{};
  for (auto v : b.faces[f]) c = c + (1.0 / D) * b.points[v];
  return c;
}

/// The boundary's faces in a bounding-volume hierarchy: a ray visits the faces whose boxes it
/// meets, in ascending order, so that cast() decides exactly as if it tried every face.
template <std::size_t D>
struct face_index {
  explicit face_index(const boundary<D>& b) {
    std::vector<sizing::aabb<D>> boxes(b.faces.size());
    for (std::size_t f = 0; f < b.faces.size(); ++f) {
      boxes[f] = sizing::aabb<D>::empty();
      for (auto v : b.faces[f]) boxes[f].add(b.points[v]);
    }
    tree = sizing::box_tree<D>(std::move(boxes), std::vector<double>(b.faces.size(), 0.0));
  }
  /// The faces whose boxes the segment o -> o + d meets, ascending.
  std::vector<std::uint32_t> along(const point<D>& o, const point<D>& d) const {
    std::vector<std::uint32_t> out;
    tree.visit([&](const sizing::aabb<D>& box) { return segment_meets(box, o, d); },
               [&](std::uint32_t f) {
                 out.push_back(f);
                 return true;
               });
    std::sort(out.begin(), out.end());
    return out;
  }
  sizing::box_tree<D> tree;
};

/// Hit side (2*face + s) of a ray from o, trying the fixed directions in turn around `base`.
template <std::size_t D>
long first_side(const boundary<D>& b, const point<D>& o, const point<D>& base, long skip, double len,
                const std::string& what, vertex_id skip_vertex = no_vertex, const face_index<D>* index = nullptr) {
  for (std::size_t k = 0; k < ray_tilts.size(); ++k) {
    bool degenerate, on_face;
    const point<D> dir = tilt_dir(base, k, len);
    std::vector<std::uint32_t> near;
    if (index) near = index->along(o, dir);
    auto [f, s] = cast(b, o, dir, skip, degenerate, on_face, skip_vertex, index ? &near : nullptr);
    if (on_face) throw conform_error(what + " lies on the boundary");
    if (degenerate) continue;
    return f < 0 ? -1 : 2 * f + s;
  }
  throw conform_error(what + ": every ray met the boundary in an edge or vertex");
}

template <std::size_t D>
labelling label_impl(const boundary<D>& b, const plc<D>& p, unsigned threads) {
  const auto& pts = b.points;
  const std::size_t F = b.faces.size();
  gsse::union_find<std::size_t> shells(2 * F);
  std::vector<std::array<std::size_t, 3>> free_ends;  // free edges (3D) / ends (2D): (u, v, face)
  // gather faces around each (D-2)-simplex: edges in 3D, vertices in 2D
  if constexpr (D == 3) {
    // faces around each edge: (u, v, face) sorted, so each edge's faces are one run
    struct edge_face {
      vertex_id u, v;
      std::uint32_t f;
      auto operator<=>(const edge_face&) const = default;
    };
    std::vector<edge_face> ef;
    ef.reserve(3 * F);
    for (std::uint32_t f = 0; f < F; ++f)
      for (int k = 0; k < 3; ++k) {
        const auto [u, v] = std::minmax(b.faces[f][static_cast<std::size_t>(k)], b.faces[f][static_cast<std::size_t>((k + 1) % 3)]);
        ef.push_back({u, v, f});
      }
    gsse::stable_sort(execution::par(threads), ef.begin(), ef.end());  // entries are distinct
    std::vector<std::size_t> runs;  // starts of the runs, and the end
    for (std::size_t i = 0; i < ef.size(); ++i)
      if (i == 0 || ef[i].u != ef[i - 1].u || ef[i].v != ef[i - 1].v) runs.push_back(i);
    runs.push_back(ef.size());
    // each run in parallel pieces: the faces sorted around the edge give the side pairs to unite
    // (in run order, so the shells do not depend on the threads) and the first error, if any
    constexpr std::size_t piece = 4096;
    const std::size_t nruns = runs.size() - 1, npieces = (nruns + piece - 1) / piece;
    std::vector<std::vector<std::pair<std::size_t, std::size_t>>> unite(npieces);
    std::vector<std::vector<std::array<std::size_t, 3>>> dangling(npieces);
    std::vector<std::string> error(npieces);
    std::vector<std::size_t> pieces(npieces);
    std::iota(pieces.begin(), pieces.end(), std::size_t{0});
    for_each(execution::par(threads), pieces, [&](std::size_t k) {
      std::vector<std::uint32_t> fs;
      std::vector<std::pair<std::size_t, std::size_t>> pairs;  // moved into unite[k] at the end
      for (std::size_t run = k * piece; run < std::min(nruns, (k + 1) * piece) && error[k].empty(); ++run) {
        const vertex_id u = ef[runs[run]].u, v = ef[runs[run]].v;
        fs.clear();
        for (std::size_t i = runs[run]; i < runs[run + 1]; ++i) fs.push_back(ef[i].f);
        auto third = [&](std::uint32_t f) {
          for (auto w : b.faces[f])
            if (w != u && w != v) return w;
          return u;
        };
        if (fs.size() == 1) {
          // a free edge of an embedded facet: the region goes round it, gluing the two sides
          // (an open boundary shows as such a side left outside, checked once cells are known)
          pairs.push_back({2 * static_cast<std::size_t>(fs[0]), 2 * static_cast<std::size_t>(fs[0]) + 1});
          dangling[k].push_back({u, v, fs[0]});
          continue;
        }
        // + side of face (u,v,w) in this vertex order faces counter-clockwise around u->v
        auto ccw_side = [&](std::uint32_t f) {
          const auto& T = b.faces[f];
          bool forward = false;
          for (int j = 0; j < 3; ++j)
            forward |= T[static_cast<std::size_t>(j)] == u && T[static_cast<std::size_t>((j + 1) % 3)] == v;
          return 2 * static_cast<std::size_t>(f) + (forward ? 0 : 1);
        };
        if (fs.size() == 2 && b.face_source[fs[0]] == b.face_source[fs[1]]) {
          // two triangles of one facet's triangulation on either side of an inner edge: they
          // cannot overlap, and two faces pair the same in either order (no orientation test:
          // on a slanted facet each one fell to exact arithmetic)
          pairs.push_back({ccw_side(fs[0]), ccw_side(fs[1]) ^ 1u});
          pairs.push_back({ccw_side(fs[1]), ccw_side(fs[0]) ^ 1u});
          continue;
        }
        const vertex_id w0 = third(fs[0]);
        const int axis = geometry::dominant_axis(pts[u], pts[v], pts[w0]);
        const int ref = geometry::orient_projected(pts[u], pts[v], pts[w0], axis);
        auto cls = [&](std::uint32_t f) {
          const vertex_id w = third(f);
          const int o = geometry::orient3d(pts[u], pts[v], pts[w0], pts[w]);
          if (o > 0) return 1;
          if (o < 0) return 3;
          return geometry::orient_projected(pts[u], pts[v], pts[w], axis) == ref ? 0 : 2;
        };
        std::sort(fs.begin(), fs.end(), [&](std::uint32_t a, std::uint32_t c) {
          const int ca = cls(a), cc = cls(c);
          if (ca != cc) return ca < cc;
          if (a == c) return false;
          return geometry::orient3d(pts[u], pts[v], pts[third(a)], pts[third(c)]) > 0;
        });
        for (std::size_t i = 0; i < fs.size(); ++i) {
          const std::uint32_t a = fs[i], c = fs[(i + 1) % fs.size()];
          const bool same_half_plane =
              i + 1 < fs.size() && cls(a) == cls(c) &&
              (cls(a) == 0 || cls(a) == 2 || geometry::orient3d(pts[u], pts[v], pts[third(a)], pts[third(c)]) == 0);
          if (same_half_plane) {
            error[k] = p.source + ": boundary faces overlap at edge (" + std::to_string(u + 1) + ", " +
                       std::to_string(v + 1) + ") (facets " + std::to_string(b.face_source[a] + 1) + " and " +
                       std::to_string(b.face_source[c] + 1) + ")";
            break;
          }
          pairs.push_back({ccw_side(a), ccw_side(c) ^ 1u});
        }
      }
      unite[k] = std::move(pairs);
    });
    for (std::size_t k = 0; k < npieces; ++k) {
      if (!error[k].empty()) throw conform_error(error[k]);
      for (auto [x, y] : unite[k]) shells.unite(x, y);
      free_ends.insert(free_ends.end(), dangling[k].begin(), dangling[k].end());
    }
  } else {
    std::map<vertex_id, std::vector<std::uint32_t>> around;
    for (std::uint32_t f = 0; f < F; ++f)
      for (auto v : b.faces[f]) around[v].push_back(f);
    for (auto& [v, fs] : around) {
      auto other = [&](std::uint32_t f) { return b.faces[f][0] == v ? b.faces[f][1] : b.faces[f][0]; };
      if (fs.size() == 1) {  // a free end of an embedded segment (see the 3D case)
        shells.unite(2 * static_cast<std::size_t>(fs[0]), 2 * static_cast<std::size_t>(fs[0]) + 1);
        free_ends.push_back({v, v, fs[0]});
        continue;
      }
      const vertex_id w0 = other(fs[0]);
      const bool ref_side = lex_less(pts[v], pts[w0]);
      auto cls = [&](std::uint32_t f) {
        const vertex_id w = other(f);
        const int o = geometry::orient2d(pts[v], pts[w0], pts[w]);
        if (o > 0) return 1;
        if (o < 0) return 3;
        return lex_less(pts[v], pts[w]) == ref_side ? 0 : 2;
      };
      std::sort(fs.begin(), fs.end(), [&](std::uint32_t a, std::uint32_t c) {
        const int ca = cls(a), cc = cls(c);
        if (ca != cc) return ca < cc;
        if (a == c) return false;
        return geometry::orient2d(pts[v], pts[other(a)], pts[other(c)]) > 0;
      });
      for (std::size_t i = 0; i < fs.size(); ++i) {
        const std::uint32_t a = fs[i], c = fs[(i + 1) % fs.size()];
        if (a != c && geometry::orient2d(pts[v], pts[other(a)], pts[other(c)]) == 0 &&
            lex_less(pts[v], pts[other(a)]) == lex_less(pts[v], pts[other(c)]))
          throw conform_error(p.source + ": boundary segments overlap at vertex " + std::to_string(v + 1));
        // the left side of the ray v->w faces counter-clockwise around v
        auto ccw_side = [&](std::uint32_t f) { return 2 * static_cast<std::size_t>(f) + (b.faces[f][0] == v ? 0 : 1); };
        shells.unite(ccw_side(a), ccw_side(c) ^ 1u);
      }
    }
  }
  // cells: link each shell to the shell its inward ray hits first
  const double len = 4 * diameter(pts);
  gsse::union_find<std::size_t> cells(2 * F + 1);
  const std::size_t unbounded = 2 * F;
  std::vector<char> done(2 * F, 0);
  std::vector<std::size_t> probes;  // the first side of each shell
  for (std::size_t s = 0; s < 2 * F; ++s) {
    const std::size_t root = shells.find(s);
    if (!done[root]) done[root] = 1, probes.push_back(s);
  }
  // A shell facing away from the region it encloses (the outside of a body) must be linked to
  // the cell around it. A ray from a face along its normal can meet the same shell again where
  // it is not convex, which links nothing; a ray from the shell's vertex of largest x, towards
  // +x, cannot (every point of the shell has a smaller or equal x). Which way a shell faces: the
  // sign of the volume its sides bound, normals into their regions (divergence theorem).
  std::vector<double> volume(2 * F, 0);
  std::vector<vertex_id> extreme(2 * F, no_vertex);
  for (std::size_t s = 0; s < 2 * F; ++s) {
    const auto& T = b.faces[s / 2];
    double v;
    if constexpr (D == 2)
      v = pts[T[0]][0] * pts[T[1]][1] - pts[T[1]][0] * pts[T[0]][1];  // > 0 summed: the region is enclosed
    else
      v = -dot(pts[T[0]], cross(pts[T[1]], pts[T[2]]));  // the same sign convention
    const std::size_t root = shells.find(s);
    volume[root] += s % 2 ? -v : v;
    for (auto w : T)
      if (extreme[root] == no_vertex || lex_less(pts[extreme[root]], pts[w])) extreme[root] = w;
  }
  const double scale = std::pow(diameter(pts), static_cast<double>(D));
  std::vector<char> outward(2 * F, 0);
  for (std::size_t& s : probes) {
    const std::size_t root = shells.find(s);
    outward[root] = !(volume[root] > 1e-12 * scale);  // not enclosing its region: a body, a sheet, an open shell
  }
  // every ray crosses every face: the probes, region points and hole points cast theirs in
  // parallel; the results (or errors) are then used in this order, as if cast one by one
  const std::size_t nr = p.regions.size(), nh = p.holes.size();
  auto region_what = [&](std::size_t r) {
    return p.source + ": region point " + std::to_string(r + 1) + " (segment " + std::to_string(p.regions[r].number) + ")";
  };
  auto hole_what = [&](std::size_t h) { return p.source + ": hole point " + std::to_string(h + 1); };
  std::vector<long> hits(probes.size() + nr + nh);
  std::vector<std::exception_ptr> failed(hits.size());
  // a hierarchy pays for its build once the rays' face tests outnumber the faces a few times
  // (each ray alone tries every face with two exact orientations; a structure's 15 rays over its
  // 12,000 faces were 3% of the rotated MOSFET's run)
  std::optional<face_index<D>> index;
  if (hits.size() > 4 && hits.size() * b.faces.size() > 65536) index.emplace(b);
  const face_index<D>* rays = index ? &*index : nullptr;
  std::vector<std::size_t> order(hits.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  for_each(execution::par(threads), order, [&](std::size_t i) {
    try {
      if (i < probes.size()) {
        const std::size_t s = probes[i], f = s / 2, root = shells.find(s);
        if (outward[root]) {
          point<D> x{};
          x[0] = 1;
          hits[i] = first_side(b, pts[extreme[root]], x, -1, len, p.source + ": probe of vertex " + std::to_string(extreme[root] + 1),
                               extreme[root], rays);
        } else {
          point<D> n = face_normal(b, f);
          if (s % 2) n = -1.0 * n;
          hits[i] = first_side(b, face_centre(b, f), (1.0 / std::sqrt(dot(n, n))) * n, static_cast<long>(f), len,
                               p.source + ": probe of face " + std::to_string(f + 1), no_vertex, rays);
        }
      } else if (const std::size_t r = i - probes.size(); r < nr) {
        hits[i] = first_side(b, p.regions[r].at, point<D>{}, -1, len, region_what(r), no_vertex, rays);
      } else {
        hits[i] = first_side(b, p.holes[r - nr], point<D>{}, -1, len, hole_what(r - nr), no_vertex, rays);
      }
    } catch (...) {
      failed[i] = std::current_exception();
    }
  });
  auto hit_of = [&](std::size_t i) {
    if (failed[i]) std::rethrow_exception(failed[i]);
    return hits[i];
  };
  for (std::size_t i = 0; i < probes.size(); ++i) {
    const long hit = hit_of(i);
    cells.unite(shells.find(probes[i]), hit < 0 ? unbounded : shells.find(static_cast<std::size_t>(hit)));
  }
  // A free edge (end) with the unbounded cell round it: the boundary is open there, or a facet
  // sticks out of the domain; either way part of the input bounds nothing that can be meshed.
  for (const auto& [u, v, f] : free_ends)
    if (cells.find(shells.find(2 * f)) == cells.find(unbounded))
      throw conform_error(p.source + ": " + (D == 3 ? "facet " : "segment ") + std::to_string(b.face_source[f] + 1) +
                          (D == 3 ? " has a free edge (" + std::to_string(u + 1) + ", " + std::to_string(v + 1) + ")"
                                  : " has a free end at vertex " + std::to_string(u + 1)) +
                          " outside every region: the boundary is not closed there, or the " +
                          (D == 3 ? "facet" : "segment") + " sticks out of the domain");
  // region and hole points
  labelling out;
  std::map<std::size_t, int> cell_region;  // cell root -> region index, or exterior for holes
  for (std::size_t r = 0; r < nr; ++r) {
    const auto& g = p.regions[r];
    const std::string what = region_what(r);
    const long hit = hit_of(probes.size() + r);
    if (hit < 0 || cells.find(shells.find(static_cast<std::size_t>(hit))) == cells.find(unbounded))
      throw conform_error(what + " lies outside the domain");
    const std::size_t cell = cells.find(shells.find(static_cast<std::size_t>(hit)));
    int idx = -1;
    for (std::size_t k = 0; k < out.regions.size(); ++k)
      if (out.regions[k].number == g.number) idx = static_cast<int>(k);
    if (idx < 0) {
      out.regions.push_back({g.number, g.name});
      idx = static_cast<int>(out.regions.size() - 1);
    }
    auto [it, fresh] = cell_region.try_emplace(cell, idx);
    if (!fresh && it->second != idx)
      throw conform_error(what + " shares its region with segment " +
                          (it->second < 0 ? std::string("hole") : std::to_string(out.regions[static_cast<std::size_t>(it->second)].number)));
  }
  for (std::size_t h = 0; h < nh; ++h) {
    const long hit = hit_of(probes.size() + nr + h);
    if (hit < 0) continue;  // outside anyway
    cell_region[cells.find(shells.find(static_cast<std::size_t>(hit)))] = exterior;
  }
  out.side.assign(F, {exterior, exterior});
  for (std::size_t s = 0; s < 2 * F; ++s) {
    const std::size_t cell = cells.find(shells.find(s));
    if (cell == cells.find(unbounded)) continue;
    auto it = cell_region.find(cell);
    if (it == cell_region.end()) {
      if (!p.regions.empty())
        throw conform_error(p.source + ": a region bounded by facet " + std::to_string(b.face_source[s / 2] + 1) +
                            " has no region point (add one, or a hole point)");
      out.regions.push_back({static_cast<int>(out.regions.size() + 1), "region_" + std::to_string(out.regions.size() + 1)});
      it = cell_region.emplace(cell, static_cast<int>(out.regions.size() - 1)).first;
    }
    out.side[s / 2][s % 2] = it->second;
  }
  // a closed surface without region points (OFF, STL) is one segment named after its file
  if (p.regions.empty() && out.regions.size() == 1 && !p.source.empty())
    out.regions[0].name = std::filesystem::path(p.source).stem().string();
  return out;
}

template <std::size_t D>
std::vector<int> locate_impl(const boundary<D>& b, const labelling& l, const std::vector<point<D>>& q) {
  std::vector<int> r(q.size(), exterior);
  if (q.empty()) return r;
  const double len = 4 * diameter(b.points);
  // a few points cast their rays against every face: cheaper than building the index (the
  // refinement's late rounds locate a handful of points on a boundary of 1e5 faces)
  std::optional<face_index<D>> index;
  if (q.size() > 8) index.emplace(b);
  for (std::size_t i = 0; i < q.size(); ++i) {
    long hit;
    try {
      hit = first_side(b, q[i], point<D>{}, -1, len, "point", no_vertex, index ? &*index : nullptr);
    } catch (const conform_error&) {
      continue;  // on the boundary: not a volume point
    }
    if (hit >= 0) r[i] = l.side[static_cast<std::size_t>(hit) / 2][static_cast<std::size_t>(hit) % 2];
  }
  return r;
}

template <std::size_t D>
labelling label_refined_impl(const boundary<D>& b, const plc<D>& p, const boundary<D>& before, const labelling& l,
                             unsigned threads) {
  // the sides every face of a source (PLC edge or facet) had, or none if they differ (a facet
  // with a wall standing on it); the faces of one source are oriented alike (triangulated
  // counter-clockwise in one projection or frame; chains in order)
  if (l.side.size() != before.faces.size() || before.face_source.size() != before.faces.size() ||
      b.face_source.size() != b.faces.size())
    return label_impl(b, p, threads);
  constexpr std::array<int, 2> mixed{-2, -2};
  // per source: its faces' sides, and the direction of its largest face in each boundary (a
  // facet's normal, an edge's tangent). b need not come from the same conformer run as `before`
  // (the pipeline labels the sized boundary from the coarse model's): a source whose faces are
  // oriented the other way round in b takes its sides swapped. The two directions lie on one line
  // (the source's plane or edge); where they are not clearly parallel or opposite (|cos| below
  // 1/2, far above rounding: a degenerate largest face), b is labelled in full
  struct entry {
    std::array<int, 2> side;
  };
  auto direction = [](const boundary<D>& x, std::size_t f) {
    const auto& F = x.faces[f];
    if constexpr (D == 2)
      return x.points[F[1]] - x.points[F[0]];
    else
      return cross(x.points[F[1]] - x.points[F[0]], x.points[F[2]] - x.points[F[0]]);
  };
  // (the faces come source by source: a source is looked up once per run of its faces, not once
  // per face). The directions are measured afterwards,
  // and only for a source whose faces differ between the two boundaries: one run in each, face for
  // face the same, is oriented alike whatever its largest face (a refinement round re-triangulates
  // a few facets; measuring every face of both boundaries, serially, was 1.4-1.8 ms a round of the
  // rotated trench, docs/benchmarks.md, fifty-eighth part). The sources are input facets (PLC
  // edges in 2D), numbered densely: per source in arrays, where two ordered maps over them were
  // 16 ms a round of a torus whose 39,700 Gmsh triangles are each a facet (sixty-sixth part)
  struct run {
    std::size_t first, end;
    std::uint32_t id;  // the source
  };
  std::size_t n_sources = 0;
  for (auto s : before.face_source) n_sources = std::max<std::size_t>(n_sources, std::size_t{s} + 1);
  for (auto s : b.face_source) n_sources = std::max<std::size_t>(n_sources, std::size_t{s} + 1);
  // (numbers far beyond the faces' count are no conformer's: labelled in full, as other misfits)
  if (n_sources > 2 * (before.faces.size() + b.faces.size()) + 1024) return label_impl(b, p, threads);
  std::vector<entry> sides(n_sources);
  std::vector<char> known(n_sources, 0);
  std::vector<run> was;  // before's faces, by runs of one source
  for (std::size_t f = 0; f < before.faces.size(); ++f) {
    const std::uint32_t id = before.face_source[f];
    if (was.empty() || was.back().id != id) {
      if (!known[id]) known[id] = 1, sides[id] = entry{l.side[f]};
      was.push_back({f, f, id});
    }
    was.back().end = f + 1;
    if (sides[id].side != l.side[f]) sides[id].side = mixed;
  }
  std::vector<run> of;  // b's faces, by runs of one source
  for (std::size_t f = 0; f < b.faces.size(); ++f) {
    const std::uint32_t id = b.face_source[f];
    if (of.empty() || of.back().id != id) {
      if (!known[id] || sides[id].side == mixed) return label_impl(b, p, threads);
      of.push_back({f, f, id});
    }
    of.back().end = f + 1;
  }
  // per source: its runs in each boundary (placed by counting, in run order), and whether it has
  // one in each with the same faces (of the same points: b's points begin with before's, as in
  // the refinement's rounds)
  const bool same_points = b.points.size() >= before.points.size() &&
                           std::equal(before.points.begin(), before.points.end(), b.points.begin());
  auto by_source = [n_sources](const std::vector<run>& rs, std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& at) {
    start.assign(n_sources + 1, 0);
    for (const auto& r : rs) ++start[r.id + 1];
    for (std::size_t k = 0; k < n_sources; ++k) start[k + 1] += start[k];
    at.resize(rs.size());
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::uint32_t i = 0; i < rs.size(); ++i) at[next[rs[i].id]++] = i;
  };
  std::vector<std::uint32_t> was_start, was_at, of_start, of_at;
  by_source(was, was_start, was_at);
  by_source(of, of_start, of_at);
  std::vector<std::uint32_t> measure;  // the sources measured, ascending
  for (std::uint32_t id = 0; id < n_sources; ++id) {
    if (of_start[id] == of_start[id + 1]) continue;  // no face of it in b
    if (same_points && was_start[id + 1] - was_start[id] == 1 && of_start[id + 1] - of_start[id] == 1) {
      const run &x = was[was_at[was_start[id]]], &y = of[of_at[of_start[id]]];
      if (x.end - x.first == y.end - y.first &&
          std::equal(before.faces.begin() + static_cast<long>(x.first), before.faces.begin() + static_cast<long>(x.end),
                     b.faces.begin() + static_cast<long>(y.first), same_vertices<D>))
        continue;
    }
    measure.push_back(id);
  }
  // each source's largest face in each boundary (in face order, the first of equal ones), in
  // parallel over the sources
  std::vector<std::size_t> which(measure.size());
  std::iota(which.begin(), which.end(), std::size_t{0});
  std::vector<char> flip(measure.size(), 0), unclear(measure.size(), 0);
  auto runs_in = [](const std::vector<run>& rs, const std::vector<std::uint32_t>& start, const std::vector<std::uint32_t>& at,
                    std::uint32_t id, auto&& f) {
    for (std::uint32_t k = start[id]; k < start[id + 1]; ++k) f(rs[at[k]]);
  };
  for_each(execution::par(threads), which, [&](std::size_t k) {
    auto largest = [&](const boundary<D>& x, const std::vector<run>& rs, const std::vector<std::uint32_t>& start,
                       const std::vector<std::uint32_t>& at, point<D>& dir) {
      double len = -1;
      runs_in(rs, start, at, measure[k], [&](const run& r) {
        for (std::size_t f = r.first; f < r.end; ++f) {
          const point<D> d = direction(x, f);
          if (const double n = dot(d, d); n > len) len = n, dir = d;
        }
      });
      return len;
    };
    point<D> before_dir{}, dir{};
    const double before_len = largest(before, was, was_start, was_at, before_dir), len = largest(b, of, of_start, of_at, dir);
    const double c = dot(dir, before_dir);
    unclear[k] = !(std::abs(c) >= 0.5 * std::sqrt(len) * std::sqrt(before_len));
    flip[k] = c < 0;
  }, [&](std::size_t k) {
    double n = 0;
    runs_in(was, was_start, was_at, measure[k], [&](const run& r) { n += static_cast<double>(r.end - r.first); });
    runs_in(of, of_start, of_at, measure[k], [&](const run& r) { n += static_cast<double>(r.end - r.first); });
    return n;
  });
  for (std::size_t k = 0; k < measure.size(); ++k) {
    if (unclear[k]) return label_impl(b, p, threads);
    if (flip[k]) std::swap(sides[measure[k]].side[0], sides[measure[k]].side[1]);
  }
  labelling out;
  out.regions = l.regions;
  out.side.resize(b.faces.size());
  for (const auto& r : of)
    std::fill(out.side.begin() + static_cast<long>(r.first), out.side.begin() + static_cast<long>(r.end), sides[r.id].side);
  return out;
}

}  // namespace

labelling label(const boundary<2>& b, const plc<2>& p, unsigned threads) { return label_impl(b, p, threads); }
labelling label(const boundary<3>& b, const plc<3>& p, unsigned threads) { return label_impl(b, p, threads); }
labelling label_refined(const boundary<2>& b, const plc<2>& p, const boundary<2>& before, const labelling& l,
                        unsigned threads) {
  return label_refined_impl(b, p, before, l, threads);
}
labelling label_refined(const boundary<3>& b, const plc<3>& p, const boundary<3>& before, const labelling& l,
                        unsigned threads) {
  return label_refined_impl(b, p, before, l, threads);
}
std::vector<int> locate(const boundary<2>& b, const labelling& l, const std::vector<point2>& q) {
  return locate_impl(b, l, q);
}
std::vector<int> locate(const boundary<3>& b, const labelling& l, const std::vector<point3>& q) {
  return locate_impl(b, l, q);
}

}  // namespace gsse::conformer
