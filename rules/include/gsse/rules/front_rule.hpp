#pragma once
// Front rules in unit coordinates: what to build on a front element (edge in 2D, triangle in 3D).
// Rule vertices are numbered in one index space: [0, D) the base vertices, then the matched
// points, then the new points (front_rule::points holds base + matched, front_rule::created the
// new ones). Elements, faces and orientation conditions are lists of such indices.
#include <array>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "gsse/geometry/point.hpp"
#include "gsse/rules/unit_frame.hpp"

namespace gsse::rules {

/// A base vertex or a matched existing point: reference position and tolerance (unit frame).
struct rule_point {
  std::string name;
  point3 ref{};    // z = 0 in 2D
  double tol = 0;  // max distance of the actual position from ref
  int line = 0;
};

struct mix_term {
  double weight = 0;
  std::size_t point = 0;  // index into front_rule::points
};

/// A new point: at `shift` in the unit frame if `mix` is empty, otherwise the affine
/// combination sum(weight * actual position) + shift, so it follows the matched points.
struct new_point {
  std::string name;
  std::vector<mix_term> mix;
  point3 shift{};
  int line = 0;
};

struct front_rule {
  std::string name;
  int dimension = 2;
  int quality = 1;
  double tolerance = 0.5;  // default tolerance of base and matched points
  std::vector<rule_point> points;  // base vertices first (dimension of them), then matched
  std::vector<new_point> created;
  std::vector<std::vector<std::size_t>> elements;       // triangles (2D) / tetrahedra (3D)
  std::vector<std::vector<std::size_t>> added_faces;    // new front edges / triangles
  std::vector<std::vector<std::size_t>> removed_faces;  // front faces consumed
  std::vector<std::vector<std::size_t>> orientations;   // tuples that must be positive
  std::vector<std::vector<point3>> free_zone;           // convex pieces (hull of each list)
  int line = 0;

  std::size_t vertex_count() const { return points.size() + created.size(); }
  const std::string& vertex_name(std::size_t v) const;
  /// Reference unit position of any vertex (new points evaluated on the reference positions).
  point3 reference(std::size_t v) const;
};

/// Reference positions of the base vertices: (0,0),(1,0) in 2D; the unit equilateral triangle
/// (0,0,0),(1,0,0),(1/2,sqrt(3)/2,0) in 3D.
point3 base_reference(int dimension, std::size_t i);

struct front_rule_set {
  std::vector<front_rule> rules;  // in file order
  /// Rules eligible at quality class `cls` (quality <= cls), ordered by quality, then file order.
  std::vector<const front_rule*> eligible(int cls) const;
};

/// Positive orientation in unit coordinates: 2D counter-clockwise, 3D det(b-a, c-a, d-a) > 0
/// (d above the counter-clockwise triangle abc). Points are given with z = 0 in 2D.
double orientation(int dimension, std::span<const point3> p);

/// Whether u (unit coordinates) lies in the convex hull of `piece`, at least `margin` inside
/// every supporting line/plane (margin < 0 admits points slightly outside).
bool in_convex_piece(int dimension, std::span<const point3> piece, const point3& u, double margin);

/// A free-zone piece made ready for many questions: its bounding box and its supporting lines
/// (2D) or planes (3D), each through two (three) of its points, in the order in_convex_piece
/// tries them. `contains(u, margin)` is in_convex_piece(dimension, piece, u, margin), the same
/// arithmetic, without finding the supporting planes again: that search over every triple and
/// every point of the piece was an eighth of a `--fill rules` run (docs/benchmarks.md,
/// forty-ninth part).
struct convex_piece {
  struct plane {
    point3 o{}, normal{};  // through o, unit normal
    bool positive = true;  // the piece lies on the normal's side
  };
  int dimension = 2;
  point3 lo{}, hi{};  // the bounding box (the first D axes)
  std::vector<plane> planes;
  static convex_piece of(int dimension, std::span<const point3> piece);
  bool contains(const point3& u, double margin) const;
};

enum class rejection { none, degenerate_base, tolerance, no_match, free_zone, orientation };
std::string_view to_string(rejection r);

template <std::size_t D>
struct front_result {
  rejection reason = rejection::none;
  std::string detail;      // which point / element caused the rejection
  double error = 0;        // largest deviation of a base or matched point from its reference
  std::vector<std::size_t> matched;  // cloud index of each matched point, in rule order
  std::vector<point<D>> vertices;    // world position of every rule vertex (rule index space)
  explicit operator bool() const { return reason == rejection::none; }
  /// World positions of the new points only.
  std::vector<point<D>> created(const front_rule& r) const {
    return {vertices.begin() + static_cast<std::ptrdiff_t>(r.points.size()), vertices.end()};
  }
};

/// Applies a rule to a front element. `cloud` holds the nearby existing points (it may contain
/// the base vertices, which are never counted as free-zone violations). Matched points take the
/// nearest unused cloud point to their reference position. Rejects when a deviation exceeds its
/// tolerance, a cloud point lies strictly inside the free zone, or a new element or orientation
/// condition is not positively oriented with the actual positions.
front_result<2> apply(const front_rule& r, std::span<const point2, 2> base, std::span<const point2> cloud,
                      double h);
front_result<3> apply(const front_rule& r, std::span<const point3, 3> base, std::span<const point3> cloud,
                      double h);

/// The free zone of r made ready (convex_piece::of of each piece), for the apply below.
std::vector<convex_piece> zone_of(const front_rule& r);

/// What every rule tried on one front element (in one rotation of its vertices) shares: the
/// element's unit frame and the nearby points mapped into it. A mesher that tries several rules
/// on each element prepares once and applies each rule to the frame: the same results as
/// apply(r, base, cloud, h), without mapping the cloud again for every rule. The frame keeps a
/// view of `cloud`, which must outlive it. With `reach` (unit lengths: the farthest from the
/// first base vertex any rule looks, free-zone vertices and matched points' references plus their
/// tolerance; rules::reach gives it) only the cloud points within it are mapped: a point beyond
/// lies in no free zone and matches no point, and it is kept at infinity, where every rule
/// ignores it (the same results: no point a rule can see is left out).
template <std::size_t D>
struct front_frame {
  unit_frame<D> frame;
  bool degenerate = false;           // the base is degenerate or h <= 0: every rule rejects
  std::array<point<D>, D> base{};    // world positions of the base vertices
  std::array<point3, D> base_unit{}; // and in the unit frame (z = 0 in 2D)
  std::span<const point<D>> cloud;   // the nearby points, world positions
  std::vector<point3> cloud_unit;    // and in the unit frame
  std::vector<char> at_base;         // a cloud point within 1e-9 (unit) of a base vertex is that vertex
};
front_frame<2> prepare(std::span<const point2, 2> base, std::span<const point2> cloud, double h,
                       double reach = std::numeric_limits<double>::infinity());
front_frame<3> prepare(std::span<const point3, 3> base, std::span<const point3> cloud, double h,
                       double reach = std::numeric_limits<double>::infinity());
/// How far from the first base vertex (unit lengths) rule r looks at the cloud: its free-zone
/// vertices, and its matched points' references plus their tolerances.
double reach(const front_rule& r);
/// apply(r, base, cloud, h) for the frame's element; `zone` is zone_of(r) (computed here if its
/// size is not that of r's free zone).
front_result<2> apply(const front_rule& r, std::span<const convex_piece> zone, const front_frame<2>& f);
front_result<3> apply(const front_rule& r, std::span<const convex_piece> zone, const front_frame<3>& f);

}  // namespace gsse::rules
