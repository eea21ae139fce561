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
front_result<D> apply_impl(const front_rule& r, std::span<const point<D>, D> base, std::span<const point<D>> cloud,
                           double h) {
  front_result<D> res;
  auto reject = [&](rejection why, std::string detail) {
    res.reason = why;
    res.detail = std::move(detail);
    return res;
  };
  if (r.dimension != static_cast<int>(D) || r.points.size() < D)
    return reject(rejection::degenerate_base, "rule '" + r.name + "' is not a " + std::to_string(D) + "D rule");
  const auto frame = make_unit_frame<D>(base, h);
  for (const auto& ax : frame.axes)
    if (!(h > 0) || !is_finite(ax)) return reject(rejection::degenerate_base, "degenerate base or h <= 0");

  std::vector<point3> act(r.vertex_count());
  for (std::size_t i = 0; i < D; ++i) {
    act[i] = lift<D>(frame.to_unit(base[i]));
    const double dev = distance(act[i], r.points[i].ref);
    res.error = std::max(res.error, dev);
    if (dev > r.points[i].tol)
      return reject(rejection::tolerance, "base vertex '" + r.points[i].name + "' deviates by " + fmt(dev) +
                                              " > " + fmt(r.points[i].tol));
  }

  std::vector<point3> cu(cloud.size());
  std::vector<char> used(cloud.size(), 0);
  for (std::size_t k = 0; k < cloud.size(); ++k) {
    cu[k] = lift<D>(frame.to_unit(cloud[k]));
    for (std::size_t i = 0; i < D; ++i)
      if (distance(cu[k], act[i]) < same_point) used[k] = 1;
  }

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
    used[best] = 1;
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
    for (const auto& piece : r.free_zone)
      if (in_convex_piece(r.dimension, piece, cu[k], zone_margin))
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
  for (std::size_t i = 0; i < D; ++i) res.vertices[i] = base[i];
  for (std::size_t i = D; i < r.points.size(); ++i) res.vertices[i] = cloud[res.matched[i - D]];
  for (std::size_t i = r.points.size(); i < act.size(); ++i) res.vertices[i] = frame.to_world(drop<D>(act[i]));
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

bool in_convex_piece(int dimension, std::span<const point3> piece, const point3& u, double margin) {
  // The hull is the intersection of all supporting lines (planes) through 2 (3) of its points.
  const std::size_t n = piece.size();
  // outside the bounding box (by more than -margin): outside the hull; the cheap test first
  for (int a = 0; a < (dimension == 2 ? 2 : 3); ++a) {
    double lo = piece[0][a], hi = piece[0][a];
    for (const auto& q : piece) lo = std::min(lo, q[a]), hi = std::max(hi, q[a]);
    if (u[a] < lo + margin - eps || u[a] > hi - margin + eps) return false;
  }
  bool any = false;
  auto test = [&](const point3& o, const point3& normal) {  // normal has unit length
    bool pos = false, neg = false;
    for (const auto& q : piece) {
      const double s = dot(q - o, normal);
      pos |= s > eps;
      neg |= s < -eps;
    }
    if (pos == neg) return true;  // not supporting (or degenerate): no constraint
    any = true;
    const double s = dot(u - o, normal);
    return (pos ? s : -s) >= margin;
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const point3 d = piece[j] - piece[i];
      if (dimension == 2) {
        const double l = std::hypot(d[0], d[1]);
        if (!(l > eps)) continue;
        if (!test(piece[i], {-d[1] / l, d[0] / l, 0})) return false;
        continue;
      }
      for (std::size_t k = j + 1; k < n; ++k) {
        const point3 c = cross(d, piece[k] - piece[i]);
        const double l = std::sqrt(dot(c, c));
        if (!(l > eps)) continue;
        if (!test(piece[i], (1.0 / l) * c)) return false;
      }
    }
  return any;
}

std::string_view to_string(rejection r) {
  constexpr std::string_view names[] = {"accepted", "degenerate base", "tolerance exceeded", "no point to match",
                                        "free zone violated", "orientation violated"};
  return names[static_cast<int>(r)];
}

front_result<2> apply(const front_rule& r, std::span<const point2, 2> base, std::span<const point2> cloud, double h) {
  return apply_impl<2>(r, base, cloud, h);
}
front_result<3> apply(const front_rule& r, std::span<const point3, 3> base, std::span<const point3> cloud, double h) {
  return apply_impl<3>(r, base, cloud, h);
}

}  // namespace gsse::rules
