#include "gsse/placement/placement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include "gsse/container/union_find.hpp"
#include "gsse/geometry/hash_grid.hpp"
#include "gsse/sizing/distance.hpp"
#include "gsse/sizing/place_points.hpp"
#include "gsse/traversal/for_each.hpp"
#include "gsse/traversal/parallel_sort.hpp"

namespace gsse::placement {

template <std::size_t D>
void add_cloud(std::vector<point<D>>& out, const std::vector<point<D>>& cloud, const location::locator<D>& at,
               std::size_t& dropped, unsigned threads, std::vector<double>* values) {
  for (const auto& q : cloud) {
    if (at.in_segment(q))
      out.push_back(q);
    else
      ++dropped;
  }
  if (!values) {
    gsse::stable_sort(execution::par(threads), out.begin(), out.end(), [](const auto& x, const auto& y) { return lex_less(x, y); });
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return;
  }
  // the same order (a stable sort of the points), the values carried along
  values->resize(out.size(), 0.0);
  std::vector<std::pair<point<D>, double>> both(out.size());
  for (std::size_t i = 0; i < out.size(); ++i) both[i] = {out[i], (*values)[i]};
  gsse::stable_sort(execution::par(threads), both.begin(), both.end(), [](const auto& x, const auto& y) { return lex_less(x.first, y.first); });
  out.clear(), values->clear();
  for (const auto& [q, v] : both) {
    if (!out.empty() && out.back() == q) {
      values->back() = std::max(values->back(), v);
      continue;
    }
    out.push_back(q), values->push_back(v);
  }
}

namespace {

/// The closest point (foot) of the faces of `b` offered to it, of those within `keep` of q; then
/// q carried to `lift` off that foot (the band's move, README step 4), or nothing if none was
/// within `keep` or q lies on a face.
template <std::size_t D>
struct nearest_foot {
  const surface<D>& b;
  point<D> q;
  double best;  // squared distance of the closest so far (keep^2 at first)
  point<D> foot{};
  nearest_foot(const surface<D>& b_, const point<D>& q_, double keep) : b(b_), q(q_), best(keep * keep) {}
  bool operator()(std::uint32_t f) {
    std::array<point<D>, D> F;
    for (std::size_t i = 0; i < D; ++i) F[i] = b.points[b.faces[f][i]];
    const point<D> c = sizing::face_closest<D>(F, q);
    const double d2 = squared_distance(c, q);
    if (d2 < best) best = d2, foot = c;
    return true;
  }
  std::optional<point<D>> lifted(double keep, double lift) const {
    if (best >= keep * keep || best <= 0) return std::nullopt;
    return foot + (lift / std::sqrt(best)) * (q - foot);
  }
};

}  // namespace

template <std::size_t D>
std::vector<point<D>> field_points(const surface<D>& b, const location::locator<D>& at, const std::vector<int>& numbers,
                                   const sizing::size_field<D>& h, unsigned threads, std::vector<double>* lower) {
  std::vector<sizing::aabb<D>> fb(b.faces.size());
  for (std::size_t f = 0; f < b.faces.size(); ++f) {
    fb[f] = sizing::aabb<D>::empty();
    for (vertex_id v : b.faces[f]) fb[f].add(b.points[v]);
  }
  const sizing::box_tree<D> faces(std::move(fb), std::vector<double>(b.faces.size(), 0.0));
  sizing::placement<D> where;
  where.segment_of = [&](const point<D>& q) {
    thread_local std::uint32_t hint = location::locator<D>::no_cell;  // per worker: its last cell (region_of)
    const int r = at.region_of(q, hint);
    return r < 0 ? sizing::no_segment : numbers[static_cast<std::size_t>(r)];
  };
  where.clear = [&](const point<D>& q, double keep) {
    return faces.visit([&](const sizing::aabb<D>& bx) { return bx.distance2(q) < keep * keep; }, [&](std::uint32_t f) {
      std::array<point<D>, D> F;
      for (std::size_t i = 0; i < D; ++i) F[i] = b.points[b.faces[f][i]];
      return sizing::face_distance2<D>(F, q) >= keep * keep;
    });
  };
  where.away = [&](const point<D>& q, double keep, double lift) {
    nearest_foot<D> n(b, q, keep);
    faces.visit_near(q, [&](const sizing::aabb<D>& bx) { return bx.distance2(q) < n.best; }, n);
    return n.lifted(keep, lift);
  };
  return sizing::place_points<D>(h, sizing::aabb<D>{at.lo(), at.hi()}, where, threads, lower);
}

template <std::size_t D>
std::vector<point<D>> lattice_points(const surface<D>& b, const location::locator<D>& at, double h, unsigned threads) {
  const point<D> lo = at.lo(), hi = at.hi();
  auto in_segment = [&](const point<D>& q, std::uint32_t& hint) { return at.in_segment(q, hint); };
  std::vector<point<D>> out;
  if (h > 0) {
    // keep-off distance from the boundary faces (not only their vertices: a lattice point close to
    // a facet's interior would be projected onto it, leaving a very short edge), through a hash
    // of the faces' bounding boxes; double distances only place points, they decide no topology
    // (a hair over half the lattice's neighbour distance h: two neighbours both this far from
    // every face have no face between them, so the segment test below is asked once per
    // connected set of clear points; 1e-7 covers the rounding of positions and distances)
    const double keep = 0.5 * h * (1 + 1e-7);
    hash_grid<D> near(lo, keep);
    using cell = typename hash_grid<D>::cell;
    auto face_distance2 = [&](std::uint32_t f, const point<D>& q) {
      const auto& F = b.faces[f];
      if constexpr (D == 2) {
        return sizing::segment_distance2(b.points[F[0]], b.points[F[1]], q);
      } else {
        // closest point of the triangle: the plane's foot if inside, else the nearest edge point
        return sizing::triangle_distance2(b.points[F[0]], b.points[F[1]], b.points[F[2]], q);
      }
    };
    // the hash's cells over the model's box: a dense map of them is kept where it is small
    std::array<long, D> dims{};
    double cells_total = 1;
    for (std::size_t k = 0; k < D; ++k) {
      dims[k] = static_cast<long>((hi[k] - lo[k]) / keep) + 1;
      cells_total *= static_cast<double>(dims[k]);
      if (dims[k] >= (1l << 20)) cells_total = 1e300;
    }
    // a cell clamped into the dense map: a face in a cell within one cell of q's lies within one
    // cell of q's clamped cell too (clamping keeps the order of coordinates and shortens gaps)
    auto index_of = [&](const cell& c) {
      std::size_t i = 0;
      for (std::size_t k = D; k-- > 0;) i = i * static_cast<std::size_t>(dims[k]) + static_cast<std::size_t>(std::clamp(c[k], 0l, dims[k] - 1));
      return i;
    };
    // each face's cells (not its box: a slanted facet's box is a volume of cells), listed in
    // parallel. Up to 2^24 cells they are filed in a dense table (faces per cell, counted then
    // filled in face order), else in the hash: filing 467,000 (cell, face) pairs one by one into
    // the hash, a vector per cell, was 40 ms of serial work on the rotated trench at 6e5 elements
    std::vector<std::vector<cell>> face_cells(b.faces.size());
    {
      std::vector<std::uint32_t> face_ids(b.faces.size());
      std::iota(face_ids.begin(), face_ids.end(), std::uint32_t{0});
      // largest first: a face's cells grow with its extent (to the power D - 1)
      for_each(execution::par(threads), face_ids, [&](std::uint32_t f) {
        std::array<point<D>, D> v;
        for (std::size_t k = 0; k < D; ++k) v[k] = b.points[b.faces[f][k]];
        near.simplex_cells(v, [&](const cell& c) { face_cells[f].push_back(c); });
      }, [&](std::uint32_t f) {
        double e = 0;
        for (std::size_t k = 1; k < D; ++k) e = std::max(e, distance(b.points[b.faces[f][0]], b.points[b.faces[f][k]]));
        return std::pow(e / keep + 1, static_cast<double>(D - 1));
      });
    }
    const bool dense = cells_total <= double(1 << 24);
    std::vector<std::uint32_t> first, listed;  // dense: the faces of cell i are listed[first[i] .. first[i + 1])
    if (dense) {
      first.assign(static_cast<std::size_t>(cells_total) + 1, 0);
      for (const auto& cs : face_cells)
        for (const auto& c : cs) ++first[index_of(c) + 1];
      for (std::size_t i = 1; i < first.size(); ++i) first[i] += first[i - 1];
      listed.resize(first.back());
      std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
      for (std::uint32_t f = 0; f < face_cells.size(); ++f)
        for (const auto& c : face_cells[f]) listed[fill[index_of(c)]++] = f;
    } else {
      for (std::uint32_t f = 0; f < face_cells.size(); ++f)
        for (const auto& c : face_cells[f]) near.insert_cell(f, c);
    }
    face_cells = {};
    // a dense map of the cells the ring search below can find a face from (within one cell of an
    // occupied one): a lattice point in an unmarked cell is clear without a look at the faces
    // (most of a slanted model's bounding box is far from every face, and each look reads the 3^D
    // cells about the point). Marked from the faces' own cells, not their boxes (a slanted face's
    // box is a volume of cells: on the rotated structures most cells were marked), so a point is
    // unmarked exactly when the ring search would find no face. Skipped above 2^26 cells or 2^20
    // along an axis (the hash's cell keys are exact below that).
    std::vector<char> marked;
    auto mark_about = [&](const cell& o) {
      cell a = o, e = o;
      for (std::size_t k = 0; k < D; ++k) a[k] = std::clamp(o[k] - 1, 0l, dims[k] - 1), e[k] = std::clamp(o[k] + 1, 0l, dims[k] - 1);
      if constexpr (D == 3) {
        for (long z = a[2]; z <= e[2]; ++z)
          for (long y = a[1]; y <= e[1]; ++y)
            std::fill_n(marked.begin() + ((z * dims[1] + y) * dims[0] + a[0]), e[0] - a[0] + 1, 1);
      } else {
        for (long y = a[1]; y <= e[1]; ++y) std::fill_n(marked.begin() + (y * dims[0] + a[0]), e[0] - a[0] + 1, 1);
      }
    };
    if (cells_total <= double(1 << 26)) {
      marked.assign(static_cast<std::size_t>(cells_total), 0);
      if (dense) {
        for (std::size_t i = 0; i + 1 < first.size(); ++i) {
          if (first[i] == first[i + 1]) continue;
          cell o;
          std::size_t r = i;
          for (std::size_t k = 0; k < D; ++k) o[k] = static_cast<long>(r % static_cast<std::size_t>(dims[k])), r /= static_cast<std::size_t>(dims[k]);
          mark_about(o);
        }
      } else {
        near.for_each_occupied(mark_about);
      }
    }
    // calls f(face) for the faces filed in the cells within one cell of q's (clamped) cell, each
    // at most once for the first 16 (a face meets several of those cells); f returns false to stop
    auto visit_faces_near = [&](const point<D>& q, auto&& f) {
      if (!dense) return near.visit_ring(q, 1, f);
      const auto c = near.cell_of(q);
      cell lo_c, hi_c;
      for (std::size_t k = 0; k < D; ++k) {
        const long x = std::clamp(c[k], 0l, dims[k] - 1);
        lo_c[k] = std::max(x - 1, 0l), hi_c[k] = std::min(x + 1, dims[k] - 1);
      }
      std::array<std::uint32_t, 16> seen;
      std::size_t n_seen = 0;
      cell cur = lo_c;
      for (;;) {
        const std::size_t i = index_of(cur);
        for (auto j = first[i]; j < first[i + 1]; ++j) {
          const std::uint32_t face = listed[j];
          if (std::find(seen.begin(), seen.begin() + static_cast<long>(n_seen), face) != seen.begin() + static_cast<long>(n_seen)) continue;
          if (!f(face)) return false;
          if (n_seen < seen.size()) seen[n_seen++] = face;
        }
        std::size_t k = 0;
        while (k < D && ++cur[k] > hi_c[k]) cur[k] = lo_c[k], ++k;
        if (k == D) return true;
      }
    };
    auto clear_of_boundary = [&](const point<D>& q) {
      if (!marked.empty() && !marked[index_of(near.cell_of(q))]) return true;
      return visit_faces_near(q, [&](std::uint32_t f) { return face_distance2(f, q) >= keep * keep; });
    };
    // lattice: BCC in 3D (nearest-neighbour distance h), triangular in 2D; the origin is shifted
    // by odd fractions so lattice points rarely sit exactly on axis-aligned input planes
    const double a = D == 3 ? 2 * h / std::sqrt(3.0) : h;
    const double rowh = D == 3 ? a : h * std::sqrt(3.0) / 2;
    std::array<long, D> n;
    for (std::size_t k = 0; k < D; ++k) n[k] = static_cast<long>((hi[k] - lo[k]) / (k == 1 && D == 2 ? rowh : a)) + 2;
    // the origin's shift along each axis, in steps (the band's index ranges below use it too)
    static constexpr double off[3] = {0.0137, 0.0271, 0.0419};
    // the lattice point k of slab s (its last index): 3D k = 2 (i n1 + j) + corner/centre
    const long slabs = n[D - 1];
    const std::size_t per_slab = D == 3 ? static_cast<std::size_t>(2 * n[0] * n[1]) : static_cast<std::size_t>(n[0]);
    auto lattice_point = [&](long s, std::size_t k) -> point<D> {
      if constexpr (D == 3) {
        const auto ij = static_cast<long>(k / 2);
        const long i = ij / n[1], j = ij % n[1];
        point3 q{lo[0] + a * (static_cast<double>(i) + off[0]), lo[1] + a * (static_cast<double>(j) + off[1]),
                 lo[2] + a * (static_cast<double>(s) + off[2])};
        if (k % 2) q = q + point3{a / 2, a / 2, a / 2};
        return q;
      } else {
        const auto i = static_cast<long>(k);
        return point2{lo[0] + a * (static_cast<double>(i) + off[0] + 0.5 * static_cast<double>(s % 2)),
                      lo[1] + rowh * (static_cast<double>(s) + off[1])};
      }
    };
    // 1. which points are clear of the boundary, in parallel by eighths of slabs (slabs near many
    // faces cost more; whole slabs, handed out in order, left one thread the last costly one)
    std::vector<std::vector<char>> clear(static_cast<std::size_t>(slabs));
    for (auto& c : clear) c.resize(per_slab);
    std::vector<long> ids(static_cast<std::size_t>(slabs));
    std::iota(ids.begin(), ids.end(), 0l);
    constexpr long parts = 8;
    std::vector<long> pieces(static_cast<std::size_t>(slabs * parts));
    std::iota(pieces.begin(), pieces.end(), 0l);
    for_each(execution::par(threads), pieces, [&](long x) {
      const long s = x / parts, part = x % parts;
      auto& c = clear[static_cast<std::size_t>(s)];
      const std::size_t from = per_slab * static_cast<std::size_t>(part) / parts, to = per_slab * static_cast<std::size_t>(part + 1) / parts;
      for (std::size_t k = from; k < to; ++k) c[k] = clear_of_boundary(lattice_point(s, k)) ? 1 : 0;
    });
    // 2. whether they lie in a segment. Lattice neighbours (3D: a corner and the 8 centres about
    // it; 2D: the 6 about a point) are h apart, so no face passes between two clear neighbours
    // (it would come within h/2 < keep of one): the points joined through clear neighbours lie on
    // one side of every face, and the exact point location is asked once per such set, at its
    // first point. Skipped (each point asked) for a lattice of over 2^24 points, or coordinates
    // so far from the origin, against h, that rounding nears the margin.
    double mag = 0;
    for (std::size_t k = 0; k < D; ++k) mag = std::max({mag, std::abs(lo[k]), std::abs(hi[k]) + 2 * a});
    const double points_total = static_cast<double>(per_slab) * static_cast<double>(slabs);
    const bool joined = points_total <= double(1 << 24) && mag * 256 * std::numeric_limits<double>::epsilon() < 1e-9 * h;
    std::vector<char> in_of;             // per root: in a segment
    std::vector<std::uint32_t> root_of;  // per point: its root
    if (joined) {
      const std::size_t total = per_slab * static_cast<std::size_t>(slabs);
      auto is_clear = [&](std::size_t x) { return clear[x / per_slab][x % per_slab] != 0; };
      union_find<std::uint32_t> uf(total);
      auto link = [&](std::size_t x, std::size_t y) {
        if (is_clear(y)) uf.unite(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y));
      };
      for (long s = 0; s < slabs; ++s)
        for (std::size_t k = 0; k < per_slab; ++k) {
          const std::size_t x = static_cast<std::size_t>(s) * per_slab + k;
          if (!is_clear(x)) continue;
          if constexpr (D == 3) {
            if (k % 2) continue;  // from the corners only: each to the centres of the 8 cubes about it
            const auto ij = static_cast<long>(k / 2);
            const long i = ij / n[1], j = ij % n[1];
            for (long ds = -1; ds <= 0; ++ds)
              for (long di = -1; di <= 0; ++di)
                for (long dj = -1; dj <= 0; ++dj) {
                  const long S = s + ds, I = i + di, J = j + dj;
                  if (S < 0 || I < 0 || J < 0) continue;
                  link(x, static_cast<std::size_t>(S) * per_slab + static_cast<std::size_t>(2 * (I * n[1] + J) + 1));
                }
          } else {
            const auto i = static_cast<long>(k);
            if (i + 1 < n[0]) link(x, x + 1);
            if (s + 1 < slabs) {
              const long other = s % 2 ? i + 1 : i - 1;  // the row above is shifted by half the other way
              for (long I : {i, other})
                if (I >= 0 && I < n[0]) link(x, static_cast<std::size_t>(s + 1) * per_slab + static_cast<std::size_t>(I));
            }
          }
        }
      // every point to its root (the smallest index of its set: its first point; parents have
      // smaller indices, so one pass in order), the roots asked in parallel
      auto& up = uf.up;
      for (std::size_t x = 0; x < total; ++x) up[x] = up[up[x]];
      std::vector<std::uint32_t> roots;
      for (std::size_t x = 0; x < total; ++x)
        if (up[x] == x && is_clear(x)) roots.push_back(static_cast<std::uint32_t>(x));
      std::vector<char> root_in(roots.size());
      std::vector<std::size_t> which(roots.size());
      std::iota(which.begin(), which.end(), std::size_t{0});
      for_each(execution::par(threads), which, [&](std::size_t r) {
        const std::uint32_t x = roots[r];
        root_in[r] = at.in_segment(lattice_point(static_cast<long>(x / per_slab), x % per_slab)) ? 1 : 0;
      });
      in_of.assign(total, 0);
      for (std::size_t r = 0; r < roots.size(); ++r) in_of[roots[r]] = root_in[r];
      root_of = std::move(up);
    }
    // 3. the points kept, in slab order
    std::vector<std::vector<point<D>>> kept(static_cast<std::size_t>(slabs));
    for_each(execution::par(threads), ids, [&](long s) {
      // filled locally, moved once: neighbouring vectors' headers share cache lines
      std::vector<point<D>> out_s;
      std::uint32_t hint = location::locator<D>::no_cell;
      auto& c = clear[static_cast<std::size_t>(s)];
      for (std::size_t k = 0; k < per_slab; ++k) {
        if (!c[k]) continue;
        const point<D> q = lattice_point(s, k);
        if (joined ? in_of[root_of[static_cast<std::size_t>(s) * per_slab + k]] != 0 : in_segment(q, hint))
          out_s.push_back(q), c[k] = 2;  // 2: kept
      }
      kept[static_cast<std::size_t>(s)] = std::move(out_s);
    });
    for (const auto& k : kept) out.insert(out.end(), k.begin(), k.end());
    {
      // 4. the band next to the boundary. Points clear of it by h/2 leave holes there, up to a
      // lattice layer deep: edges up to 1.9 h from the boundary's vertices to the first interior
      // points. Each lattice point dropped as too close to a face is moved away from its nearest
      // face (the closest point of it) to `lift` above it; in lattice order, a moved point is added
      // when it is clear of the boundary, in a segment, and at least `gap` from every point kept
      // so far. Chosen on the 8 benchmark structures (docs/benchmarks.md part 36): lift 0.6 h and
      // gap 0.65 h left 0-25 edges above 1.5 h of about 1.1e5 (160-2,131 before), points +3-12%;
      // a gap of 0.7 h left up to 90, a lift of 0.7 h up to 400.
      const double gap = sizing::band_gap * h, lift = sizing::band_lift * h;
      // the lattice indices within r of x along axis k (3D corners at shift 0, centres at 1/2; 2D
      // along x the row's shift, along y the rows)
      auto range = [&](double x, std::size_t k, double shift, double r) {
        const double step = D == 2 && k == 1 ? rowh : a;
        const double u = (x - lo[k]) / step - off[k] - shift;
        return std::pair<long, long>{static_cast<long>(std::ceil(u - r / step)), static_cast<long>(std::floor(u + r / step))};
      };
      // whether a kept lattice point lies within gap of q
      auto near_kept = [&](const point<D>& q) {
        auto kept_near = [&](long s, std::size_t k) {
          return clear[static_cast<std::size_t>(s)][k] == 2 && squared_distance(lattice_point(s, k), q) < gap * gap;
        };
        if constexpr (D == 3) {
          for (long c = 0; c < 2; ++c) {
            std::array<std::pair<long, long>, 3> rg;
            for (std::size_t x = 0; x < 3; ++x) rg[x] = range(q[x], x, c ? 0.5 : 0.0, gap);
            for (long s = std::max(rg[2].first, 0l); s <= std::min(rg[2].second, slabs - 1); ++s)
              for (long i = std::max(rg[0].first, 0l); i <= std::min(rg[0].second, n[0] - 1); ++i)
                for (long j = std::max(rg[1].first, 0l); j <= std::min(rg[1].second, n[1] - 1); ++j)
                  if (kept_near(s, static_cast<std::size_t>(2 * (i * n[1] + j) + c))) return true;
          }
        } else {
          const auto rows = range(q[1], 1, 0.0, gap);
          for (long s = std::max(rows.first, 0l); s <= std::min(rows.second, slabs - 1); ++s) {
            const auto rg = range(q[0], 0, 0.5 * static_cast<double>(s % 2), gap);
            for (long i = std::max(rg.first, 0l); i <= std::min(rg.second, n[0] - 1); ++i)
              if (kept_near(s, static_cast<std::size_t>(i))) return true;
          }
        }
        return false;
      };
      // the moved points, each with the tests that do not depend on the points kept before it (no
      // kept lattice point within gap, clear of the boundary, in a segment) asked here, slab by
      // slab in parallel; the choice below, in lattice order, only asks the gap to the band's
      // points kept so far (the tests in this order left the rotated MOSFET's choice 5.2 ms of
      // serial work, 3,675 point locations for 4,913 moved points)
      std::vector<std::vector<point<D>>> moved(static_cast<std::size_t>(slabs));
      for_each(execution::par(threads), ids, [&](long s) {
        auto& m = moved[static_cast<std::size_t>(s)];
        std::uint32_t hint = location::locator<D>::no_cell;
        for (std::size_t k = 0; k < per_slab; ++k) {
          if (clear[static_cast<std::size_t>(s)][k]) continue;
          nearest_foot<D> nf(b, lattice_point(s, k), keep);
          visit_faces_near(nf.q, nf);
          if (const auto q = nf.lifted(keep, lift); q && !near_kept(*q) && clear_of_boundary(*q) && in_segment(*q, hint))
            m.push_back(*q);
        }
      });
      hash_grid<D> added(lo, gap);
      std::vector<point<D>> band;
      for (const auto& m : moved)
        for (const point<D>& q : m) {
          if (!added.visit_ring(q, 1, [&](std::uint32_t x) { return squared_distance(band[x], q) >= gap * gap; })) continue;
          added.insert(static_cast<std::uint32_t>(band.size()), q);
          band.push_back(q);
        }
      out.insert(out.end(), band.begin(), band.end());
    }
  }
  return out;
}

template std::vector<point<2>> lattice_points<2>(const surface<2>&, const location::locator<2>&, double, unsigned);
template std::vector<point<3>> lattice_points<3>(const surface<3>&, const location::locator<3>&, double, unsigned);
template std::vector<point<2>> field_points<2>(const surface<2>&, const location::locator<2>&, const std::vector<int>&,
                                               const sizing::size_field<2>&, unsigned, std::vector<double>*);
template std::vector<point<3>> field_points<3>(const surface<3>&, const location::locator<3>&, const std::vector<int>&,
                                               const sizing::size_field<3>&, unsigned, std::vector<double>*);
template void add_cloud<2>(std::vector<point<2>>&, const std::vector<point<2>>&, const location::locator<2>&, std::size_t&, unsigned,
                           std::vector<double>*);
template void add_cloud<3>(std::vector<point<3>>&, const std::vector<point<3>>&, const location::locator<3>&, std::size_t&, unsigned,
                           std::vector<double>*);

}  // namespace gsse::placement
