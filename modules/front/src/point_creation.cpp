#include "gsse/front/point_creation.hpp"
#include "gsse/geometry/circumcentre.hpp"
#include "gsse/geometry/exact_ball.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "gsse/front/gift_wrap.hpp"
#include "gsse/front/kernels.hpp"
#include "gsse/front/point_overlay.hpp"
#include "gsse/geometry/predicates.hpp"
#include "gsse/rules/front_rule.hpp"

namespace gsse::front {

creation_stats& creation_stats::operator+=(const creation_stats& o) {
  too_far += o.too_far;
  created += o.created;
  no_rule += o.no_rule;
  outside += o.outside;
  encroaching += o.encroaching;
  in_circumball += o.in_circumball;
  not_needed += o.not_needed;
  return *this;
}

namespace {

/// Items with bounding boxes in a dense uniform grid of linked lists; an item covering more than
/// `max_span` grid cells goes to a list visited by every query. Queries may see an item twice.
template <std::size_t D>
class box_buckets {
 public:
  box_buckets(const point<D>& lo, const point<D>& hi, double cell, std::size_t max_cells, std::size_t max_span = 64)
      : lo_(lo), max_span_(max_span) {
    if (!(cell > 0) || !std::isfinite(cell)) cell = 1;
    for (;;) {
      std::size_t total = 1;
      for (std::size_t a = 0; a < D; ++a) {
        dims_[a] = static_cast<long>((hi[a] - lo[a]) / cell) + 1;
        total *= static_cast<std::size_t>(dims_[a]);
      }
      if (total <= max_cells) {
        head_.assign(total, -1);
        break;
      }
      cell *= 1.5;
    }
    inv_ = 1 / cell;
  }

  void insert(std::uint32_t item, const point<D>& blo, const point<D>& bhi) {
    std::array<long, D> a, b;
    std::size_t span = 1;
    bool finite = true;
    for (std::size_t k = 0; k < D; ++k) {
      finite &= std::isfinite(blo[k]) && std::isfinite(bhi[k]);
      a[k] = index(blo[k], k);
      b[k] = index(bhi[k], k);
      span *= static_cast<std::size_t>(b[k] - a[k] + 1);
    }
    if (!finite || span > max_span_) {
      large_.push_back(item);
      return;
    }
    for_cells(a, b, [&](std::size_t c) {
      next_.push_back(head_[c]);
      head_[c] = static_cast<std::int32_t>(items_.size());
      items_.push_back(item);
      return true;
    });
  }

  /// f(item) for the items whose cells overlap [qlo, qhi]; stops when f returns false.
  template <class F>
  bool visit(const point<D>& qlo, const point<D>& qhi, F&& f) const {
    for (auto item : large_)
      if (!f(item)) return false;
    std::array<long, D> a, b;
    for (std::size_t k = 0; k < D; ++k) a[k] = index(qlo[k], k), b[k] = index(qhi[k], k);
    return for_cells(a, b, [&](std::size_t c) {
      for (auto e = head_[c]; e >= 0; e = next_[static_cast<std::size_t>(e)])
        if (!f(items_[static_cast<std::size_t>(e)])) return false;
      return true;
    });
  }

 private:
  long index(double x, std::size_t k) const {
    const double t = std::floor((x - lo_[k]) * inv_);
    if (!(t > 0)) return 0;  // also NaN
    return std::min(static_cast<long>(std::min(t, 1e15)), dims_[k] - 1);
  }
  template <class G>
  bool for_cells(const std::array<long, D>& a, const std::array<long, D>& b, G&& g) const {
    std::array<long, D> i = a;
    for (;;) {
      std::size_t lin = 0;
      for (std::size_t k = D; k-- > 0;) lin = lin * static_cast<std::size_t>(dims_[k]) + static_cast<std::size_t>(i[k]);
      if (!g(lin)) return false;
      std::size_t k = 0;
      for (; k < D; ++k) {
        if (++i[k] <= b[k]) break;
        i[k] = a[k];
      }
      if (k == D) return true;
    }
  }

  point<D> lo_;
  std::size_t max_span_;
  double inv_ = 1;
  std::array<long, D> dims_{};
  std::vector<std::int32_t> head_, next_;
  std::vector<std::uint32_t> items_, large_;
};

/// Circumcentre and radius of a simplex's circumball (a triangle's in its plane in 3D), in
/// double, padded so the ball surely contains the exact one; radius +inf when unreliable.
template <std::size_t D, std::size_t N>
std::pair<point<D>, double> padded_ball(const std::array<const point<D>*, N>& s) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const point<D>& a = *s[0];
  point<D> c{};
  double rel = 1, longest = 0;
  if constexpr (N == 2) {  // an edge: its midpoint ball
    c = 0.5 * (a + *s[1]);
    rel = 4 * eps;
    longest = distance(a, *s[1]);
  } else if constexpr (D == 2) {  // triangle in 2D
    const point2 u = *s[1] - a, v = *s[2] - a;
    double d;
    const point2 off = geometry::plane_circumcentre_offset(u, v, d);
    rel = d == 0 ? 1 : std::sqrt(dot(u, u) * dot(v, v)) / std::abs(d) * eps * 64;
    c = a + off;
    longest = std::sqrt(std::max(dot(u, u), dot(v, v)));
  } else if constexpr (N == 3) {  // triangle in 3D
    const point3 u = *s[1] - a, v = *s[2] - a, n = cross(u, v);
    const double nn = dot(n, n);
    rel = nn == 0 ? 1 : dot(u, u) * dot(v, v) / nn * eps * 64;
    c = a + geometry::triangle_circumcentre_offset(u, v, n, nn);
    longest = std::sqrt(std::max(dot(u, u), dot(v, v)));
  } else {  // tetrahedron
    const point3 u = *s[1] - a, v = *s[2] - a, w = *s[3] - a;
    double det;
    const point3 off = geometry::tetrahedron_circumcentre_offset(u, v, w, det);
    rel = det == 0 ? 1 : std::sqrt(dot(u, u) * dot(v, v) * dot(w, w)) / std::abs(det) * eps * 64;
    c = a + off;
    longest = std::sqrt(std::max({dot(u, u), dot(v, v), dot(w, w)}));
  }
  if (rel > 1e-6 || !is_finite(c)) return {a, std::numeric_limits<double>::infinity()};
  return {c, distance(c, a) * (1 + 4 * rel + 1e-12) + 4 * rel * longest + 1e-300};
}

template <std::size_t D>
std::pair<point<D>, point<D>> ball_box(const std::pair<point<D>, double>& b) {
  point<D> lo, hi;
  for (std::size_t k = 0; k < D; ++k) lo[k] = b.first[k] - b.second, hi[k] = b.first[k] + b.second;
  return {lo, hi};
}

}  // namespace

template <std::size_t D>
struct boundary_faces<D>::impl {
  std::span<const point<D>> p;
  std::vector<std::array<vertex_id, D>> faces;
  std::vector<vertex_id> apex;                     // 3D, per face: its apex if kept as a Delaunay face, or none
  std::vector<std::pair<point<D>, point<D>>> box;  // of each face itself, for crossings
  box_buckets<D> balls, boxes;                     // diametral-ball boxes; face boxes

  static point<D> lower(std::span<const point<D>> p) {
    point<D> lo = p.empty() ? point<D>{} : p[0];
    for (const auto& q : p)
      for (std::size_t k = 0; k < D; ++k) lo[k] = std::min(lo[k], q[k]);
    return lo;
  }
  static point<D> upper(std::span<const point<D>> p) {
    point<D> hi = p.empty() ? point<D>{} : p[0];
    for (const auto& q : p)
      for (std::size_t k = 0; k < D; ++k) hi[k] = std::max(hi[k], q[k]);
    return hi;
  }
  static double mean_size(std::span<const point<D>> p, std::span<const std::array<vertex_id, D>> f) {
    double s = 0;
    for (const auto& F : f) s += distance(p[F[0]], p[F[1]]);
    return f.empty() ? 1 : 2 * s / static_cast<double>(f.size());
  }

  impl(std::span<const point<D>> pts, std::span<const std::array<vertex_id, D>> fs, std::span<const vertex_id> ax)
      : p(pts),
        faces(fs.begin(), fs.end()),
        apex(ax.begin(), ax.end()),
        balls(lower(pts), upper(pts), mean_size(pts, fs), 4 * fs.size() + 16),
        boxes(lower(pts), upper(pts), mean_size(pts, fs), 4 * fs.size() + 16) {
    box.reserve(faces.size());
    for (std::uint32_t f = 0; f < faces.size(); ++f) {
      std::array<const point<D>*, D> s;
      point<D> lo = p[faces[f][0]], hi = lo;
      for (std::size_t k = 0; k < D; ++k) {
        s[k] = &p[faces[f][k]];
        for (std::size_t a = 0; a < D; ++a) lo[a] = std::min(lo[a], (*s[k])[a]), hi[a] = std::max(hi[a], (*s[k])[a]);
      }
      box.emplace_back(lo, hi);
      boxes.insert(f, lo, hi);
      auto [blo, bhi] = ball_box<D>(padded_ball<D, D>(s));
      if constexpr (D == 3)
        if (f < apex.size() && apex[f] != no_vertex) {
          // a kept face: the sphere through it and its apex too (no bound: asked by every query)
          point3 sc;
          double sr = 0;
          if (geometry::circumball_bound(p[faces[f][0]], p[faces[f][1]], p[faces[f][2]], p[apex[f]], sc, sr))
            for (std::size_t k = 0; k < 3; ++k) blo[k] = std::min(blo[k], sc[k] - sr), bhi[k] = std::max(bhi[k], sc[k] + sr);
          else
            for (std::size_t k = 0; k < 3; ++k) blo[k] = -std::numeric_limits<double>::infinity(), bhi[k] = std::numeric_limits<double>::infinity();
        }
      balls.insert(f, blo, bhi);
    }
  }
};

template <std::size_t D>
boundary_faces<D>::boundary_faces(std::span<const point<D>> pts, std::span<const std::array<vertex_id, D>> faces,
                                  std::span<const vertex_id> apex)
    : impl_(new impl(pts, faces, apex)) {}
template <std::size_t D>
boundary_faces<D>::~boundary_faces() {
  delete impl_;
}

template <std::size_t D>
bool boundary_faces<D>::encroached_by(const point<D>& q) const {
  const auto& m = *impl_;
  return !m.balls.visit(q, q, [&](std::uint32_t f) {
    const auto& F = m.faces[f];
    int in;
    if constexpr (D == 2) {
      in = geometry::in_diametral(m.p[F[0]], m.p[F[1]], q);
    } else {
      if (f < m.apex.size() && m.apex[f] != no_vertex) return !geometry::breaks_face_with_apex(m.p[F[0]], m.p[F[1]], m.p[F[2]], m.p[m.apex[f]], q);
      in = geometry::in_equatorial(m.p[F[0]], m.p[F[1]], m.p[F[2]], q);
    }
    return in < 0;  // closed ball: on the sphere counts as encroaching
  });
}

template <std::size_t D>
bool boundary_faces<D>::crossed(const point<D>& s, const point<D>& q, const std::array<vertex_id, D>& except) const {
  const auto& m = *impl_;
  point<D> lo, hi;
  for (std::size_t k = 0; k < D; ++k) lo[k] = std::min(s[k], q[k]), hi[k] = std::max(s[k], q[k]);
  auto key = except;
  std::sort(key.begin(), key.end());
  return !m.boxes.visit(lo, hi, [&](std::uint32_t f) {
    const auto& [flo, fhi] = m.box[f];
    for (std::size_t k = 0; k < D; ++k)
      if (flo[k] > hi[k] || fhi[k] < lo[k]) return true;
    auto F = m.faces[f];
    auto sorted = F;
    std::sort(sorted.begin(), sorted.end());
    if (sorted == key) return true;
    // closed segment-simplex intersection from exact orientations; coplanar (collinear) cases
    // with overlapping boxes count as crossing, which only forgoes a point
    if constexpr (D == 2) {
      const point2 &a = m.p[F[0]], &b = m.p[F[1]];
      const int o1 = geometry::orient2d(a, b, s), o2 = geometry::orient2d(a, b, q);
      const int o3 = geometry::orient2d(s, q, a), o4 = geometry::orient2d(s, q, b);
      if (o1 * o2 > 0 || o3 * o4 > 0) return true;
      return false;
    } else {
      const point3 &a = m.p[F[0]], &b = m.p[F[1]], &c = m.p[F[2]];
      const int os = geometry::orient3d(a, b, c, s), oq = geometry::orient3d(a, b, c, q);
      if (os * oq > 0) return true;
      if (os == 0 && oq == 0) return false;
      const int d1 = geometry::orient3d(s, q, a, b), d2 = geometry::orient3d(s, q, b, c),
                d3 = geometry::orient3d(s, q, c, a);
      const bool all_nonneg = d1 >= 0 && d2 >= 0 && d3 >= 0, all_nonpos = d1 <= 0 && d2 <= 0 && d3 <= 0;
      return !(all_nonneg || all_nonpos);
    }
  });
}

namespace {

/// The creation step of one region: state shared by the calls of the gift wrapper's hook.
template <std::size_t D, class K>
class creator {
 public:
  using face = std::array<vertex_id, D>;
  using cell = std::array<vertex_id, D + 1>;

  creator(std::vector<point<D>>& pts, K& k, const point_grid<D>& grid, point_overlay<D>& overlay,
          const boundary_faces<D>& faces, const creation_options& o, creation_stats& st)
      : pts_(pts),
        k_(k),
        grid_(grid),
        overlay_(overlay),
        faces_(faces),
        o_(o),
        st_(st),
        balls_(lower(grid), upper(grid), o.h, 8 * grid.size() + 64, 512),
        eligible_(o.rules->eligible(std::numeric_limits<int>::max())) {
    // how far from a face's vertex the rules look, in units of h (rules::reach): the cloud is
    // gathered within that of the face's vertices (a hair more than what rules::prepare maps, so
    // that nothing it maps is missing; until 2026-12-03 every rule vertex's reach plus h / 2, whose
    // extra points rules::prepare now leaves at infinity, unmapped)
    for (const auto* r : eligible_) zones_.push_back(rules::zone_of(*r)), unit_reach_ = std::max(unit_reach_, rules::reach(*r));
    reach_ = unit_reach_ * (1 + 1e-5);
  }

  using result = typename gift_wrapper<K>::creation;

  result operator()(const face& f, vertex_id x, const std::vector<cell>& cells) {
    index_cells(cells);
    if (st_.created >= o_.max_points) return result::fine;
    std::array<const point<D>*, D + 1> s;
    for (std::size_t i = 0; i < D; ++i) s[i] = &pts_[f[i]];
    s[D] = &pts_[x];
    if (const auto b = padded_ball<D, D + 1>(s); b.second <= o_.too_far * o_.h) return result::fine;
    ++st_.too_far;

    // the existing points near the face: the rules' free zones and matched points see these
    point<D> lo = pts_[f[0]], hi = lo, centroid{};
    for (std::size_t i = 0; i < D; ++i) {
      centroid = centroid + (1.0 / D) * pts_[f[i]];
      for (std::size_t a = 0; a < D; ++a) lo[a] = std::min(lo[a], pts_[f[i]][a]), hi[a] = std::max(hi[a], pts_[f[i]][a]);
    }
    for (std::size_t a = 0; a < D; ++a) lo[a] -= reach_ * o_.h, hi[a] += reach_ * o_.h;
    cloud_.clear();
    double radius = 0;  // of a ball around the centroid holding everything the rules look at
    for (std::size_t i = 0; i < D; ++i) radius = std::max(radius, distance(centroid, pts_[f[i]]));
    radius += reach_ * o_.h;
    auto gather = [&](vertex_id, const std::array<double, D>& q) {
      if (squared_distance(q, centroid) <= radius * radius) cloud_.push_back(q);
      return true;
    };
    grid_.visit_box(lo, hi, gather);
    overlay_.visit_box(lo, hi, gather);

    // the face in each of its rotations (same orientation), each mapped to its unit frame once
    // for all the rules tried on it
    constexpr std::size_t rotations = D == 3 ? 3 : 1;
    std::array<rules::front_frame<D>, rotations> frames;
    for (std::size_t rot = 0; rot < rotations; ++rot) {
      std::array<point<D>, D> base;
      for (std::size_t i = 0; i < D; ++i) base[i] = pts_[f[(i + rot) % D]];
      frames[rot] = rules::prepare(std::span<const point<D>, D>(base), std::span<const point<D>>(cloud_), o_.h, unit_reach_);
    }
    bool any_accepted = false;
    for (std::size_t ri = 0; ri < eligible_.size(); ++ri) {
      const auto* r = eligible_[ri];
      // the best fit over the rotations wins
      rules::front_result<D> best;
      bool found = false;
      for (const auto& frame : frames) {
        auto res = rules::apply(*r, zones_[ri], frame);
        if (res && (!found || res.error < best.error)) best = std::move(res), found = true;
      }
      if (!found) continue;
      any_accepted = true;
      const auto created = best.created(*r);
      if (created.empty()) {
        ++st_.not_needed;
        return result::fine;
      }
      if (!admissible(created, f, centroid)) continue;
      for (const auto& q : created) {
        const auto id = static_cast<vertex_id>(pts_.size());
        pts_.push_back(q);
        overlay_.insert(id, q);
        ++st_.created;
      }
      k_.p = std::span<const point<D>>(pts_);
      return result::created;
    }
    if (!any_accepted) ++st_.no_rule;
    return result::declined;
  }

 private:
  static point<D> lower(const point_grid<D>& g) { return g.lower(); }
  static point<D> upper(const point_grid<D>& g) { return g.upper(); }

  bool admissible(const std::vector<point<D>>& created, const face& f, const point<D>& centroid) {
    for (const auto& q : created) {
      if (!is_finite(q) || faces_.crossed(centroid, q, f)) {
        ++st_.outside;
        return false;
      }
      if (faces_.encroached_by(q)) {
        ++st_.encroaching;
        return false;
      }
      if (in_some_circumball(q)) {
        ++st_.in_circumball;
        return false;
      }
    }
    return true;
  }

  void index_cells(const std::vector<cell>& cells) {
    for (; indexed_ < cells.size(); ++indexed_) {
      std::array<const point<D>*, D + 1> s;
      for (std::size_t i = 0; i <= D; ++i) s[i] = &pts_[cells[indexed_][i]];
      const auto b = padded_ball<D, D + 1>(s);
      cell_balls_.push_back(b);
      const auto [lo, hi] = ball_box<D>(b);
      balls_.insert(static_cast<std::uint32_t>(indexed_), lo, hi);
    }
    cells_ = &cells;
  }

  bool in_some_circumball(const point<D>& q) const {
    return !balls_.visit(q, q, [&](std::uint32_t c) {
      const auto& [centre, r] = cell_balls_[c];
      if (std::isfinite(r) && squared_distance(centre, q) > r * r) return true;
      const auto& C = (*cells_)[c];
      int in;
      if constexpr (D == 2)
        in = geometry::in_circle_perturbed(pts_[C[0]], pts_[C[1]], pts_[C[2]], q);
      else
        in = geometry::in_sphere_perturbed(pts_[C[0]], pts_[C[1]], pts_[C[2]], pts_[C[3]], q);
      return in < 0;
    });
  }

  std::vector<point<D>>& pts_;
  K& k_;
  const point_grid<D>& grid_;
  point_overlay<D>& overlay_;
  const boundary_faces<D>& faces_;
  const creation_options& o_;
  creation_stats& st_;
  box_buckets<D> balls_;
  std::vector<std::pair<point<D>, double>> cell_balls_;
  const std::vector<cell>* cells_ = nullptr;
  std::size_t indexed_ = 0;
  std::vector<const rules::front_rule*> eligible_;
  std::vector<std::vector<rules::convex_piece>> zones_;  // each eligible rule's free zone, made ready
  double unit_reach_ = 0;  // the farthest any eligible rule looks from a face's first vertex (rules::reach)
  std::vector<point<D>> cloud_;
  double reach_ = 0;
};

template <std::size_t D, class K>
auto run_creating(std::vector<point<D>>& pts, const point_grid<D>& grid, const boundary_faces<D>& faces,
                  const std::vector<std::array<vertex_id, D>>& boundary, const std::string& label,
                  const creation_options& o, creation_stats* cstats, wrap_stats* stats) {
  if (!o.rules || !(o.h > 0)) throw front_error(label + ": point creation needs front rules and a size h > 0");
  K k{std::span<const point<D>>(pts)};
  point_overlay<D> overlay(grid);
  creation_stats st;
  creator<D, K> make(pts, k, grid, overlay, faces, o, st);
  gift_wrapper<K> w(k, grid);
  w.enable_creation(&overlay, [&](const auto& f, vertex_id x, const auto& cells) { return make(f, x, cells); });
  auto cells = w.run(boundary, label);
  if (cstats) *cstats += st;
  if (stats) *stats += w.stats();
  return cells;
}

}  // namespace

std::vector<std::array<vertex_id, 4>> wrap_creating(std::vector<point3>& pts, const point_grid<3>& grid,
                                                    const boundary_faces<3>& faces,
                                                    const std::vector<std::array<vertex_id, 3>>& boundary,
                                                    const std::string& label, const creation_options& o,
                                                    creation_stats* cstats, wrap_stats* stats) {
  return run_creating<3, volume_kernel>(pts, grid, faces, boundary, label, o, cstats, stats);
}
std::vector<std::array<vertex_id, 3>> wrap_creating(std::vector<point2>& pts, const point_grid<2>& grid,
                                                    const boundary_faces<2>& faces,
                                                    const std::vector<std::array<vertex_id, 2>>& boundary,
                                                    const std::string& label, const creation_options& o,
                                                    creation_stats* cstats, wrap_stats* stats) {
  return run_creating<2, plane_kernel>(pts, grid, faces, boundary, label, o, cstats, stats);
}

template class boundary_faces<2>;
template class boundary_faces<3>;

}  // namespace gsse::front
