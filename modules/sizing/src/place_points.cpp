#include "gsse/sizing/place_points.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>

#include "gsse/geometry/hash_grid.hpp"
#include "gsse/traversal/for_each.hpp"
#include "gsse/traversal/parallel_sort.hpp"

namespace gsse::sizing {
namespace {

template <std::size_t D>
struct candidate {
  point<D> q;
  int level;
  std::uint64_t order;  // generation order within the whole run (root cube, then depth-first)
  double h = 0;         // the size at its cube's centre
  double off = 0;       // its distance from that centre, at most
};

constexpr int max_level = 40;

}  // namespace

template <std::size_t D>
std::vector<point<D>> place_points(const size_field<D>& h, const aabb<D>& box, const placement<D>& where,
                                   unsigned threads, std::vector<double>* lower) {
  const double extent = std::sqrt(squared_distance(box.lo, box.hi));
  const double d0 = std::isfinite(h.global()) ? std::min(h.global(), extent) : 0.5 * extent;
  const bool bounded = std::isfinite(h.slope());
  return place_points<D>([&h](const point<D>& x, int seg, double cap) { return seg == no_segment ? h.capped(x, cap) : h.capped(x, seg, cap); },
                         d0, box, where, threads, 1.0, true, h.global(), bounded ? h.slope() : 0.0, bounded ? lower : nullptr);
}

template <std::size_t D>
std::vector<point<D>> place_points(const std::function<double(const point<D>&, int, double)>& h, double d0, const aabb<D>& box,
                                   const placement<D>& where, unsigned threads, double stretch,
                                   bool parent, double band_from, double slope, std::vector<double>* lower) {
  const double extent = std::sqrt(squared_distance(box.lo, box.hi));
  if (!(extent > 0) || !(d0 > 0)) return {};
  // cube side of the level-0 lattice: BCC nearest neighbours at sqrt(3)/2 a; 2D: squares of side
  // d holding the triangular lattice's points (rows sqrt(3)/2 d apart)
  const double a0 = D == 3 ? 2 * d0 / std::sqrt(3.0) : d0;
  const double row0 = std::sqrt(3.0) / 2 * d0;
  // the origin shifted by odd fractions, as the uniform lattice: points rarely on axis-aligned planes
  point<D> origin;
  const double shift[3] = {0.0137, 0.0271, 0.0419};
  for (std::size_t k = 0; k < D; ++k) origin[k] = box.lo[k] - a0 * (1 - shift[k]);
  std::array<long, D> n;
  std::size_t roots = 1;
  for (std::size_t k = 0; k < D; ++k) {
    n[k] = static_cast<long>(std::ceil((box.hi[k] - origin[k]) / a0)) + 1;
    roots *= static_cast<std::size_t>(n[k]);
  }
  // a lattice coordinate: origin + (i * a0) / 2^level, exact in the level (scaling by two is exact)
  auto coord = [&](const std::array<std::int64_t, D>& i, int level) {
    point<D> q;
    for (std::size_t k = 0; k < D; ++k) q[k] = origin[k] + std::ldexp(static_cast<double>(i[k]) * a0, -level);
    return q;
  };
  // exact duplicates (shared corners) kept once, at their first place in (level, order)
  auto first = [](const candidate<D>& x, const candidate<D>& y) { return x.level < y.level || (x.level == y.level && x.order < y.order); };
  auto by_point = [&](const candidate<D>& x, const candidate<D>& y) {
    if (x.q != y.q) return x.q < y.q;
    return first(x, y);
  };
  // sorted by point, each kept at its first place (the keys are distinct: any sort gives one order)
  auto drop_duplicates = [&](std::vector<candidate<D>>& v) {
    gsse::stable_sort(execution::par(threads), v.begin(), v.end(), by_point);
    v.erase(std::unique(v.begin(), v.end(), [](const candidate<D>& x, const candidate<D>& y) { return x.q == y.q; }), v.end());
  };
  // per root cube: the candidates of its subtree, depth first
  std::vector<std::vector<candidate<D>>> per_root(roots);
  std::vector<std::size_t> generated(roots, 0);  // per root: its candidates before its duplicates went
  std::vector<std::size_t> ids(roots);
  std::iota(ids.begin(), ids.end(), std::size_t{0});
  for_each(execution::par(threads), ids, [&](std::size_t r) {
    std::array<std::int64_t, D> i0;
    std::size_t rest = r;
    for (std::size_t k = 0; k < D; ++k) i0[k] = static_cast<std::int64_t>(rest % static_cast<std::size_t>(n[k])), rest /= static_cast<std::size_t>(n[k]);
    auto& out = per_root[r];
    std::uint64_t order = 0;
    // cube at `level` with min corner index i (in units of a0 / 2^level)
    // hp: h at the parent cube's centre cp, in segment sp (unbounded at a root)
    auto visit = [&](auto&& self, const std::array<std::int64_t, D>& i, int level, double hp, const point<D>& cp, int sp) -> void {
      const double a = std::ldexp(a0, -level), d = std::ldexp(d0, -level);
      // the centre as the next level's corner 2i + 1, by the same formula: lo + a / 2 rounds
      // differently, and centres then sat an ulp off the plane of the corners beside them, whose
      // nearly coplanar, cocircular squares made flat tetrahedra (the FinFET with --grade)
      point<D> lo = coord(i, level), c;
      {
        std::array<std::int64_t, D> ic;
        for (std::size_t k = 0; k < D; ++k) ic[k] = 2 * i[k] + 1;
        c = coord(ic, level + 1);
      }
      // skip cubes (with their neighbourhood of one spacing) outside the model's box
      for (std::size_t k = 0; k < D; ++k)
        if (lo[k] > box.hi[k] + a || lo[k] + a < box.lo[k] - a) return;
      const int seg = where.segment_of(c);
      // a cube whose centre lies in no segment and that no boundary face comes near (within its
      // circumradius, every candidate of it and of its children inside, plus placement::slack)
      // lies wholly in no segment: all those candidates would be dropped, so it is neither asked
      // nor divided (a CAD part's box is mostly outside it). The points taken are the same: a
      // point dropped here is outside wherever else it is a candidate
      if (seg == no_segment && where.clear(c, std::sqrt(static_cast<double>(D)) * 0.5 * a * (1 + 1e-6) + where.slack)) return;
      // asked up to a cap that h cannot reach: in the parent's segment, h(c) <= h(cp) + slope |c -
      // cp| (h is Lipschitz, a segment's maximum one constant more in the minimum), so the value
      // is h itself, found by a search that skips every term above the cap from the start (it
      // gains little: the search finds the nearby terms first anyway; docs/benchmarks.md,
      // forty-fourth part)
      const bool capped = std::isfinite(hp) && sp == seg && slope > 0 && std::isfinite(slope);
      const double hc = h(c, seg, capped ? (hp + slope * distance(c, cp)) * (1 + 1e-9) : unbounded);
      // the coarsest level whose spacing is at most stretch * h (1: spacings in (h/2, h]); with
      // `parent`, h the smaller of the centre's and the parent's centre's (a corner of this cube):
      // where h dips across a cube (a thin layer whose size is smallest at its faces) the centre
      // alone chose a spacing above the size at the corners, and the mixed levels left edges up to
      // 1.63 h (the FinFET's gate oxide: 4,656 edges above 1.5 h, none with it; docs/benchmarks.md,
      // thirty-eighth part). The value is there already: no query more.
      if (d > stretch * (parent ? std::min(hc, hp) : hc) && level < max_level) {
        for (unsigned m = 0; m < (1u << D); ++m) {
          std::array<std::int64_t, D> j;
          for (std::size_t k = 0; k < D; ++k) j[k] = 2 * i[k] + ((m >> k) & 1u);
          self(self, j, level + 1, hc, c, seg);
        }
        return;
      }
      if constexpr (D == 3) {
        // (the corners lie d from the centre: BCC's nearest neighbours; 1e-9 for rounding)
        out.push_back({c, level, order++, hc, 0.0});
        for (unsigned m = 0; m < (1u << D); ++m) {
          std::array<std::int64_t, D> j;
          for (std::size_t k = 0; k < D; ++k) j[k] = i[k] + ((m >> k) & 1u);
          out.push_back({coord(j, level), level, order++, hc, d * (1 + 1e-9)});
        }
      } else {
        // the triangular lattice's points in the half-open square: row j at origin + j row0 / 2^level,
        // column m (same parity as j) at origin + m (d0 / 2) / 2^level; exact, and nested by level
        const double hi0 = lo[0] + a, hi1 = lo[1] + a;
        const double row = std::ldexp(row0, -level), half = std::ldexp(0.5 * d0, -level);
        for (auto j = static_cast<std::int64_t>(std::floor((lo[1] - origin[1]) / row)) - 1;; ++j) {
          const double y = origin[1] + std::ldexp(static_cast<double>(j) * row0, -level);
          if (y >= hi1) break;
          if (y < lo[1]) continue;
          auto m = static_cast<std::int64_t>(std::floor((lo[0] - origin[0]) / half)) - 2;
          if (((m - j) % 2 + 2) % 2 != 0) ++m;
          for (;; m += 2) {
            const double x = origin[0] + std::ldexp(static_cast<double>(m) * 0.5 * d0, -level);
            if (x >= hi0) break;
            if (x >= lo[0]) out.push_back({point<D>{x, y}, level, order++, hc, distance(point<D>{x, y}, c) * (1 + 1e-9)});
          }
        }
      }
    };
    visit(visit, i0, 0, unbounded, point<D>{}, no_segment);
    generated[r] = out.size();
  }, [&](std::size_t) { return 1.0; });
  // the roots' own duplicates (corners their cubes share) dropped root by root, each sort in
  // parallel (one root can hold most of the candidates: sorted inside the roots' tasks, the
  // graded trench's biggest root took a thread alone for a second), each point kept at its first
  // place in (level, order). Most of a cube's corners are another's: the gather and the sorts
  // below then read a quarter of the candidates (the graded trench: 8 million, 1.8 after;
  // sizing 4.91-5.17 -> 4.42-4.52 s, the same points)
  for (auto& out : per_root) drop_duplicates(out);
  std::vector<candidate<D>> all;
  {
    std::size_t total = 0, base = 0;
    for (const auto& v : per_root) total += v.size();
    all.reserve(total);
    for (std::size_t r = 0; r < per_root.size(); ++r) {
      for (auto& x : per_root[r]) all.push_back({x.q, x.level, base + x.order, x.h, x.off});
      base += generated[r];  // the orders a root generated, so that (level, order) is as if one run
      std::vector<candidate<D>>().swap(per_root[r]);
    }
  }
  // the duplicates between roots (corners on their shared faces) likewise; (both sorts in
  // parallel: their keys are distinct, (point, level, order) and (level, order), so any sort
  // gives the one order)
  drop_duplicates(all);
  gsse::stable_sort(execution::par(threads), all.begin(), all.end(), first);
  // classification in parallel: inside a segment and clear of the boundary by half the spacing
  // (1); or, where h at the cube's centre is at least `band_from`, too near a face but the point
  // moved off it is (2, the point in `moved`)
  std::vector<char> ok(all.size(), 0);
  const bool band = where.away && std::isfinite(band_from);
  std::vector<point<D>> moved(where.away ? all.size() : 0);
  constexpr std::size_t chunk = 1024;
  std::vector<std::size_t> chunks((all.size() + chunk - 1) / chunk);
  std::iota(chunks.begin(), chunks.end(), std::size_t{0});
  for_each(execution::par(threads), chunks, [&](std::size_t c) {
    for (std::size_t k = c * chunk; k < std::min(all.size(), (c + 1) * chunk); ++k) {
      const auto& x = all[k];
      const double d = std::ldexp(d0, -x.level);
      if (where.segment_of(x.q) == no_segment) continue;
      // clear of the faces by half the spacing, and by graded_keep h: only half the spacing, in
      // (h/4, h/2], left points on a slanted facet's side a quarter of h from it, and edges to the
      // facet's vertices below h/2 (5% of the edges on the rotated MOSFET); one too near by that
      // much only is moved graded_lift h off its nearest face (3)
      const double keep = std::isfinite(x.h) ? graded_keep<D> * x.h : 0.0;
      if (where.clear(x.q, std::max(0.5 * d, keep))) {
        ok[k] = 1;
      } else if (where.away && keep > 0.5 * d && !(band && x.h >= band_from) && where.clear(x.q, 0.5 * d)) {
        const auto m = where.away(x.q, keep, graded_lift<D> * x.h);
        if (m && where.clear(*m, keep) && where.segment_of(*m) != no_segment) ok[k] = 3, moved[k] = *m;
      } else if (band && x.h >= band_from) {
        const auto m = where.away(x.q, 0.5 * d, band_lift * d);
        if (m && where.clear(*m, 0.5 * d) && where.segment_of(*m) != no_segment) ok[k] = 2, moved[k] = *m;
      }
    }
  }, [&](std::size_t) { return 1.0; });
  // greedy, sequential: one hash grid per level with its spacing as cell
  std::vector<std::unique_ptr<hash_grid<D>>> grids(max_level + 1);
  std::vector<point<D>> out;
  int deepest = 0;
  for (const auto& x : all) deepest = std::max(deepest, x.level);
  // whether q (a candidate's point or its band point) is at least max(0.8 of the smaller spacing,
  // hf * h) from every point taken, h the size at the candidate's cube's centre
  auto free_of = [&](const point<D>& q, const candidate<D>& x, double hf) {
    bool free = true;
    for (int j = 0; j <= deepest && free; ++j) {
      if (!grids[static_cast<std::size_t>(j)]) continue;
      const double r = std::max(0.8 * std::ldexp(d0, -std::max(j, x.level)), hf * x.h);
      point<D> lo, hi;
      for (std::size_t a = 0; a < D; ++a) lo[a] = q[a] - r, hi[a] = q[a] + r;
      grids[static_cast<std::size_t>(j)]->visit(lo, hi, [&](std::uint32_t p) {
        if (squared_distance(out[p], q) < r * r) free = false;
        return free;
      });
    }
    return free;
  };
  if (lower) lower->clear();
  auto take = [&](const point<D>& q, const candidate<D>& x, double off) {
    auto& g = grids[static_cast<std::size_t>(x.level)];
    if (!g) g = std::make_unique<hash_grid<D>>(origin, std::ldexp(d0, -x.level));
    g->insert(static_cast<std::uint32_t>(out.size()), q);
    out.push_back(q);
    if (lower) lower->push_back(std::isfinite(x.h) ? x.h - slope * off : x.h);
  };
  for (std::size_t k = 0; k < all.size(); ++k) {
    // 0.8 of the smaller spacing, and at least 0.55 h in 3D, 0.5 h in 2D: the spacing alone let
    // a finer level's points crowd a coarser one's, edges below h/2 (11-13% of the edges on the
    // rotated MOSFET and FinFET graded from the feature size); 0.6 h in 3D and 0.55 h in 2D began
    // to leave holes (edges above 1.5 h), docs/benchmarks.md thirty-seventh part
    if (ok[k] == 1 && free_of(all[k].q, all[k], D == 3 ? 0.55 : 0.5)) take(all[k].q, all[k], all[k].off);
  }
  // the points moved off a face by graded_lift, taken in candidate order when band_gap h from
  // every point taken, before the band's
  for (std::size_t k = 0; k < all.size(); ++k)
    if (ok[k] == 3 && free_of(moved[k], all[k], band_gap))
      take(moved[k], all[k], all[k].off + std::sqrt(squared_distance(moved[k], all[k].q)) * (1 + 1e-9));
  // the band next to the boundary where h is the global size (modules/placement/README.md, step 4,
  // as the uniform lattice): a candidate dropped as too near a face, moved `band_lift` d off it,
  // taken in candidate order when clear, in a segment and band_gap h from every point taken
  for (std::size_t k = 0; k < all.size(); ++k)
    if (ok[k] == 2 && free_of(moved[k], all[k], band_gap))  // moved at most band_lift d
      take(moved[k], all[k], all[k].off + band_lift * std::ldexp(d0, -all[k].level) * (1 + 1e-9));
  return out;
}

template std::vector<point2> place_points<2>(const size_field<2>&, const aabb<2>&, const placement<2>&, unsigned, std::vector<double>*);
template std::vector<point2> place_points<2>(const std::function<double(const point2&, int, double)>&, double, const aabb<2>&,
                                             const placement<2>&, unsigned, double, bool, double, double, std::vector<double>*);
template std::vector<point3> place_points<3>(const std::function<double(const point3&, int, double)>&, double, const aabb<3>&,
                                             const placement<3>&, unsigned, double, bool, double, double, std::vector<double>*);
template std::vector<point3> place_points<3>(const size_field<3>&, const aabb<3>&, const placement<3>&, unsigned, std::vector<double>*);

}  // namespace gsse::sizing
