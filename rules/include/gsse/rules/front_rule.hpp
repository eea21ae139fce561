#pragma once
// Front rules in unit coordinates: what to build on a front element (edge in 2D, triangle in 3D).
// Rule vertices are numbered in one index space: [0, D) the base vertices, then the matched
// points, then the new points (front_rule::points holds base + matched, front_rule::created the
// new ones). Elements, faces and orientation conditions are lists of such indices.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "gsse/geometry/point.hpp"

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

}  // namespace gsse::rules
