#include "gsse/refinement/refinement.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <set>
#include <span>
#include <stdexcept>
#include <tuple>

#include "gsse/geometry/circumcentre.hpp"
#include "gsse/geometry/hash_grid.hpp"
#include "gsse/geometry/predicates.hpp"
#include "gsse/sizing/box_tree.hpp"
#include "gsse/traversal/for_each.hpp"

namespace gsse::refinement {

double ratio_bound(std::size_t dimension, double bound) {
  if (dimension == 2) {
    const double angle = bound > 0 ? bound : default_angle2;
    if (!(angle > 0 && angle <= max_angle2))
      throw std::invalid_argument("quality: the 2D bound is a smallest angle in degrees, in (0, " +
                                  std::to_string(max_angle2) + "]");
    return 1 / (2 * std::sin(angle * std::numbers::pi / 180));
  }
  const double ratio = bound > 0 ? bound : default_ratio3;
  if (!(ratio >= min_ratio3))
    throw std::invalid_argument("quality: the 3D bound is a radius-edge ratio of at least " + std::to_string(min_ratio3));
  return ratio;
}

namespace {

template <std::size_t D>
using cell_t = std::array<vertex_id, D + 1>;

template <std::size_t D>
struct candidate {
  point<D> c;
  double r;
  std::uint32_t first, count;  // its encroached faces, in the chunk's face list
  bool shape;                  // above the shape bound (else only too large for the size field)
};

/// Circumcentre and circumradius of a cell; false if it is flat in double precision.
template <std::size_t D>
bool circumball(const std::vector<point<D>>& p, const cell_t<D>& c, point<D>& at, double& r) {
  if constexpr (D == 2) {
    double det;
    const point2 off = geometry::plane_circumcentre_offset(p[c[1]] - p[c[0]], p[c[2]] - p[c[0]], det);
    if (det == 0) return false;
    at = p[c[0]] + off;
    r = std::sqrt(dot(off, off));
  } else {
    double det;
    const point3 off = geometry::tetrahedron_circumcentre_offset(p[c[1]] - p[c[0]], p[c[2]] - p[c[0]], p[c[3]] - p[c[0]], det);
    if (det == 0) return false;
    at = p[c[0]] + off;
    r = std::sqrt(dot(off, off));
  }
  return std::isfinite(r);
}

/// The diametral (2D) or equatorial (3D) ball of a boundary face, as a padded box.
template <std::size_t D>
sizing::aabb<D> face_box(const std::vector<point<D>>& p, const std::array<vertex_id, D>& F) {
  point<D> c;
  double r;
  if constexpr (D == 2) {
    c = 0.5 * (p[F[0]] + p[F[1]]);
    r = 0.5 * distance(p[F[0]], p[F[1]]);
  } else {
    const point3 u = p[F[1]] - p[F[0]], v = p[F[2]] - p[F[0]], n = cross(u, v);
    const point3 off = geometry::triangle_circumcentre_offset(u, v, n, dot(n, n));
    c = p[F[0]] + off;
    r = std::sqrt(dot(off, off));
  }
  r = r * (1 + 1e-9) + 1e-300;
  sizing::aabb<D> b;
  for (std::size_t k = 0; k < D; ++k) b.lo[k] = c[k] - r, b.hi[k] = c[k] + r;
  return b;
}

/// Points accepted in a round, found by distance: one hash grid per power-of-two radius in use,
/// so that a query of radius r visits at most 3^D cells whatever the grading.
template <std::size_t D>
class accepted_points {
 public:
  accepted_points(const point<D>& origin, const std::set<int>& levels) {
    for (int k : levels) grids_.emplace(k, hash_grid<D>(origin, std::ldexp(1.0, k)));
  }
  static int level(double r) { return std::ilogb(r) + 1; }
  bool any_within(const point<D>& c, double r) const {
    const auto& g = grids_.at(level(r));
    point<D> lo, hi;
    for (std::size_t k = 0; k < D; ++k) lo[k] = c[k] - r, hi[k] = c[k] + r;
    return !g.visit(lo, hi, [&](std::uint32_t i) { return !(squared_distance(points_[i], c) < r * r); });
  }
  void add(const point<D>& c) {
    const auto i = static_cast<std::uint32_t>(points_.size());
    points_.push_back(c);
    for (auto& [k, g] : grids_) g.insert(i, c);
  }
  std::vector<point<D>>& points() { return points_; }

 private:
  std::map<int, hash_grid<D>> grids_;
  std::vector<point<D>> points_;
};

}  // namespace

/// Smallest and largest dihedral angle of a tetrahedron, degrees.
std::pair<double, double> dihedral_range(const std::vector<point3>& p, const std::array<vertex_id, 4>& c) {
  double lo = 180, hi = 0;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j) {
      std::size_t k = 0;
      while (k == i || k == j) ++k;
      const std::size_t l = 6 - i - j - k;
      const point3 e = p[c[j]] - p[c[i]];
      const point3 n1 = cross(e, p[c[k]] - p[c[i]]), n2 = cross(e, p[c[l]] - p[c[i]]);
      const double cosv = dot(n1, n2) / std::sqrt(dot(n1, n1) * dot(n2, n2));
      const double a = std::acos(std::clamp(cosv, -1.0, 1.0)) * 180 / std::numbers::pi;
      lo = std::min(lo, a), hi = std::max(hi, a);
    }
  return {lo, hi};
}

template <std::size_t D>
plan<D> plan_round(const domain<D>& d, const conformer::boundary<D>& b, double bound, unsigned threads,
                   const std::function<double(const point<D>&)>& size, double sliver, const conformer::labelling* l) {
  plan<D> out;
  const auto& bp = b.points;
  std::vector<sizing::aabb<D>> boxes(b.faces.size());
  for (std::size_t f = 0; f < b.faces.size(); ++f) boxes[f] = face_box(bp, b.faces[f]);
  const sizing::box_tree<D> tree(std::move(boxes), std::vector<double>(b.faces.size(), 0.0));
  // the cells in chunks, segment by segment: candidates are found in parallel and merged in
  // chunk order (deterministic)
  struct chunk {
    std::span<const cell_t<D>> cells;
  };
  constexpr std::size_t piece = 4096;
  std::vector<chunk> chunks;
  for (const auto& s : d.segments()) {
    const auto cells = s.cell_data();
    for (std::size_t a = 0; a < cells.size(); a += piece) chunks.push_back({cells.subspan(a, std::min(piece, cells.size() - a))});
  }
  std::vector<std::vector<candidate<D>>> found(chunks.size());
  std::vector<std::vector<std::uint32_t>> faces(chunks.size());
  std::vector<std::size_t> ids(chunks.size());
  std::iota(ids.begin(), ids.end(), std::size_t{0});
  const auto& p = d.points();
  for_each(execution::par(threads), ids, [&](std::size_t k) {
    for (const auto& c : chunks[k].cells) {
      double shortest = 1e300;
      std::size_t si = 0, sj = 1;
      for (std::size_t i = 0; i <= D; ++i)
        for (std::size_t j = i + 1; j <= D; ++j)
          if (const double l2 = squared_distance(p[c[i]], p[c[j]]); l2 < shortest) shortest = l2, si = i, sj = j;
      point<D> at;
      double r;
      if (!circumball(p, c, at, r)) continue;
      bool bad_shape = r > bound * std::sqrt(shortest);
      if constexpr (D == 3) {
        if (!bad_shape && sliver > 0) {
          const auto [lo, hi] = dihedral_range(p, c);
          bad_shape = lo < sliver || hi > 180 - 2 * sliver;
        }
      }
      if (!bad_shape && !(size && 3 * r * r > size(at) * size(at))) continue;
      if (D == 2 && bad_shape) {
        // Ungor's off-centre: on the shortest edge's bisector, no farther from it than the apex
        // of the triangle on that edge with the bound's angle (so that triangle is not bad), if
        // the circumcentre is farther (fewer points)
        const point<D> m = 0.5 * (p[c[si]] + p[c[sj]]);
        const double half = 0.5 * std::sqrt(shortest), far = distance(m, at);
        const double reach = half * (2 * bound + std::sqrt(4 * bound * bound - 1));  // cot(theta/2) * half
        if (far > reach && far > 0) {
          at = m + (reach / far) * (at - m);
          r = distance(at, p[c[si]]);
        }
      }
      candidate<D> x{at, r, static_cast<std::uint32_t>(faces[k].size()), 0, bad_shape};
      // boundary faces whose closed ball holds the circumcentre (exact; a tie counts)
      tree.visit([&](const sizing::aabb<D>& box) { return box.contains(at); },
                 [&](std::uint32_t f) {
                   const auto& F = b.faces[f];
                   int s;
                   if constexpr (D == 2)
                     s = geometry::in_diametral(bp[F[0]], bp[F[1]], at);
                   else
                     s = geometry::in_equatorial(bp[F[0]], bp[F[1]], bp[F[2]], at);
                   if (s >= 0) faces[k].push_back(f);
                   return true;
                 });
      x.count = static_cast<std::uint32_t>(faces[k].size()) - x.first;
      found[k].push_back(x);
    }
  }, [&](std::size_t k) { return static_cast<double>(chunks[k].cells.size()); });
  // in order of decreasing circumradius (ties: by position), each at least its circumradius from
  // the points taken before it
  struct ref {
    std::uint32_t chunk, index;
  };
  std::vector<ref> all;
  std::set<int> levels;
  for (std::uint32_t k = 0; k < found.size(); ++k)
    for (std::uint32_t i = 0; i < found[k].size(); ++i) {
      all.push_back({k, i});
      if (found[k][i].count == 0) levels.insert(accepted_points<D>::level(found[k][i].r));
    }
  out.bad = static_cast<std::size_t>(std::count_if(all.begin(), all.end(), [&](const ref& x) { return found[x.chunk][x.index].shape; }));
  out.large = all.size() - out.bad;
  auto at = [&](const ref& x) -> const candidate<D>& { return found[x.chunk][x.index]; };
  std::sort(all.begin(), all.end(), [&](const ref& x, const ref& y) {
    const auto &a = at(x), &c = at(y);
    if (a.r != c.r) return a.r > c.r;
    return lex_less(a.c, c.c);
  });
  std::set<std::size_t> split;
  accepted_points<D> taken(p.empty() ? point<D>{} : p[0], levels);
  for (const auto& x : all) {
    const auto& c = at(x);
    if (c.count > 0) {
      for (std::uint32_t j = 0; j < c.count; ++j) split.insert(faces[x.chunk][c.first + j]);
      continue;
    }
    if (taken.any_within(c.c, c.r)) continue;
    taken.add(c.c);
  }
  out.add = std::move(taken.points());
  // a circumcentre outside every segment that encroaches no subfacet (it may lie in a subsegment's
  // ball only, or outside by rounding) is not inserted: the conformer would project a point from
  // the outside, which it never sees otherwise. Its element stays for a later round
  if (l && !out.add.empty()) {
    const auto where = conformer::locate(b, *l, out.add);
    std::vector<point<D>> inside;
    for (std::size_t k = 0; k < out.add.size(); ++k)
      if (where[k] != conformer::exterior) inside.push_back(out.add[k]);
    out.outside = out.add.size() - inside.size();
    out.add = std::move(inside);
  }
  out.split.assign(split.begin(), split.end());
  return out;
}

template <std::size_t D>
domain<D> refine(const plc<D>& p, conformer::boundary<D>& b, conformer::labelling& l, domain<D> d,
                 const conformer::options& co, const options& o, const mesher<D>& mesh, stats& st) {
  const double bound = ratio_bound(D, o.bound);
  for (;;) {
    std::function<double(const point<D>&)> size;
    if constexpr (D == 2)
      size = o.size2;
    else
      size = o.size3;
    auto clock = std::chrono::steady_clock::now();
    auto lap = [&clock]() {
      const auto now = std::chrono::steady_clock::now();
      const double s = std::chrono::duration<double>(now - clock).count();
      clock = now;
      return s;
    };
    auto pl = plan_round(d, b, bound, o.threads, size, D == 3 ? o.sliver_angle : 0.0, &l);
    st.plan_seconds += lap();
    st.outside += pl.outside;
    st.bad_left = pl.bad;
    st.excepted = pl.excepted;
    if (pl.bad == pl.excepted && pl.large == 0) {
      st.converged = true;
      break;
    }
    if (st.rounds >= (o.max_rounds ? o.max_rounds : D == 2 ? 250 : 60) || d.points().size() >= o.max_points || (pl.add.empty() && pl.split.empty())) break;
    ++st.rounds;
    st.inserted += pl.add.size();
    st.split_requests += pl.split.size();
    if (o.progress)
      o.progress("quality round " + std::to_string(st.rounds) + ": " + std::to_string(pl.bad) + " elements above the bound, " +
                 std::to_string(pl.add.size()) + " circumcentres, " + std::to_string(pl.split.size()) + " boundary splits");
    // a round that fails (an error from the conformer, the labelling or the mesher) leaves the
    // last good mesh, its boundary and labels as they were; the failure is reported, not hidden
    try {
      auto b2 = conformer::resume(p, b, pl.add, pl.split, co);
      st.conform_seconds += lap();
      auto l2 = conformer::label(b2, p, o.threads);
      st.label_seconds += lap();
      auto d2 = mesh(b2, l2);
      st.mesh_seconds += lap();
      b = std::move(b2), l = std::move(l2), d = std::move(d2);
    } catch (const std::exception& e) {
      st.failure = "round " + std::to_string(st.rounds) + ": " + e.what();
      --st.rounds;
      st.inserted -= pl.add.size();
      st.split_requests -= pl.split.size();
      break;
    }
  }
  return d;
}

template plan<2> plan_round<2>(const domain<2>&, const conformer::boundary<2>&, double, unsigned,
                               const std::function<double(const point2&)>&, double, const conformer::labelling*);
template plan<3> plan_round<3>(const domain<3>&, const conformer::boundary<3>&, double, unsigned,
                               const std::function<double(const point3&)>&, double, const conformer::labelling*);
template domain<2> refine<2>(const plc<2>&, conformer::boundary<2>&, conformer::labelling&, domain<2>, const conformer::options&,
                             const options&, const mesher<2>&, stats&);
template domain<3> refine<3>(const plc<3>&, conformer::boundary<3>&, conformer::labelling&, domain<3>, const conformer::options&,
                             const options&, const mesher<3>&, stats&);

}  // namespace gsse::refinement
