#define BOOST_TEST_MODULE rules_split
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>

#include "gsse/rules/defaults.hpp"

using namespace gsse;
using namespace gsse::rules;

namespace {

const rule_set& c2() {
  static const auto s = default_rules("conformer2d");
  return s;
}
const rule_set& c3() {
  static const auto s = default_rules("conformer3d");
  return s;
}
const split_rule& rule2(relation r) { return *c2().split.lookup(element_kind::subsegment, r); }
const split_rule& rule3(element_kind k, relation r) { return *c3().split.lookup(k, r); }

template <std::size_t D>
bool near(const point<D>& a, const point<D>& b, double tol = 1e-12) {
  return distance(a, b) <= tol;
}

}  // namespace

BOOST_AUTO_TEST_CASE(power_of_two_shells) {
  // documented snapping: the largest power of two not above the distance
  BOOST_TEST(snap_to_shell(0.3) == 0.25);
  BOOST_TEST(snap_to_shell(0.25) == 0.25);
  BOOST_TEST(snap_to_shell(0.2499) == 0.125);
  BOOST_TEST(snap_to_shell(1.0) == 1.0);
  BOOST_TEST(snap_to_shell(3.0) == 2.0);
  BOOST_TEST(snap_to_shell(1e-3) == std::ldexp(1.0, -10));
}

// ---- 2D -------------------------------------------------------------------------------------
const std::array<point2, 2> seg{{{0, 0}, {1, 0}}};

BOOST_AUTO_TEST_CASE(free_vertex_is_projected) {
  const auto c = split_point(rule2(relation::free), seg, {0.3, 0.2});
  BOOST_REQUIRE(c);
  BOOST_TEST(near(c->at, point2{0.3, 0}));
  BOOST_TEST((c->action == split_action::project));
  BOOST_TEST(c->step == 1u);  // step 0, `shell`, has no centre here
}

BOOST_AUTO_TEST_CASE(projection_too_close_to_an_end_falls_back_to_midpoint) {
  for (point2 e : {point2{0.05, 0.2}, point2{0.95, -0.1}, point2{1.3, 0.2}, point2{-0.2, 0.1}}) {
    const auto c = split_point(rule2(relation::free), seg, e);
    BOOST_REQUIRE(c);
    BOOST_TEST(near(c->at, point2{0.5, 0}));
    BOOST_TEST((c->action == split_action::midpoint));
    BOOST_TEST(c->step == 2u);
  }
}

BOOST_AUTO_TEST_CASE(shell_radius_is_a_power_of_two_in_the_middle_third) {
  for (double l : {1.0, 0.75, 0.7, 3.0, 1e-3, 0.123456789, 5.5e7}) {
    const double r = shell_radius(l);
    int e = 0;
    BOOST_TEST(std::frexp(r, &e) == 0.5);  // a power of two
    BOOST_TEST(r >= l / 3);
    BOOST_TEST(r <= 2 * l / 3);
  }
}

BOOST_AUTO_TEST_CASE(shell_splits_about_the_small_angle_end) {
  // whatever the encroacher, a subsegment with a shell centre at one end is split on the shell
  // about it nearest the midpoint (the first step of every default subsegment rule)
  const std::array<point2, 2> s{{{0, 0}, {0.7, 0}}};
  for (auto rel : {relation::free, relation::on_incident_vertex, relation::on_carrier}) {
    const auto from_start = split_point(rule2(rel), s, {0.3, 0.1}, point2{0, 0}, point2{0, 0});
    BOOST_REQUIRE(from_start);
    BOOST_TEST((from_start->action == split_action::shell));
    BOOST_TEST(near(from_start->at, point2{0.25, 0}));
    const auto from_end = split_point(rule2(rel), s, {0.3, 0.1}, point2{0.7, 0}, point2{0.7, 0});
    BOOST_REQUIRE(from_end);
    BOOST_TEST(near(from_end->at, point2{0.45, 0}));  // 0.7 - 0.25
  }
}

BOOST_AUTO_TEST_CASE(dyadic_distances) {
  // the coarsest m 2^k in [lo, hi]
  BOOST_TEST(dyadic_between(3, 5) == 4.0);
  BOOST_TEST(dyadic_between(5, 7) == 6.0);
  BOOST_TEST(dyadic_between(0.54, 0.86) == 0.75);
  BOOST_TEST(dyadic_between(0.3, 0.3125) == 0.3125);
  const double r = dyadic_between(0.1, 0.1 + 1e-9);
  BOOST_TEST((r >= 0.1 && r <= 0.1 + 1e-9));
}

BOOST_AUTO_TEST_CASE(shell_splits_edges_of_different_lengths_at_one_distance) {
  // two subsegments away from the small-angle vertex (0,0), on edges of different lengths (whose
  // midpoints differ): both are split at the same dyadic distance from it, so neither split
  // encroaches the other edge's subsegment again (the cascade along edges meeting at a fraction
  // of a degree, scad_example002, came from midpoints)
  const point2 o{0, 0};
  const std::array<point2, 2> s1{{{0.5, 0}, {0.9, 0}}}, s2{{{0.5 * 0.999, 0.5 * 0.0447}, {0.95 * 0.999, 0.95 * 0.0447}}};
  const auto c1 = split_point(rule2(relation::on_incident_vertex), s1, {0.7, 0.01}, o, o);
  const auto c2 = split_point(rule2(relation::on_incident_vertex), s2, {0.7, 0.02}, o, o);
  BOOST_REQUIRE(c1);
  BOOST_REQUIRE(c2);
  BOOST_TEST((c1->action == split_action::shell && c2->action == split_action::shell));
  BOOST_TEST(std::abs(distance(c1->at, o) - 0.75) < 1e-12);
  BOOST_TEST(std::abs(distance(c2->at, o) - 0.75) < 1e-12);
}

BOOST_AUTO_TEST_CASE(a_rejected_candidate_falls_through_to_the_next_step) {
  const auto c = split_point(rule2(relation::free), seg, {0.3, 0.2}, {}, {}, [](const point2& q, split_action) { return q[0] != 0.3; });
  BOOST_REQUIRE(c);
  BOOST_TEST((c->action == split_action::midpoint));
}

BOOST_AUTO_TEST_CASE(incident_vertex_is_rotated_onto_a_shell) {
  // encroacher on a segment leaving the shared vertex (0,0) at 30 degrees, 0.3 from it
  const double a = std::numbers::pi / 6;
  const point2 e{0.3 * std::cos(a), 0.3 * std::sin(a)};
  const auto c = split_point(rule2(relation::on_incident_vertex), seg, e, point2{0, 0});
  BOOST_REQUIRE(c);
  BOOST_TEST(near(c->at, point2{0.25, 0}));
  BOOST_TEST((c->action == split_action::rotate_vertex));
  // the vertex order of the subsegment does not matter
  const std::array<point2, 2> rev{{{1, 0}, {0, 0}}};
  BOOST_TEST(near(split_point(rule2(relation::on_incident_vertex), rev, e, point2{0, 0})->at, point2{0.25, 0}));
}

BOOST_AUTO_TEST_CASE(rotation_on_a_subsegment_away_from_the_shared_vertex) {
  const std::array<point2, 2> s{{{0.5, 0}, {1.5, 0}}};
  const point2 shared{0, 0};
  // distance 1.1 -> shell 1: split at (1, 0)
  auto c = split_point(rule2(relation::on_incident_vertex), s, {0, 1.1}, shared);
  BOOST_TEST(near(c->at, point2{1, 0}));
  BOOST_TEST((c->action == split_action::rotate_vertex));
  // distance 0.9 -> shell 0.5 is the subsegment's end: not inside, midpoint instead
  c = split_point(rule2(relation::on_incident_vertex), s, {0, 0.9}, shared);
  BOOST_TEST(near(c->at, point2{1, 0}));
  BOOST_TEST((c->action == split_action::midpoint));
}

BOOST_AUTO_TEST_CASE(rotation_without_a_shared_vertex_falls_back) {
  const auto c = split_point(rule2(relation::on_incident_vertex), seg, {0.3, 0.2});
  BOOST_REQUIRE(c);
  BOOST_TEST((c->action == split_action::midpoint));
}

BOOST_AUTO_TEST_CASE(vertex_on_carrier_bisects) {
  const auto c = split_point(rule2(relation::on_carrier), seg, {0.2, 0});
  BOOST_TEST(near(c->at, point2{0.5, 0}));
}

BOOST_AUTO_TEST_CASE(acceptance_conditions) {
  const split_step gap{split_action::project, 0.1, false, 0};
  const split_step in{split_action::project, 0, true, 0};
  BOOST_TEST(accepts(gap, seg, {0.1, 0}));
  BOOST_TEST(!accepts(gap, seg, {0.0999, 0}));
  BOOST_TEST(!accepts(gap, seg, {0.9001, 0}));
  BOOST_TEST(accepts(in, seg, {1e-9, 0}));
  BOOST_TEST(!accepts(in, seg, {0, 0}));
  BOOST_TEST(!accepts(in, seg, {1, 0}));
}

// ---- 3D -------------------------------------------------------------------------------------
const std::array<point3, 3> tri{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};

BOOST_AUTO_TEST_CASE(subsegment_3d) {
  const std::array<point3, 2> s{{{0, 0, 0}, {1, 0, 0}}};
  auto c = split_point(rule3(element_kind::subsegment, relation::free), s, {0.3, 0.2, 0.7});
  BOOST_TEST(near(c->at, point3{0.3, 0, 0}));
  // on a facet containing the segment: projected as well
  c = split_point(rule3(element_kind::subsegment, relation::on_incident_edge), s, {0.6, 0.1, 0.1});
  BOOST_TEST(near(c->at, point3{0.6, 0, 0}));
  const std::array<point3, 2> up{{{0, 0, 0}, {0, 0, 1}}};
  c = split_point(rule3(element_kind::subsegment, relation::on_incident_vertex), up, {0.3, 0, 0},
                  shared3{point3{0, 0, 0}, {}, {}});
  BOOST_TEST(near(c->at, point3{0, 0, 0.25}));
  BOOST_TEST((c->action == split_action::rotate_vertex));
  c = split_point(rule3(element_kind::subsegment, relation::on_carrier), s, {0.2, 0, 0});
  BOOST_TEST(near(c->at, point3{0.5, 0, 0}));
}

BOOST_AUTO_TEST_CASE(subfacet_free_vertex_is_projected) {
  const auto c = split_point(rule3(element_kind::subfacet, relation::free), tri, {0.25, 0.25, 0.4});
  BOOST_REQUIRE(c);
  BOOST_TEST(near(c->at, point3{0.25, 0.25, 0}));
  BOOST_TEST((c->action == split_action::project));
  const auto u = unit_coordinates(std::span<const point3>(tri), c->at);
  BOOST_TEST(std::abs(u[0] - 0.5) < 1e-12);
  BOOST_TEST(std::abs(u[1] - 0.25) < 1e-12);
  BOOST_TEST(std::abs(u[2] - 0.25) < 1e-12);
}

BOOST_AUTO_TEST_CASE(subfacet_projection_outside_the_subfacet) {
  // The default 3D set projects onto the facet plane without a containment condition (the
  // conformer checks the facet itself), so a projection outside the subfacet is kept ...
  auto c = split_point(rule3(element_kind::subfacet, relation::free), tri, {0.9, 0.9, 0.3});
  BOOST_REQUIRE(c);
  BOOST_TEST(near(c->at, point3{0.9, 0.9, 0}));
  BOOST_TEST((c->action == split_action::project));
  // ... while a rule that asks for `inside` falls back to the circumcentre
  const auto custom = parse_rules(
      "dimension 3\nsplit f\n element subfacet\n relation free\n try project inside\n try midpoint\nend\n", "custom.rules");
  c = split_point(*custom.split.lookup(element_kind::subfacet, relation::free), tri, {0.9, 0.9, 0.3});
  BOOST_REQUIRE(c);
  BOOST_TEST(near(c->at, point3{0.5, 0.5, 0}));  // right triangle: hypotenuse midpoint
  BOOST_TEST((c->action == split_action::midpoint));
}

BOOST_AUTO_TEST_CASE(subfacet_rotated_about_the_shared_vertex) {
  const point3 e{0.3, 0.3, 0.2};  // |e| = sqrt(0.22) = 0.469 -> shell 0.25
  const auto c = split_point(rule3(element_kind::subfacet, relation::on_incident_vertex), tri, e,
                             shared3{point3{0, 0, 0}, {}, {}});
  BOOST_REQUIRE(c);
  const double x = 0.25 / std::sqrt(2.0);
  BOOST_TEST(near(c->at, point3{x, x, 0}));
  BOOST_TEST((c->action == split_action::rotate_vertex));
}

BOOST_AUTO_TEST_CASE(subfacet_rotated_about_the_shared_edge) {
  // facets meeting along the x axis at a 10 degree dihedral angle
  const std::array<point3, 3> t{{{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}}};
  const double a = 10 * std::numbers::pi / 180;
  const point3 e{0.4, 0.3 * std::cos(a), 0.3 * std::sin(a)};  // 0.3 from the axis -> shell 0.25
  const shared3 sh{{}, std::array<point3, 2>{point3{0, 0, 0}, point3{1, 0, 0}}, {}};
  const auto c = split_point(rule3(element_kind::subfacet, relation::on_incident_edge), t, e, sh);
  BOOST_REQUIRE(c);
  BOOST_TEST(near(c->at, point3{0.4, 0.25, 0}));
  BOOST_TEST((c->action == split_action::rotate_edge));
  // the same encroacher with the edge given in the other direction
  const shared3 rev{{}, std::array<point3, 2>{point3{1, 0, 0}, point3{0, 0, 0}}, {}};
  BOOST_TEST(near(split_point(rule3(element_kind::subfacet, relation::on_incident_edge), t, e, rev)->at,
                  point3{0.4, 0.25, 0}));
}

BOOST_AUTO_TEST_CASE(subfacet_on_carrier_uses_the_circumcentre) {
  const std::array<point3, 3> eq{{{0, 0, 1}, {2, 0, 1}, {1, std::sqrt(3.0), 1}}};
  const auto c = split_point(rule3(element_kind::subfacet, relation::on_carrier), eq, {1, 0.2, 1});
  BOOST_TEST(near(c->at, point3{1, std::sqrt(3.0) / 3, 1}, 1e-12));
}

BOOST_AUTO_TEST_CASE(actions_that_cannot_be_computed) {
  BOOST_TEST(!split_candidate(split_action::rotate_edge, std::span<const point3>(tri), {0, 0, 1}, shared3{}));
  BOOST_TEST(!split_candidate(split_action::rotate_vertex, std::span<const point3>(tri), {0, 0, 1}, shared3{}));
  const std::array<point3, 2> s{{{0, 0, 0}, {1, 0, 0}}};
  BOOST_TEST(!split_candidate(split_action::rotate_edge, std::span<const point3>(s), {0, 1, 0},
                              shared3{{}, std::array<point3, 2>{point3{0, 0, 0}, point3{1, 0, 0}}, {}}));
}
