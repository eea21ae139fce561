// Split-rule lookup and the geometry of split candidates (double constructions; no topological
// decision is taken here, the conformer re-checks encroachment with exact predicates).
#include <cmath>

#include "gsse/geometry/circumcentre.hpp"
#include "gsse/rules/split_rule.hpp"

namespace gsse::rules {

namespace {

constexpr std::string_view kind_names[] = {"subsegment", "subfacet"};
constexpr std::string_view relation_names[] = {"free", "on-incident-vertex", "on-incident-edge", "on-carrier"};
constexpr std::string_view action_names[] = {"project", "rotate-vertex", "rotate-edge", "midpoint", "shell"};

template <class E, std::size_t N>
std::optional<E> from_names(const std::string_view (&names)[N], std::string_view s) {
  for (std::size_t i = 0; i < N; ++i)
    if (names[i] == s) return static_cast<E>(i);
  return std::nullopt;
}

template <std::size_t D>
std::optional<point<D>> normalized(const point<D>& v) {
  const double n = std::sqrt(dot(v, v));
  if (!(n > 0) || !std::isfinite(n)) return std::nullopt;
  return (1.0 / n) * v;
}

// Unit normal-free projection of p onto the plane of (a, b, c).
point3 project_to_plane(const point3& a, const point3& b, const point3& c, const point3& p) {
  const point3 n = cross(b - a, c - a);
  return p - (dot(p - a, n) / dot(n, n)) * n;
}

template <std::size_t D>
std::optional<point<D>> segment_candidate(split_action a, const point<D>& p0, const point<D>& p1,
                                          const point<D>& e, const std::optional<point<D>>& s,
                                          const std::optional<point<D>>& shell) {
  const point<D> d = p1 - p0;
  switch (a) {
    case split_action::shell: {
      if (!shell) return std::nullopt;
      // the centre is one end, or lies on the line behind the nearer end (the vertex of a
      // protecting ball whose sphere the subsegment starts on)
      const double d0 = distance(*shell, p0), d1 = distance(*shell, p1);
      const point<D>& far = d0 > d1 ? p0 : p1;
      const double dn = std::min(d0, d1), df = std::max(d0, d1);
      const auto u = normalized<D>(far - *shell);
      if (!u) return std::nullopt;
      if (dn == 0) return *shell + shell_radius(df) * *u;
      // the coarsest dyadic distance m 2^k inside, 10% of the subsegment clear of its ends: a
      // power of two where there is one, else the midpoint of a shell interval, and so on, so
      // that every edge at this vertex is split at the same distances
      const double gap = 0.1 * (df - dn), lo = dn + gap, hi = df - gap;
      if (!(lo < hi)) return std::nullopt;
      const double r = dyadic_between(lo, hi);
      if (!(r > dn && r < df)) return std::nullopt;
      return *shell + r * *u;
    }
    case split_action::project:
      return p0 + (dot(e - p0, d) / dot(d, d)) * d;
    case split_action::midpoint:
      return 0.5 * (p0 + p1);
    case split_action::rotate_vertex: {
      if (!s) return std::nullopt;
      // along the carrier, away from the shared vertex
      const point<D>& far = squared_distance(*s, p0) > squared_distance(*s, p1) ? p0 : p1;
      const auto u = normalized<D>(far - *s);
      if (!u) return std::nullopt;
      return *s + snap_to_shell(distance(e, *s)) * *u;
    }
    case split_action::rotate_edge:
      return std::nullopt;  // a subsegment has no shared edge axis
  }
  return std::nullopt;
}

template <std::size_t D>
bool accepts_coordinates(const split_step& s, const std::vector<double>& u) {
  for (double x : u) {
    if (!std::isfinite(x)) return false;
    if (s.inside && !(x > 0)) return false;
    if (x < s.min_gap) return false;
  }
  return true;
}

std::vector<double> segment_coordinates(double t) {
  return {t, 1 - t};  // both ends: min-gap applies to either endpoint
}

}  // namespace

std::string_view to_string(element_kind k) { return kind_names[static_cast<int>(k)]; }
std::string_view to_string(relation r) { return relation_names[static_cast<int>(r)]; }
std::string_view to_string(split_action a) { return action_names[static_cast<int>(a)]; }
std::optional<element_kind> element_kind_from(std::string_view s) { return from_names<element_kind>(kind_names, s); }
std::optional<relation> relation_from(std::string_view s) { return from_names<relation>(relation_names, s); }
std::optional<split_action> split_action_from(std::string_view s) { return from_names<split_action>(action_names, s); }

const split_rule* split_rule_set::lookup(element_kind kind, relation rel) const {
  for (const auto& r : rules)
    if (r.kind == kind && r.rel == rel) return &r;
  return nullptr;
}

double shell_radius(double l) {
  if (!(l > 0) || !std::isfinite(l)) return 0.5 * l;
  int e = 0;
  std::frexp(2 * l / 3, &e);  // 2l/3 = m * 2^e, m in [0.5, 1)
  return std::ldexp(1.0, e - 1);
}

double dyadic_between(double lo, double hi) {
  if (!(lo > 0) || !(hi >= lo) || !std::isfinite(hi)) return 0.5 * (lo + hi);
  int e = 0;
  std::frexp(hi, &e);  // hi < 2^e
  for (double step = std::ldexp(1.0, e - 1);; step *= 0.5) {
    const double m = std::ceil(lo / step);
    if (m * step <= hi) return m * step;
    if (step < hi * 1e-12) return 0.5 * (lo + hi);
  }
}

double snap_to_shell(double d) {
  if (!(d > 0) || !std::isfinite(d)) return d;
  int e = 0;
  // a distance a hair below a shell is on it: points on slanted carriers sit 1e-10 of their
  // element off their construction, and their images must not drop a shell each time
  std::frexp(d * (1 + 1e-8), &e);  // d (1 + 1e-8) = m * 2^e, m in [0.5, 1)
  return std::ldexp(1.0, e - 1);
}

std::vector<double> unit_coordinates(std::span<const point2> el, const point2& p) {
  const point2 d = el[1] - el[0];
  return {dot(p - el[0], d) / dot(d, d)};
}

std::vector<double> unit_coordinates(std::span<const point3> el, const point3& p) {
  if (el.size() == 2) {
    const point3 d = el[1] - el[0];
    return {dot(p - el[0], d) / dot(d, d)};
  }
  const point3 n = cross(el[1] - el[0], el[2] - el[0]);
  const double nn = dot(n, n);
  const point3 q = project_to_plane(el[0], el[1], el[2], p);
  const double la = dot(cross(el[1] - q, el[2] - q), n) / nn;
  const double lb = dot(cross(el[2] - q, el[0] - q), n) / nn;
  return {la, lb, 1 - la - lb};
}

bool accepts(const split_step& s, std::span<const point2> el, const point2& p) {
  return accepts_coordinates<2>(s, segment_coordinates(unit_coordinates(el, p)[0]));
}

bool accepts(const split_step& s, std::span<const point3> el, const point3& p) {
  auto u = unit_coordinates(el, p);
  if (u.size() == 1) u = segment_coordinates(u[0]);
  return accepts_coordinates<3>(s, u);
}

std::optional<point2> split_candidate(split_action a, std::span<const point2, 2> seg, const point2& e,
                                      const std::optional<point2>& shared_vertex, const std::optional<point2>& shell) {
  return segment_candidate<2>(a, seg[0], seg[1], e, shared_vertex, shell);
}

std::optional<point3> split_candidate(split_action a, std::span<const point3> el, const point3& e,
                                      const shared3& shared) {
  if (el.size() == 2) return segment_candidate<3>(a, el[0], el[1], e, shared.vertex, shared.shell);
  if (el.size() != 3) return std::nullopt;
  const point3 &p0 = el[0], &p1 = el[1], &p2 = el[2];
  const point3 centroid = (1.0 / 3) * (p0 + p1 + p2);
  std::optional<point3> r;
  switch (a) {
    case split_action::project:
      r = project_to_plane(p0, p1, p2, e);
      break;
    case split_action::midpoint: {  // a subfacet's circumcentre
      const point3 u = p1 - p0, v = p2 - p0, n = cross(u, v);
      r = p0 + geometry::triangle_circumcentre_offset(u, v, n, dot(n, n));
      break;
    }
    case split_action::rotate_vertex: {
      if (!shared.vertex) return std::nullopt;
      const point3& s = *shared.vertex;
      // in-plane direction of the encroacher seen from s; straight above s: towards the element
      auto w = normalized<3>(project_to_plane(p0, p1, p2, e) - project_to_plane(p0, p1, p2, s));
      if (!w) w = normalized<3>(centroid - s);
      if (!w) return std::nullopt;
      r = s + snap_to_shell(distance(e, s)) * *w;
      break;
    }
    case split_action::shell:
      return std::nullopt;  // subsegments only
    case split_action::rotate_edge: {
      if (!shared.edge) return std::nullopt;
      const auto& [q0, q1] = *shared.edge;
      const auto u = normalized<3>(q1 - q0);
      if (!u) return std::nullopt;
      const point3 foot = q0 + dot(e - q0, *u) * *u;
      const point3 g = centroid - q0;
      const auto w = normalized<3>(g - dot(g, *u) * *u);  // in the element's plane, towards it
      if (!w) return std::nullopt;
      // a rotation for facets folding over the element (a dihedral angle below 90 degrees); an
      // encroacher beyond the edge, on a facet that continues the element's nearly flat, would
      // be mirrored into a cocircular copy of itself
      if (!(dot(e - foot, *w) > 0)) return std::nullopt;
      r = foot + snap_to_shell(distance(e, foot)) * *w;
      break;
    }
  }
  if (r && !is_finite(*r)) return std::nullopt;
  return r;
}

std::optional<split_choice<2>> split_point(const split_rule& r, std::span<const point2, 2> seg, const point2& e,
                                           const std::optional<point2>& shared_vertex, const std::optional<point2>& shell,
                                           const std::function<bool(const point2&, split_action)>& usable) {
  for (std::size_t i = 0; i < r.steps.size(); ++i) {
    const auto c = split_candidate(r.steps[i].action, seg, e, shared_vertex, shell);
    if (c && is_finite(*c) && accepts(r.steps[i], std::span<const point2>(seg), *c) && (!usable || usable(*c, r.steps[i].action)))
      return split_choice<2>{*c, r.steps[i].action, i};
  }
  return std::nullopt;
}

std::optional<split_choice<3>> split_point(const split_rule& r, std::span<const point3> el, const point3& e,
                                           const shared3& shared, const std::function<bool(const point3&, split_action)>& usable) {
  for (std::size_t i = 0; i < r.steps.size(); ++i) {
    const auto c = split_candidate(r.steps[i].action, el, e, shared);
    if (c && accepts(r.steps[i], el, *c) && (!usable || usable(*c, r.steps[i].action)))
      return split_choice<3>{*c, r.steps[i].action, i};
  }
  return std::nullopt;
}

}  // namespace gsse::rules
