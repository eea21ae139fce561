#include "gsse/sizing/size_field.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iomanip>
#include <limits>
#include <mutex>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "gsse/geometry/plane_axes.hpp"
#include "gsse/sizing/distance.hpp"
#include "gsse/traversal/for_each.hpp"

namespace gsse::sizing {

double size_of_measure(double measure, std::size_t dimension) {
  // regular tetrahedron: V = a^3 / (6 sqrt 2); equilateral triangle: A = sqrt(3) a^2 / 4
  if (dimension == 3) return std::cbrt(6 * std::numbers::sqrt2 * measure);
  return std::sqrt(4 * measure / std::numbers::sqrt3);
}

template <std::size_t D>
void add_region_volumes(spec<D>& s, const plc<D>& p) {
  for (const auto& r : p.regions)
    if (r.max_volume > 0) {
      const double h = size_of_measure(r.max_volume, D);
      auto [it, fresh] = s.segment_size.try_emplace(r.number, h);
      if (!fresh) it->second = std::min(it->second, h);
    }
}

template <std::size_t D>
double size_field<D>::background_value(const point<D>& x) const {
  if (!background_) return unbounded;
  const auto& B = *background_;
  double v = unbounded;
  background_cells_.visit([&](const aabb<D>& b) { return b.contains(x); }, [&](std::uint32_t c) {
    const auto& C = B.cells[c];
    // barycentric coordinates by Cramer's rule
    std::array<std::array<double, D>, D> m;
    for (std::size_t i = 0; i < D; ++i)
      for (std::size_t k = 0; k < D; ++k) m[k][i] = B.points[C[i + 1]][k] - B.points[C[0]][k];
    const point<D> r = x - B.points[C[0]];
    std::array<double, D + 1> lam{};
    if constexpr (D == 2) {
      const double det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
      if (det == 0) return true;
      lam[1] = (r[0] * m[1][1] - m[0][1] * r[1]) / det;
      lam[2] = (m[0][0] * r[1] - r[0] * m[1][0]) / det;
    } else {
      auto det3 = [](const std::array<std::array<double, 3>, 3>& a) {
        return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
               a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
      };
      const double det = det3(m);
      if (det == 0) return true;
      for (std::size_t i = 0; i < 3; ++i) {
        auto mi = m;
        for (std::size_t k = 0; k < 3; ++k) mi[k][i] = r[k];
        lam[i + 1] = det3(mi) / det;
      }
    }
    lam[0] = 1;
    for (std::size_t i = 1; i <= D; ++i) lam[0] -= lam[i];
    constexpr double eps = 1e-12;
    for (double t : lam)
      if (t < -eps) return true;
    double s = 0;
    for (std::size_t i = 0; i <= D; ++i) s += std::max(0.0, lam[i]) * B.size[C[i]];
    v = s;
    return false;
  });
  return v;
}

template <std::size_t D>
void size_field<D>::group_faces() {
  // each piece's unit normal, its sign fixed (first clear component positive); pieces whose
  // normal is an axis (or that are degenerate) go in the model's axes. A direction held by at
  // least `least` pieces gets a group of its own (the 15 most held), keyed by the normal rounded
  // to 1e-6: the pieces of one facet, and of facets parallel to it, share it up to rounding
  constexpr std::size_t least = 64, most_groups = 15;
  const std::size_t n = face_pieces_.size();
  using key = std::array<long long, D>;
  std::map<key, std::size_t> held;
  std::map<key, point<D>> normal;  // per direction: its first piece's normal (the group's frame)
  std::vector<key> key_of(n);
  std::vector<char> slanted(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& s = face_pieces_[i];
    point<D> m{};
    if constexpr (D == 3)
      m = cross(s[1] - s[0], s[2] - s[0]);
    else
      m = point<D>{s[0][1] - s[1][1], s[1][0] - s[0][0]};
    const double len = std::sqrt(dot(m, m));
    if (!(len > 0) || !std::isfinite(len)) continue;
    m = (1.0 / len) * m;
    for (std::size_t k = 0; k < D; ++k)
      if (std::abs(m[k]) > 1e-9) {
        if (m[k] < 0) m = -1.0 * m;
        break;
      }
    double largest = 0;
    for (std::size_t k = 0; k < D; ++k) largest = std::max(largest, std::abs(m[k]));
    if (largest >= 1 - 1e-9) continue;
    slanted[i] = 1;
    for (std::size_t k = 0; k < D; ++k) key_of[i][k] = std::llround(m[k] * 1e6);
    ++held[key_of[i]];
    normal.emplace(key_of[i], m);
  }
  std::vector<std::pair<std::size_t, key>> ranked;
  for (const auto& [k, c] : held)
    if (c >= least) ranked.push_back({c, k});
  std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
  if (ranked.size() > most_groups) ranked.resize(most_groups);
  std::map<key, std::size_t> group_of;
  groups_.assign(ranked.size() + 1, face_group{});  // the last: the model's axes
  for (std::size_t g = 0; g < ranked.size(); ++g) group_of[ranked[g].second] = g;
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t g = ranked.size();
    if (slanted[i])
      if (const auto it = group_of.find(key_of[i]); it != group_of.end()) g = it->second;
    groups_[g].items.push_back(static_cast<std::uint32_t>(i));
  }
  // the frames: the normal of the group's first piece last, the others across it
  double scale = 0;
  for (const auto& s : face_pieces_)
    for (const auto& q : s)
      for (std::size_t k = 0; k < D; ++k) scale = std::max(scale, std::abs(q[k]));
  for (std::size_t g = 0; g < ranked.size(); ++g) {
    auto& G = groups_[g];
    const point<D> m = normal.at(ranked[g].second);
    G.turned = true;
    if constexpr (D == 3) {
      const auto across = geometry::plane_axes(m);
      G.axes = {across[0], across[1], m};
    } else {
      G.axes = {point<D>{-m[1], m[0]}, m};
    }
  }
  for (auto& G : groups_) {
    std::vector<aabb<D>> boxes;
    std::vector<double> values;
    boxes.reserve(G.items.size()), values.reserve(G.items.size());
    // a frame's coordinates are dot products with rows of length 1 up to rounding: the boxes
    // padded by far more (1e-12 of the coordinates' magnitude), so that no box distance exceeds
    // a piece's true distance
    const double pad = G.turned ? 1e-12 * scale + 1e-300 : 0.0;
    for (std::uint32_t i : G.items) {
      aabb<D> bx = aabb<D>::empty();
      for (const auto& q : face_pieces_[i]) {
        G.box.add(q);
        point<D> y = q;
        if (G.turned)
          for (std::size_t k = 0; k < D; ++k) y[k] = dot(G.axes[k], q);
        bx.add(y);
      }
      for (std::size_t k = 0; k < D; ++k) bx.lo[k] -= pad, bx.hi[k] += pad;
      boxes.push_back(bx);
      values.push_back(face_values_[i]);
      G.min_value = std::min(G.min_value, face_values_[i]);
    }
    G.tree = box_tree<D>(std::move(boxes), std::move(values));
  }
  std::erase_if(groups_, [](const face_group& G) { return G.items.empty(); });
}

template <std::size_t D>
double size_field<D>::operator()(const point<D>& x) const {
  return capped(x, unbounded);
}

template <std::size_t D>
double size_field<D>::box_terms(const point<D>& x, double v) const {
  for (const auto& b : boxes_) {
    aabb<D> box{b.lo, b.hi};
    v = std::min(v, b.size + (b.grade > 0 ? b.grade - 1 : slope_) * std::sqrt(box.distance2(x)));
  }
  return v;
}

template <std::size_t D>
double size_field<D>::capped(const point<D>& x, double cap) const {
  double v = box_terms(x, std::min(global_, cap));
  // each thread's last winning piece of this field starts its next search (queries come in places
  // near each other: a placement's cubes, a facet's faces); the value found does not depend on it
  thread_local struct {
    const void* field = nullptr;
    std::uint32_t item = 0;
  } last;
  if (last.field != this) last = {this, ~std::uint32_t{0}};
  if (last.item < face_pieces_.size())
    v = std::min(v, face_values_[last.item] + slope_ * std::sqrt(face_distance2<D>(face_pieces_[last.item], x)));
  for (const auto& g : groups_) {
    if (g.min_value + slope_ * std::sqrt(g.box.distance2(x)) >= v) continue;
    point<D> y = x;
    if (g.turned)
      for (std::size_t k = 0; k < D; ++k) y[k] = dot(g.axes[k], x);
    std::uint32_t won = ~std::uint32_t{0};
    const double r = g.tree.graded_min(y, slope_, v, [&](std::uint32_t i, double) { return face_distance2<D>(face_pieces_[g.items[i]], x); }, &won);
    if (r < v && won < g.items.size()) v = r, last.item = g.items[won];
  }
  for (const auto& L : layers_)
    v = L.tree.graded_min(x, L.slope, v, [&](std::uint32_t i, double) { return face_distance2<D>(L.pieces[i], x); });
  if (background_) v = std::min(v, background_value(x));
  return v;
}

template <std::size_t D>
double size_field<D>::exhaustive(const point<D>& x) const {
  double v = box_terms(x, global_);
  for (std::size_t i = 0; i < face_pieces_.size(); ++i) v = std::min(v, face_values_[i] + slope_ * std::sqrt(face_distance2<D>(face_pieces_[i], x)));
  for (const auto& L : layers_)
    for (std::size_t i = 0; i < L.pieces.size(); ++i) v = std::min(v, L.tree.value(static_cast<std::uint32_t>(i)) + L.slope * std::sqrt(face_distance2<D>(L.pieces[i], x)));
  if (background_) v = std::min(v, background_value(x));
  return v;
}

template <std::size_t D>
double size_field<D>::operator()(const point<D>& x, int number) const {
  return capped(x, number, unbounded);
}

template <std::size_t D>
double size_field<D>::capped(const point<D>& x, int number, double cap) const {
  return std::min(capped(x, cap), segment_maximum(number));
}

namespace {

template <std::size_t D>
using simplex_pts = std::array<point<D>, D>;

template <std::size_t D>
point<D> centroid(const simplex_pts<D>& s) {
  point<D> c{};
  for (const auto& q : s) c = c + (1.0 / static_cast<double>(D)) * q;
  return c;
}

template <std::size_t D>
void split(const simplex_pts<D>& s, std::vector<simplex_pts<D>>& out) {
  if constexpr (D == 2) {
    const point2 m = 0.5 * (s[0] + s[1]);
    out.push_back({s[0], m});
    out.push_back({m, s[1]});
  } else {
    const point3 a = 0.5 * (s[1] + s[2]), b = 0.5 * (s[0] + s[2]), c = 0.5 * (s[0] + s[1]);
    out.push_back({s[0], c, b});
    out.push_back({c, s[1], a});
    out.push_back({b, a, s[2]});
    out.push_back({a, b, c});
  }
}

}  // namespace

template <std::size_t D>
struct field_builder {
  // keep: build the field; else only count the pieces against the budget (check_feature_size)
  static size_field<D> run(const boundary_view<D>& b, const spec<D>& s, unsigned threads,
                           const std::function<void(std::size_t, std::size_t)>& progress, bool keep = true);
};

template <std::size_t D>
size_field<D> build(const boundary_view<D>& b, const spec<D>& s, unsigned threads,
                    const std::function<void(std::size_t, std::size_t)>& progress) {
  return field_builder<D>::run(b, s, threads, progress);
}

template <std::size_t D>
void check_feature_size(const boundary_view<D>& b, std::size_t max_pieces, unsigned threads) {
  spec<D> s;  // the local feature size alone
  s.max_pieces = max_pieces;
  field_builder<D>::run(b, s, threads, {}, false);
}

template <std::size_t D>
size_field<D> field_builder<D>::run(const boundary_view<D>& b, const spec<D>& s, unsigned threads,
                                    const std::function<void(std::size_t, std::size_t)>& progress, bool keep) {
  if (!(s.grade > 1)) throw std::invalid_argument("the grade must be above 1");
  size_field<D> f;
  f.slope_ = f.max_slope_ = s.grade - 1;
  for (const auto& bx : s.boxes) {
    if (bx.grade != 0 && !(bx.grade > 1)) throw std::invalid_argument("a refinement box's grade must be above 1");
    if (bx.grade > 0) f.max_slope_ = std::max(f.max_slope_, bx.grade - 1);
  }
  for (const auto& L : s.interfaces) {
    if (L.grade != 0 && !(L.grade > 1)) throw std::invalid_argument("an interface's grade must be above 1");
    if (L.grade > 0) f.max_slope_ = std::max(f.max_slope_, L.grade - 1);
  }
  f.global_ = s.global > 0 ? s.global : unbounded;
  f.segment_size_ = s.segment_size;
  for (const auto& [n, h] : s.segment_size)
    if (!(h > 0) || !std::isfinite(h)) throw std::invalid_argument("segment " + std::to_string(n) + ": the size must be positive");
  f.boxes_ = s.boxes;
  f.background_ = s.background;
  f.minimum_ = f.global_;

  // the model's extent: a floor for the values (features closer than 1e-9 of it are not resolved)
  aabb<D> all = aabb<D>::empty();
  for (const auto& q : b.points) all.add(q);
  const double extent = b.points.empty() ? 1.0 : std::sqrt(squared_distance(all.lo, all.hi));
  const double floor = 1e-9 * extent;

  // incidence of the faces' sources (the conformer's facet regions in 3D, named by their first
  // PLC facet; PLC edges in 2D): sharing a PLC vertex. The vertex sets come from the faces, so a
  // merged region of coplanar facets has the vertices of all its members
  std::size_t nsrc = 0;
  for (auto src : b.face_source) nsrc = std::max<std::size_t>(nsrc, src + 1);
  std::vector<std::vector<vertex_id>> verts(nsrc);
  for (std::size_t k = 0; k < b.faces.size() && k < b.face_source.size(); ++k)
    for (vertex_id v : b.faces[k])
      if (v < b.plc_points) verts[b.face_source[k]].push_back(v);
  for (auto& vs : verts) {
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
  }
  std::vector<std::vector<std::uint32_t>> at_vertex(b.plc_points);
  for (std::uint32_t k = 0; k < nsrc; ++k)
    for (vertex_id v : verts[k])
      if (v < at_vertex.size()) at_vertex[v].push_back(k);
  std::vector<std::vector<std::uint32_t>> touching(nsrc);  // sorted sources sharing a vertex with k
  for (std::uint32_t k = 0; k < nsrc; ++k) {
    for (vertex_id v : verts[k])
      if (v < at_vertex.size()) touching[k].insert(touching[k].end(), at_vertex[v].begin(), at_vertex[v].end());
    touching[k].push_back(k);
    std::sort(touching[k].begin(), touching[k].end());
    touching[k].erase(std::unique(touching[k].begin(), touching[k].end()), touching[k].end());
  }
  auto incident = [&](std::uint32_t x, std::uint32_t y) {
    return std::binary_search(touching[x].begin(), touching[x].end(), y);
  };

  // the faces, for the nearest non-incident face
  const std::size_t nf = b.faces.size();
  auto face_pts = [&](std::size_t k) {
    simplex_pts<D> s2;
    for (std::size_t i = 0; i < D; ++i) s2[i] = b.points[b.faces[k][i]];
    return s2;
  };
  std::vector<aabb<D>> fboxes(nf);
  for (std::size_t k = 0; k < nf; ++k) {
    fboxes[k] = aabb<D>::empty();
    for (const auto& q : face_pts(k)) fboxes[k].add(q);
  }
  const box_tree<D> ftree(fboxes, std::vector<double>(nf, 0.0));

  // the constant part of each face's value: its sides' segment sizes and interface layers
  auto side_value = [&](std::size_t k) {
    double v = unbounded;
    if (k >= b.sides.size()) return v;
    const int n0 = b.sides[k][0], n1 = b.sides[k][1];
    for (int n : {n0, n1})
      if (auto it = s.segment_size.find(n); n != 0 && it != s.segment_size.end()) v = std::min(v, it->second);
    for (const auto& L : s.interfaces)
      if (L.grade == 0 && ((L.a == n0 && L.b == n1) || (L.a == n1 && L.b == n0))) v = std::min(v, L.size);
    return v;
  };

  // per face: pieces subdivided until no larger (circumradius about the centroid) than their
  // value; pieces whose value does not beat the global size are dropped
  const std::size_t max_sources = s.max_pieces;
  std::vector<std::vector<std::pair<simplex_pts<D>, double>>> pieces(nf);
  // per face, the closest face across any of its pieces found (squared distance, where, which):
  // should the pieces overflow, the message names the closest features
  struct closest_across {
    double d2 = unbounded;
    point<D> at{};
    std::uint32_t face = 0;
  };
  std::vector<closest_across> closest(nf);
  std::vector<std::size_t> ids(nf);
  for (std::size_t k = 0; k < nf; ++k) ids[k] = k;
  std::atomic<std::size_t> total{0};
  std::atomic<bool> overflow{false};
  std::atomic<std::size_t> faces_done{0};
  std::mutex progress_lock;
  for_each(execution::par(threads), ids, [&](std::size_t k) {
    const double fixed = side_value(k);
    const std::uint32_t src = k < b.face_source.size() ? b.face_source[k] : 0;
    // Per piece, the face across its parent found nearest (none for the face itself): a child's
    // nearest face across is mostly its parent's, and its distance, taken first, bounds the search
    // from the start (the minimum found is the same up to rounding: the hint is one of the faces
    // the search would qualify, at the same distance, but a face whose closest point rounds an ulp
    // outside its box may be pruned in one visiting order and not another)
    constexpr std::uint32_t no_hint = std::numeric_limits<std::uint32_t>::max();
    // a piece's value (infinite: it binds nowhere the global size does not, dropped), its radius
    // about its centroid, and the face across it found nearest (its children's hint)
    struct evaluation {
      double v, r;
      std::uint32_t found_face;
    };
    auto evaluate = [&](const simplex_pts<D>& piece, std::uint32_t hint) {
      std::uint32_t found_face = no_hint;
      const point<D> c = centroid<D>(piece);
      point<D> normal;
      if constexpr (D == 2)
        normal = {piece[0][1] - piece[1][1], piece[1][0] - piece[0][0]};
      else
        normal = cross(piece[1] - piece[0], piece[2] - piece[0]);
      const double nn = dot(normal, normal);
      double r = 0;
      for (const auto& q : piece) r = std::max(r, std::sqrt(squared_distance(q, c)));
      double v = fixed;
      if (s.feature_size) {
        // nearest face of a source this one does not touch, searched no farther than where the
        // term could still beat the other terms
        const double cap = std::min(v, f.global_);
        double best2 = std::isfinite(cap) ? std::pow(cap / s.feature_factor + r, 2) : unbounded;
        double found2 = unbounded;
        // a face across qualifies if its nearest point lies at least 30 degrees out of this
        // piece's plane (a layer's other side, a gap's other wall), not beside it (the
        // next-but-one facet of a tessellated curved surface)
        auto consider = [&](std::uint32_t g) {
          const point<D> q = face_closest<D>(face_pts(g), c), w = q - c;
          const double d2 = dot(w, w), across = dot(w, normal);
          if (d2 < std::min(found2, best2) && across * across >= 0.25 * d2 * nn) found2 = d2, found_face = g;
        };
        if (hint != no_hint) consider(hint);  // the parent's: not incident either
        // a box whose every point x has |(x - c).n| below 0.49 |x - c| holds no nearest point
        // 30 degrees or more out of this piece's plane (the test below asks 0.5): skipped
        // whole. Without it a curved surface tessellated finely, with nothing across it near
        // (no --size to bound the search), had every piece read every face beside it:
        // occ_chair, occ_hammer, scad_csg, scad_example021 with --grade alone spent minutes
        // here. Only boxes that cannot qualify go: the field is the same
        const double nlen = std::sqrt(nn);
        auto sideways = [&](const aabb<D>& bx) {
          if (!(nlen > 0)) return false;
          double mid = 0, spread = 0;
          for (std::size_t j = 0; j < D; ++j) {
            const double nj = normal[j] / nlen;
            mid += (0.5 * (bx.lo[j] + bx.hi[j]) - c[j]) * nj;
            spread += std::abs(nj) * 0.5 * (bx.hi[j] - bx.lo[j]);
          }
          const double most = std::abs(mid) + spread;
          return most * most < 0.49 * 0.49 * bx.distance2(c);
        };
        // nearer boxes first: a face across found early bounds the rest of the search
        ftree.visit_near(c, [&](const aabb<D>& bx) { return bx.distance2(c) < std::min(best2, found2) && !sideways(bx); },
                    [&](std::uint32_t g) {
                      const std::uint32_t gs = g < b.face_source.size() ? b.face_source[g] : 0;
                      if (!(gs < nsrc && src < nsrc && incident(src, gs))) consider(g);
                      return true;
                    });
        if (std::isfinite(found2)) v = std::min(v, s.feature_factor * std::max(0.0, std::sqrt(found2) - r));
        if (found2 < closest[k].d2) closest[k] = {found2, c, found_face};
      }
      if (!(v < f.global_)) v = unbounded;  // does not bind anywhere the global size does not
      return evaluation{v, r, found_face};
    };
    auto cut = [&](const evaluation& x) { return std::isfinite(x.v) && x.r > std::max(x.v, floor); };
    // pieces of this face and all their descendants counted depth first, on a stack of a few
    // pieces a level (a level at a time holds the widest level: 16 million pieces on a face of a
    // 5e-6 layer): a piece kept counts one, a piece cut its children, as at the levels' ends
    // below. `report(n)` gets the count in batches and returns false to stop (as does an overflow)
    auto count_pieces = [&](std::size_t roots, const auto& root, const auto& report) {
      std::vector<simplex_pts<D>> stack;
      std::vector<std::uint32_t> hints;
      std::size_t counted = 0;
      for (std::size_t r = 0; r < roots; ++r) {
        const auto [first, first_hint] = root(r);
        stack.assign(1, first);
        hints.assign(1, first_hint);
        while (!stack.empty()) {
          if (overflow.load(std::memory_order_relaxed)) return;
          const simplex_pts<D> piece = stack.back();
          const std::uint32_t hint = hints.back();
          stack.pop_back();
          hints.pop_back();
          const evaluation x = evaluate(piece, hint);
          if (!std::isfinite(x.v)) continue;
          if (cut(x)) {
            const std::size_t before = stack.size();
            split<D>(piece, stack);
            hints.resize(stack.size(), x.found_face);
            counted += stack.size() - before;
          } else {
            ++counted;
          }
          if (counted >= 4096 && !report(std::exchange(counted, 0))) return;
        }
      }
      report(counted);
    };
    if (keep) {
      // a level at a time (the pieces in the order the field has always had them)
      std::vector<simplex_pts<D>> todo{face_pts(k)}, next;
      std::vector<std::uint32_t> todo_hint{no_hint}, next_hint;
      auto& out = pieces[k];
      std::size_t added = 0;  // this face's levels added to the total so far
      bool claimed = false;   // this face's whole count added to the total ahead (below)
      while (!todo.empty() && !overflow.load(std::memory_order_relaxed)) {
        next.clear();
        next_hint.clear();
        const std::size_t kept_before = out.size();  // the pieces kept at earlier levels, counted then
        for (std::size_t t = 0; t < todo.size(); ++t) {
          const auto& piece = todo[t];
          const evaluation x = evaluate(piece, todo_hint[t]);
          if (!std::isfinite(x.v)) continue;
          if (cut(x)) {
            split<D>(piece, next);
            next_hint.resize(next.size(), x.found_face);
            // (the budget asked every 65536 pieces cut, when the other faces' progress is read;
            // this face's own pieces held at every one)
            const bool ask = next.size() % 65536 == 0;
            if (!ask && (claimed || out.size() + next.size() < s.held_face)) continue;
            // over the budget already (the other faces' levels done, and this face's so far): stop
            // now, not after the level (a 5e-6 layer's face had grown a level of 16 million pieces
            // before the check, 6 GB). Only when the sum at the end would be over it too
            if (ask && !claimed && total.load(std::memory_order_relaxed) + out.size() - kept_before + next.size() > max_sources) {
              overflow = true;
              break;
            }
            // this face holding `held_face` pieces: the rest of its count first (the level's
            // pieces not yet evaluated and those cut for the next, and all they will be cut
            // into), depth first without holding any, and its whole count added to the total at
            // once. Over the budget: the error now, with this face's pieces held up to here (a
            // thin layer's rejection held the whole budget, 1.57 GB, before). Within it: the
            // build goes on, its levels no longer added (the count was theirs). Faces that fit
            // below `held_face`, all but a few on any input that fits, are never counted
            if (!claimed && out.size() + next.size() >= s.held_face) {
              claimed = true;
              // this level's pieces so far (kept, and cut for the next), as its end would add them
              std::size_t whole = added + out.size() - kept_before + next.size();
              const std::size_t later = todo.size() - t - 1;  // this level's pieces not yet evaluated
              auto rest = [&](std::size_t r) {
                return r < later ? std::pair{todo[t + 1 + r], todo_hint[t + 1 + r]} : std::pair{next[r - later], next_hint[r - later]};
              };
              count_pieces(later + next.size(), rest, [&](std::size_t n) {
                whole += n;
                if (total.load(std::memory_order_relaxed) - added + whole > max_sources) overflow = true;
                return !overflow.load(std::memory_order_relaxed);
              });
              if (overflow.load(std::memory_order_relaxed) || total.fetch_add(whole - added, std::memory_order_relaxed) + whole - added > max_sources) {
                overflow = true;
                break;
              }
            }
            continue;
          }
          out.push_back({piece, std::max(x.v, floor)});
        }
        // this level's pieces: those kept at it and those cut for the next
        const std::size_t level = out.size() - kept_before + next.size();
        if (!claimed) {
          added += level;
          if (total.fetch_add(level, std::memory_order_relaxed) + level > max_sources) overflow = true;
        }
        std::swap(todo, next);
        std::swap(todo_hint, next_hint);
      }
    } else {
      // only counted (check_feature_size): the same count as the levels' ends above add, so the
      // verdict (the total over the budget) is the same
      count_pieces(1, [&](std::size_t) { return std::pair{face_pts(k), no_hint}; }, [&](std::size_t n) {
        if (total.fetch_add(n, std::memory_order_relaxed) + n > max_sources) overflow = true;
        return !overflow.load(std::memory_order_relaxed);
      });
    }
    // progress: faces finished, every 4096th (at the end of the body, not from a destructor: a
    // callback that throws propagates like any other failure of the body)
    if (progress && (faces_done.fetch_add(1, std::memory_order_relaxed) + 1) % 4096 == 0) {
      const std::lock_guard<std::mutex> hold(progress_lock);
      progress(faces_done.load(std::memory_order_relaxed), nf);
    }
  }, [&](std::size_t) { return 1.0; });
  if (overflow) {
    // the closest features across found by the faces that got that far (the faces' order breaks
    // ties): which they are may differ between thread counts; that the budget is exceeded does not
    std::size_t at = 0;
    for (std::size_t k = 1; k < nf; ++k)
      if (closest[k].d2 < closest[at].d2) at = k;
    std::ostringstream where;
    if (nf > 0 && std::isfinite(closest[at].d2)) {
      const double gap = std::sqrt(closest[at].d2);
      auto source_of = [&](std::size_t face) {
        const std::uint32_t src = face < b.face_source.size() ? b.face_source[face] : 0;
        return std::string(D == 2 ? "segment " : "facet ") + std::to_string(src + 1);
      };
      where << "the closest " << std::setprecision(3) << gap << " apart (" << gap / extent << " of the model's extent) at (";
      for (std::size_t j = 0; j < D; ++j) where << (j ? ", " : "") << std::setprecision(6) << closest[at].at[j];
      where << "), " << source_of(at) << " and " << source_of(closest[at].face);
    }
    const std::string closest_found = where.str();
    if (!s.feature_size)  // the sizes asked for (sidecar, region volumes, --size) are the cause
      throw too_fine(b.source + ": the size field needs more than " + std::to_string(max_sources) +
                         " boundary pieces: the sizes asked for are far below the model's size",
                     closest_found);
    throw too_fine(b.source + ": the local feature size needs more than " + std::to_string(max_sources) +
                       " boundary pieces: features far below the model's size" + (closest_found.empty() ? "" : ", " + closest_found) +
                       ": thicken or remove them, or leave the local feature size out (--no-feature-size) and give sizes",
                   closest_found);
  }
  if (!keep) return f;
  for (const auto& v : pieces)
    for (const auto& [piece, value] : v) {
      f.face_values_.push_back(value);
      f.face_pieces_.push_back(piece);
      f.minimum_ = std::min(f.minimum_, value);
    }
  f.group_faces();
  // interface layers with a growth rate of their own: their faces, cut in pieces no larger than
  // the layer's size, in one tree per rate
  struct layer_parts {
    std::vector<aabb<D>> boxes;
    std::vector<double> values;
    std::vector<simplex_pts<D>> pieces;
  };
  std::map<double, layer_parts> by_slope;
  for (const auto& L : s.interfaces) {
    if (L.grade == 0 || !(L.size < f.global_)) continue;
    auto& [lboxes, lvalues, lpieces] = by_slope[L.grade - 1];
    for (std::size_t k = 0; k < nf && k < b.sides.size(); ++k) {
      const int n0 = b.sides[k][0], n1 = b.sides[k][1];
      if (!((L.a == n0 && L.b == n1) || (L.a == n1 && L.b == n0))) continue;
      std::vector<simplex_pts<D>> todo{face_pts(k)}, next;
      while (!todo.empty()) {
        next.clear();
        for (const auto& piece : todo) {
          const point<D> c = centroid<D>(piece);
          double r = 0;
          for (const auto& q : piece) r = std::max(r, std::sqrt(squared_distance(q, c)));
          if (r > std::max(L.size, floor)) {
            split<D>(piece, next);
            continue;
          }
          aabb<D> bx = aabb<D>::empty();
          for (const auto& q : piece) bx.add(q);
          lboxes.push_back(bx);
          lvalues.push_back(std::max(L.size, floor));
          lpieces.push_back(piece);
          f.minimum_ = std::min(f.minimum_, std::max(L.size, floor));
        }
        if (lboxes.size() + next.size() > max_sources)
          throw std::runtime_error(b.source + ": an interface layer needs more than " + std::to_string(max_sources) + " boundary pieces");
        std::swap(todo, next);
      }
    }
  }
  for (auto& [slope, parts] : by_slope)
    if (!parts.boxes.empty())
      f.layers_.push_back({slope, box_tree<D>(std::move(parts.boxes), std::move(parts.values)), std::move(parts.pieces)});
  f.uniform_ = f.face_pieces_.empty() && f.layers_.empty() && !f.background_;
  for (const auto& bx : s.boxes) {
    if (!(bx.size > 0)) throw std::invalid_argument("a refinement box's size must be positive");
    f.minimum_ = std::min(f.minimum_, bx.size);
    if (bx.size < f.global_) f.uniform_ = false;
  }
  for (const auto& [n, h] : s.segment_size)
    if (h < f.global_) f.uniform_ = false, f.minimum_ = std::min(f.minimum_, h);
  if (f.background_) {
    const auto& B = *f.background_;
    std::vector<aabb<D>> cb(B.cells.size());
    for (std::size_t c = 0; c < B.cells.size(); ++c) {
      cb[c] = aabb<D>::empty();
      for (vertex_id v : B.cells[c]) cb[c].add(B.points[v]);
    }
    f.background_cells_ = box_tree<D>(std::move(cb), std::vector<double>(B.cells.size(), 0.0));
    for (double h : B.size) f.minimum_ = std::min(f.minimum_, h);
  }
  return f;
}

template double size_field<2>::operator()(const point2&) const;
template double size_field<3>::operator()(const point3&) const;
template double size_field<2>::operator()(const point2&, int) const;
template double size_field<3>::operator()(const point3&, int) const;
template double size_field<2>::exhaustive(const point2&) const;
template double size_field<3>::exhaustive(const point3&) const;
template double size_field<2>::capped(const point2&, double) const;
template double size_field<3>::capped(const point3&, double) const;
template double size_field<2>::capped(const point2&, int, double) const;
template double size_field<3>::capped(const point3&, int, double) const;
template void add_region_volumes<2>(spec<2>&, const plc<2>&);
template void add_region_volumes<3>(spec<3>&, const plc<3>&);
template size_field<2> build<2>(const boundary_view<2>&, const spec<2>&, unsigned,
                                const std::function<void(std::size_t, std::size_t)>&);
template size_field<3> build<3>(const boundary_view<3>&, const spec<3>&, unsigned,
                                const std::function<void(std::size_t, std::size_t)>&);
template void check_feature_size<2>(const boundary_view<2>&, std::size_t, unsigned);
template void check_feature_size<3>(const boundary_view<3>&, std::size_t, unsigned);

}  // namespace gsse::sizing
