// Front rules: reference geometry, convex free-zone tests and application to a front element.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "gsse/rules/front_rule.hpp"
#include "gsse/rules/unit_frame.hpp"

namespace gsse::rules {

namespace {

constexpr double eps = 1e-12;        // "on the line/plane" when testing the zone's own vertices
constexpr double zone_margin = 1e-9; // a cloud point must be this far inside to violate a zone
constexpr double same_point = 1e-9;  // cloud points this close to a base vertex are that vertex

template <std::size_t D>
point3 lift(const point<D>& p) {
  if constexpr (D == 2) return {p[0], p[1], 0};
  else return p;
}
template <std::size_t D>
point<D> drop(const point3& p) {
  if constexpr (D == 2) return {p[0], p[1]};
  else return p;
}

std::string fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

template <std::size_t D>
front_frame<D> prepare_impl(std::span<const point<D>, D> base, std::span<const point<D>> cloud, double h,
                            double reach = std::numeric_limits<double>::infinity()) {
  front_frame<D> f;
  f.frame = make_unit_frame<D>(base, h);
  for (std::size_t i = 0; i < D; ++i) f.base[i] = base[i];
  f.cloud = cloud;
  for (const auto& ax : f.frame.axes)
    if (!(h > 0) || !is_finite(ax)) f.degenerate = true;
  if (f.degenerate) return f;
  for (std::size_t i = 0; i < D; ++i) f.base_unit[i] = lift<D>(f.frame.to_unit(base[i]));
  f.cloud_unit.resize(cloud.size());
  f.at_base.assign(cloud.size(), 0);
  // beyond reach (world distance over h, above it by far more than rounding): never looked at
  const double far2 = reach * h * reach * h * (1 + 1e-6);
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < cloud.size(); ++k) {
    if (!(squared_distance(cloud[k], base[0]) <= far2)) {
      f.cloud_unit[k] = {inf, inf, inf};
      continue;
    }
    f.cloud_unit[k] = lift<D>(f.frame.to_unit(cloud[k]));
    for (std::size_t i = 0; i < D; ++i)
      if (distance(f.cloud_unit[k], f.base_unit[i]) < same_point) f.at_base[k] = 1;
  }
  return f;
}

template <std::size_t D>
front_result<D> apply_impl(const front_rule& r, std::span<const convex_piece> zone, const front_frame<D>& f) {
  front_result<D> res;
  auto reject = [&](rejection why, std::string detail) {
    res.reason = why;
    res.detail = std::move(detail);
    return res;
  };
  if (r.dimension != static_cast<int>(D) || r.points.size() < D)
    return reject(rejection::degenerate_base, "rule '" + r.name + "' is not a " + std::to_string(D) + "D rule");
  if (f.degenerate) return reject(rejection::degenerate_base, "degenerate base or h <= 0");
  std::vector<convex_piece> own_zone;
  if (zone.size() != r.free_zone.size()) own_zone = zone_of(r), zone = own_zone;

  std::vector<point3> act(r.vertex_count());
  for (std::size_t i = 0; i < D; ++i) {
    act[i] = f.base_unit[i];
    const double dev = distance(act[i], r.points[i].ref);
    res.error = std::max(res.error, dev);
    if (dev > r.points[i].tol)
      return reject(rejection::tolerance, "base vertex '" + r.points[i].name + "' deviates by " + fmt(dev) +
                                              " > " + fmt(r.points[i].tol));
  }

  const auto& cloud = f.cloud;
  const auto& cu = f.cloud_unit;
  // the cloud points taken: those at a base vertex, then the matched ones (a copy only if the
  // rule matches any)
  std::vector<char> own_used;
  if (r.points.size() > D) own_used = f.at_base;
  const std::vector<char>& used = r.points.size() > D ? own_used : f.at_base;

  // matched points: nearest unused cloud point to the reference position
  for (std::size_t i = D; i < r.points.size(); ++i) {
    std::size_t best = cloud.size();
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < cloud.size(); ++k) {
      if (used[k]) continue;
      const double d = distance(cu[k], r.points[i].ref);
      if (d < best_d) best_d = d, best = k;
    }
    if (best == cloud.size()) return reject(rejection::no_match, "no point to match '" + r.points[i].name + "'");
    res.error = std::max(res.error, best_d);
    if (best_d > r.points[i].tol)
      return reject(rejection::tolerance, "nearest point to '" + r.points[i].name + "' deviates by " +
                                              fmt(best_d) + " > " + fmt(r.points[i].tol));
    own_used[best] = 1;
    res.matched.push_back(best);
    act[i] = cu[best];
  }

  for (std::size_t j = 0; j < r.created.size(); ++j) {
    const auto& np = r.created[j];
    point3 p = np.shift;
    for (const auto& t : np.mix) p = p + t.weight * act[t.point];
    act[r.points.size() + j] = p;
  }

  for (std::size_t k = 0; k < cloud.size(); ++k) {
    if (used[k]) continue;
    for (const auto& piece : zone)
      if (piece.contains(cu[k], zone_margin))
        return reject(rejection::free_zone, "cloud point " + std::to_string(k) + " lies in the free zone");
  }

  auto positive = [&](const std::vector<std::size_t>& tuple) {
    std::vector<point3> p;
    for (auto v : tuple) p.push_back(act[v]);
    return orientation(r.dimension, p) > 0;
  };
  auto names = [&](const std::vector<std::size_t>& tuple) {
    std::string s;
    for (auto v : tuple) s += (s.empty() ? "" : " ") + r.vertex_name(v);
    return s;
  };
  for (const auto& e : r.elements)
    if (!positive(e)) return reject(rejection::orientation, "element (" + names(e) + ") is not positively oriented");
  for (const auto& o : r.orientations)
    if (!positive(o)) return reject(rejection::orientation, "orientation (" + names(o) + ") is violated");

  res.vertices.resize(act.size());
  for (std::size_t i = 0; i < D; ++i) res.vertices[i] = f.base[i];
  for (std::size_t i = D; i < r.points.size(); ++i) res.vertices[i] = cloud[res.matched[i - D]];
  for (std::size_t i = r.points.size(); i < act.size(); ++i) res.vertices[i] = f.frame.to_world(drop<D>(act[i]));
  return res;
}

}  // namespace

point3 base_reference(int dimension, std::size_t i) {
  static const point3 ref[3] = {{0, 0, 0}, {1, 0, 0}, {0.5, 0.8660254037844386, 0}};
  (void)dimension;  // 2D uses the first two, which are the same
  return ref[i];
}

const std::string& front_rule::vertex_name(std::size_t v) const {
  return v < points.size() ? points[v].name : created[v - points.size()].name;
}

point3 front_rule::reference(std::size_t v) const {
  if (v < points.size()) return points[v].ref;
  const auto& np = created[v - points.size()];
  point3 p = np.shift;
  for (const auto& t : np.mix) p = p + t.weight * points[t.point].ref;
  return p;
}

std::vector<const front_rule*> front_rule_set::eligible(int cls) const {
  std::vector<const front_rule*> r;
  for (const auto& x : rules)
    if (x.quality <= cls) r.push_back(&x);
  std::stable_sort(r.begin(), r.end(), [](auto a, auto b) { return a->quality < b->quality; });
  return r;
}

double orientation(int dimension, std::span<const point3> p) {
  if (dimension == 2) {
    const point3 a = p[1] - p[0], b = p[2] - p[0];
    return a[0] * b[1] - a[1] * b[0];
  }
  return dot(cross(p[1] - p[0], p[2] - p[0]), p[3] - p[0]);
}

convex_piece convex_piece::of(int dimension, std::span<const point3> piece) {
  // The hull is the intersection of all supporting lines (planes) through 2 (3) of its points.
  convex_piece z;
  z.dimension = dimension;
  if (piece.empty()) return z;
  for (int a = 0; a < 3; ++a) {
    z.lo[a] = z.hi[a] = piece[0][a];
    for (const auto& q : piece) z.lo[a] = std::min(z.lo[a], q[a]), z.hi[a] = std::max(z.hi[a], q[a]);
  }
  const std::size_t n = piece.size();
  auto add = [&](const point3& o, const point3& normal) {  // normal has unit length
    bool pos = false, neg = false;
    for (const auto& q : piece) {
      const double s = dot(q - o, normal);
      pos |= s > eps;
      neg |= s < -eps;
    }
    if (pos != neg) z.planes.push_back({o, normal, pos});  // else not supporting (or degenerate): no constraint
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const point3 d = piece[j] - piece[i];
      if (dimension == 2) {
        const double l = std::hypot(d[0], d[1]);
        if (l > eps) add(piece[i], {-d[1] / l, d[0] / l, 0});
        continue;
      }
      for (std::size_t k = j + 1; k < n; ++k) {
        const point3 c = cross(d, piece[k] - piece[i]);
        const double l = std::sqrt(dot(c, c));
        if (l > eps) add(piece[i], (1.0 / l) * c);
      }
    }
  return z;
}

bool convex_piece::contains(const point3& u, double margin) const {
  if (planes.empty()) return false;  // an empty or flat piece holds nothing
  // outside the bounding box (by more than -margin): outside the hull; the cheap test first
  for (int a = 0; a < (dimension == 2 ? 2 : 3); ++a)
    if (u[a] < lo[a] + margin - eps || u[a] > hi[a] - margin + eps) return false;
  for (const auto& p : planes) {
    const double s = dot(u - p.o, p.normal);
    if (!((p.positive ? s : -s) >= margin)) return false;
  }
  return true;
}

bool in_convex_piece(int dimension, std::span<const point3> piece, const point3& u, double margin) {
  return convex_piece::of(dimension, piece).contains(u, margin);
}

std::vector<convex_piece> zone_of(const front_rule& r) {
  std::vector<convex_piece> z;
  z.reserve(r.free_zone.size());
  for (const auto& piece : r.free_zone) z.push_back(convex_piece::of(r.dimension, piece));
  return z;
}

std::string_view to_string(rejection r) {
  constexpr std::string_view names[] = {"accepted", "degenerate base", "tolerance exceeded", "no point to match",
                                        "free zone violated", "orientation violated"};
  return names[static_cast<int>(r)];
}

front_frame<2> prepare(std::span<const point2, 2> base, std::span<const point2> cloud, double h, double reach) {
  return prepare_impl<2>(base, cloud, h, reach);
}
front_frame<3> prepare(std::span<const point3, 3> base, std::span<const point3> cloud, double h, double reach) {
  return prepare_impl<3>(base, cloud, h, reach);
}
double reach(const front_rule& r) {
  double most = 0;
  for (const auto& piece : r.free_zone)
    for (const auto& v : piece) most = std::max(most, std::sqrt(dot(v, v)));
  for (std::size_t i = r.dimension > 0 ? static_cast<std::size_t>(r.dimension) : 0; i < r.points.size(); ++i)
    most = std::max(most, std::sqrt(dot(r.points[i].ref, r.points[i].ref)) + r.points[i].tol);
  return most;
}
front_result<2> apply(const front_rule& r, std::span<const convex_piece> zone, const front_frame<2>& f) {
  return apply_impl<2>(r, zone, f);
}
front_result<3> apply(const front_rule& r, std::span<const convex_piece> zone, const front_frame<3>& f) {
  return apply_impl<3>(r, zone, f);
}
front_result<2> apply(const front_rule& r, std::span<const point2, 2> base, std::span<const point2> cloud, double h) {
  return apply_impl<2>(r, zone_of(r), prepare_impl<2>(base, cloud, h));
}
front_result<3> apply(const front_rule& r, std::span<const point3, 3> base, std::span<const point3> cloud, double h) {
  return apply_impl<3>(r, zone_of(r), prepare_impl<3>(base, cloud, h));
}

}  // namespace gsse::rules
