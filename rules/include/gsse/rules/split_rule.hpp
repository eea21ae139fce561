#pragma once
// Conformer split rules: which split point to try when a boundary element is encroached.
// The conformer classifies the encroachment as (element kind, relation), looks the rule up and
// tries its actions in order; the first candidate that passes its acceptance conditions wins.
#include <array>
#include <limits>
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "gsse/geometry/point.hpp"

namespace gsse::rules {

enum class element_kind { subsegment, subfacet };

/// How the encroaching vertex relates to the encroached element's PLC entity (its carrier).
enum class relation {
  free,                // volume point, or vertex of a non-incident boundary entity
  on_incident_vertex,  // lies on a PLC entity sharing exactly a vertex with the carrier
  on_incident_edge,    // lies on a PLC facet sharing an edge with the carrier (3D)
  on_carrier           // lies on the carrier itself
};

enum class split_action {
  project,        // orthogonal projection of the encroacher onto the element
  rotate_vertex,  // about the shared vertex; distance snapped to a power of two
  rotate_edge,    // about the shared edge axis (3D subfacets); distance snapped to a power of two;
                  // only for an encroacher over the element's side of the edge (a fold)
  midpoint,       // subsegment midpoint, subfacet circumcentre
  shell           // subsegments with one end at a PLC vertex where a small angle meets: on the
                  // power-of-two shell about that vertex nearest the midpoint
};

/// One action with its acceptance conditions, in unit coordinates of the element
/// (subsegment: parameter t in [0,1]; subfacet: barycentric coordinates).
struct split_step {
  split_action action = split_action::midpoint;
  // every unit coordinate >= min_gap (t in [g, 1-g] for a subsegment); without `min-gap` there
  // is no bound: the point may lie anywhere on the element's carrier (line or plane)
  double min_gap = -std::numeric_limits<double>::infinity();
  bool inside = false;  // every unit coordinate > 0 (strictly inside the element)
  int line = 0;
};

struct split_rule {
  std::string name;
  element_kind kind = element_kind::subsegment;
  relation rel = relation::free;
  std::vector<split_step> steps;
  int line = 0;
};

struct split_rule_set {
  std::vector<split_rule> rules;
  /// The rule for (kind, relation), or nullptr. A validated set has exactly one per valid pair.
  const split_rule* lookup(element_kind kind, relation rel) const;
};

// Keyword spellings used by the language (also for messages).
std::string_view to_string(element_kind k);
std::string_view to_string(relation r);
std::string_view to_string(split_action a);
std::optional<element_kind> element_kind_from(std::string_view s);
std::optional<relation> relation_from(std::string_view s);
std::optional<split_action> split_action_from(std::string_view s);

/// The power-of-two shell a rotated distance is snapped to: the largest 2^k <= d (1 + 1e-8) (exact
/// powers of two are kept, and distances rounding left a hair below them), in world units. Shells are nested for every shared vertex, which is what
/// makes mutual encroachment of small angles terminate.
double snap_to_shell(double d);
/// The coarsest dyadic number m 2^k in [lo, hi] (0 < lo <= hi): the split distance of the shell
/// action, the same for every edge at a vertex whose subsegment spans it.
double dyadic_between(double lo, double hi);
/// The split of a subsegment of length l with one end at a small-angle vertex: the largest power
/// of two not above 2l/3 (so in [l/3, 2l/3]), its distance from that vertex (Ruppert's concentric
/// shells). Every edge at the vertex is split on the same spheres about it, so the ends of two
/// subsegments there never encroach each other, whatever the angle between them.
double shell_radius(double l);

/// The shared PLC entity of an on-incident-* encroachment (3D); empty members when absent.
struct shared3 {
  std::optional<point3> vertex;
  std::optional<std::array<point3, 2>> edge;
  std::optional<point3> shell;  // the centre of `shell`: the subsegment's end, or on its line behind it
};

template <std::size_t D>
struct split_choice {
  point<D> at;  // the split point
  split_action action;
  std::size_t step;  // index into split_rule::steps
};

/// Unit coordinates of p (assumed on the element's carrier): {t} for a subsegment (2 vertices),
/// barycentric {la, lb, lc} of p's projection for a subfacet (3 vertices).
std::vector<double> unit_coordinates(std::span<const point2> element, const point2& p);
std::vector<double> unit_coordinates(std::span<const point3> element, const point3& p);

/// Whether p passes the step's acceptance conditions.
bool accepts(const split_step& s, std::span<const point2> element, const point2& p);
bool accepts(const split_step& s, std::span<const point3> element, const point3& p);

/// The candidate of one action before acceptance; nullopt if the action cannot be computed
/// (missing shared entity, degenerate geometry).
std::optional<point2> split_candidate(split_action a, std::span<const point2, 2> segment,
                                      const point2& encroacher, const std::optional<point2>& shared_vertex,
                                      const std::optional<point2>& shell = {});
std::optional<point3> split_candidate(split_action a, std::span<const point3> element,
                                      const point3& encroacher, const shared3& shared);

/// Tries the rule's steps in order; the first accepted candidate. 2D has only subsegments.
/// `usable`, if given, can reject a candidate the conditions accept (the conformer rejects one that
/// coincides with an existing point); the next step is then tried.
std::optional<split_choice<2>> split_point(const split_rule& r, std::span<const point2, 2> segment,
                                           const point2& encroacher,
                                           const std::optional<point2>& shared_vertex = {},
                                           const std::optional<point2>& shell = {},
                                           const std::function<bool(const point2&, split_action)>& usable = {});
/// element: 2 vertices (subsegment) or 3 (subfacet).
std::optional<split_choice<3>> split_point(const split_rule& r, std::span<const point3> element,
                                           const point3& encroacher, const shared3& shared = {},
                                           const std::function<bool(const point3&, split_action)>& usable = {});

}  // namespace gsse::rules
