#define BOOST_TEST_MODULE rules_front
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "gsse/rules/defaults.hpp"
#include "gsse/rules/unit_frame.hpp"

using namespace gsse;
using namespace gsse::rules;

namespace {

template <std::size_t D>
bool near(const point<D>& a, const point<D>& b, double tol = 1e-12) {
  return distance(a, b) <= tol;
}

const rule_set& f2() {
  static const auto s = default_rules("front2d");
  return s;
}
const rule_set& f3() {
  static const auto s = default_rules("front3d");
  return s;
}
const front_rule& named(const rule_set& s, const std::string& n) {
  for (const auto& r : s.front.rules)
    if (r.name == n) return r;
  throw std::runtime_error("no rule " + n);
}

// Two 2D rules that match an existing point (one with a free zone, one loose without).
const rule_set& matching_rules() {
  static const auto s = [] {
    auto r = parse_rules(R"(dimension 2
front close
  quality 1
  base a b
  match q at 0.5 0.8 tol 0.25
  element a b q
  remove a b
  add a q
  add q b
  free 0 0, 1 0, 0.5 0.6
end
front close-loose
  quality 1
  tolerance 2
  base a b
  match q at 0.5 0.3
  element a b q
  remove a b
  add a q
  add q b
end
)");
    require_valid(r);
    return r;
  }();
  return s;
}

// The escalation the mesher performs: the first rule of the lowest class that accepts.
template <std::size_t D>
std::pair<const front_rule*, front_result<D>> first_accepted(const rule_set& s, std::span<const point<D>, D> base,
                                                             std::span<const point<D>> cloud, double h) {
  for (const auto* r : s.front.eligible(1000))
    if (auto res = apply(*r, base, cloud, h)) return {r, res};
  return {nullptr, {}};
}

}  // namespace

BOOST_AUTO_TEST_CASE(unit_frame_2d) {
  const std::array<point2, 2> base{{{2, 1}, {2, 3}}};
  const auto f = make_unit_frame<2>(base, 2.0);
  BOOST_TEST(near(f.to_unit({2, 3}), point2{1, 0}));
  BOOST_TEST(near(f.to_unit({0, 2}), point2{0.5, 1}));  // left of the base edge: y > 0
  BOOST_TEST(near(f.to_world(f.to_unit({-3, 7})), point2{-3, 7}, 1e-12));
}

BOOST_AUTO_TEST_CASE(unit_frame_3d) {
  const std::array<point3, 3> base{{{1, 1, 1}, {1, 3, 1}, {0, 2, 1}}};
  const auto f = make_unit_frame<3>(base, 2.0);
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) BOOST_TEST(std::abs(dot(f.axes[i], f.axes[j]) - (i == j)) < 1e-15);
  BOOST_TEST(near(f.to_unit(base[1]), point3{1, 0, 0}));
  const auto u3 = f.to_unit(base[2]);
  BOOST_TEST(u3[1] > 0);
  BOOST_TEST(std::abs(u3[2]) < 1e-15);
  // the side where det(b-a, c-a, x-a) > 0 is z > 0 in the unit frame
  const point3 x{0.7, 2, 3};
  BOOST_TEST(dot(cross(base[1] - base[0], base[2] - base[0]), x - base[0]) > 0);
  BOOST_TEST(f.to_unit(x)[2] > 0);
  BOOST_TEST(near(f.to_world(f.to_unit(x)), x, 1e-12));
}

BOOST_AUTO_TEST_CASE(ideal_triangle_on_the_unit_base) {
  const auto& r = named(f2(), "triangle-ideal");
  const std::array<point2, 2> base{{{0, 0}, {1, 0}}};
  const std::vector<point2> cloud{{0, 0}, {1, 0}, {3, 3}, {0.5, -0.5}};  // base vertices and outsiders
  const auto res = apply(r, base, cloud, 1.0);
  BOOST_REQUIRE_MESSAGE(res, res.detail);
  const auto c = res.created(r);
  BOOST_REQUIRE(c.size() == 1u);
  BOOST_TEST(near(c[0], point2{0.5, std::sqrt(3.0) / 2}));
  BOOST_TEST(res.vertices.size() == 3u);
  BOOST_TEST(res.error == 0.0);
}

BOOST_AUTO_TEST_CASE(ideal_triangle_rejects_a_point_in_the_free_zone) {
  const auto& r = named(f2(), "triangle-ideal");
  const std::array<point2, 2> base{{{0, 0}, {1, 0}}};
  const std::vector<point2> cloud{{0.5, 0.5}};
  const auto res = apply(r, base, cloud, 1.0);
  BOOST_TEST(!res);
  BOOST_TEST((res.reason == rejection::free_zone));
}

BOOST_AUTO_TEST_CASE(ideal_triangle_in_world_coordinates) {
  const auto& r = named(f2(), "triangle-ideal");
  // base going up the y axis, h = 2, base length 2.2: the new point follows the actual midpoint
  const std::array<point2, 2> base{{{2, 1}, {2, 3.2}}};
  const auto res = apply(r, base, std::span<const point2>{}, 2.0);
  BOOST_REQUIRE(res);
  BOOST_TEST(std::abs(res.error - 0.1) < 1e-12);
  BOOST_TEST(near(res.created(r)[0], point2{2 - 2 * std::sqrt(3.0) / 2, 2.1}, 1e-12));
}

BOOST_AUTO_TEST_CASE(long_base_exceeds_the_tolerance) {
  const auto& r = named(f2(), "triangle-ideal");
  const std::array<point2, 2> base{{{0, 0}, {2, 0}}};
  const auto res = apply(r, base, std::span<const point2>{}, 1.0);
  BOOST_TEST((res.reason == rejection::tolerance));
  // escalation: only the class-3 rule admits a base of 2h
  const auto [rule, acc] = first_accepted<2>(f2(), base, {}, 1.0);
  BOOST_REQUIRE(rule);
  BOOST_TEST(rule->name == "triangle-low");
  BOOST_TEST(near(acc.created(*rule)[0], point2{1, 0.4}));
}

BOOST_AUTO_TEST_CASE(escalation_past_occupied_free_zones) {
  const std::array<point2, 2> base{{{0, 0}, {1, 0}}};
  const std::vector<point2> cloud{{0.5, 0.7}};  // inside the zones of classes 1 and 2
  BOOST_TEST((apply(named(f2(), "triangle-ideal"), base, cloud, 1.0).reason == rejection::free_zone));
  BOOST_TEST((apply(named(f2(), "triangle-flat"), base, cloud, 1.0).reason == rejection::free_zone));
  const auto [rule, res] = first_accepted<2>(f2(), base, cloud, 1.0);
  BOOST_REQUIRE(rule);
  BOOST_TEST(rule->quality == 3);
  BOOST_TEST(near(res.created(*rule)[0], point2{0.5, 0.4}));
}

BOOST_AUTO_TEST_CASE(flat_triangle_rule) {
  const auto& r = named(f2(), "triangle-flat");
  const std::array<point2, 2> base{{{0, 0}, {1.5, 0}}};  // deviation 0.5 <= 0.6
  const auto res = apply(r, base, std::span<const point2>{}, 1.0);
  BOOST_REQUIRE(res);
  BOOST_TEST(near(res.created(r)[0], point2{0.75, 0.6}));
}

BOOST_AUTO_TEST_CASE(regular_tetrahedron_on_the_unit_base) {
  const auto& r = named(f3(), "tetrahedron-ideal");
  const std::array<point3, 3> base{{{0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}}};
  const std::vector<point3> cloud{{0, 0, 0}, {2, 2, 2}, {0.3, 0.3, -0.5}};
  const auto res = apply(r, base, cloud, 1.0);
  BOOST_REQUIRE_MESSAGE(res, res.detail);
  const auto d = res.created(r)[0];
  BOOST_TEST(near(d, point3{0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3)}, 1e-12));
  for (const auto& b : base) BOOST_TEST(std::abs(distance(b, d) - 1) < 1e-12);  // regular
  // a point inside the free zone
  const std::vector<point3> busy{{0.5, 0.3, 0.5}};
  BOOST_TEST((apply(r, base, busy, 1.0).reason == rejection::free_zone));
  // the flatter class-2 rule has a lower zone and accepts a point that high above
  const std::vector<point3> high{{0.5, 0.3, 0.9}};
  BOOST_TEST((apply(r, base, high, 1.0).reason == rejection::free_zone));
  const auto [rule, acc] = first_accepted<3>(f3(), base, high, 1.0);
  BOOST_REQUIRE(rule);
  BOOST_TEST(rule->name == "tetrahedron-flat");
  BOOST_TEST(near(acc.created(*rule)[0], point3{0.5, std::sqrt(3.0) / 6, 0.55}, 1e-12));
}

BOOST_AUTO_TEST_CASE(tetrahedron_follows_the_base_orientation) {
  const auto& r = named(f3(), "tetrahedron-ideal");
  // the same triangle listed clockwise seen from +z: the unmeshed side is z < 0
  const std::array<point3, 3> base{{{0, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}, {1, 0, 0}}};
  const auto res = apply(r, base, std::span<const point3>{}, 1.0);
  BOOST_REQUIRE(res);
  BOOST_TEST(res.created(r)[0][2] < -0.8);
}

BOOST_AUTO_TEST_CASE(degenerate_base) {
  const auto& r = named(f3(), "tetrahedron-ideal");
  const std::array<point3, 3> base{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}};
  BOOST_TEST((apply(r, base, std::span<const point3>{}, 1.0).reason == rejection::degenerate_base));
}

// A custom rule that matches an existing point instead of creating one.
BOOST_AUTO_TEST_CASE(matching_an_existing_point) {
  const auto& s = matching_rules();
  const auto& r = s.front.rules[0];
  const std::array<point2, 2> base{{{0, 0}, {1, 0}}};
  const std::vector<point2> cloud{{3, 0}, {0.55, 0.75}, {0.5, 1.2}};
  auto res = apply(r, base, cloud, 1.0);
  BOOST_REQUIRE_MESSAGE(res, res.detail);
  BOOST_TEST(res.matched == std::vector<std::size_t>{1});
  BOOST_TEST(near(res.vertices[2], point2{0.55, 0.75}));
  BOOST_TEST(res.created(r).empty());
  // nearest candidate too far from the reference position
  const std::vector<point2> far{{0.5, 1.2}};
  BOOST_TEST((apply(r, base, far, 1.0).reason == rejection::tolerance));
  BOOST_TEST((apply(r, base, std::span<const point2>{}, 1.0).reason == rejection::no_match));
  // an unmatched point in the free zone
  const std::vector<point2> busy{{0.5, 0.8}, {0.5, 0.2}};
  BOOST_TEST((apply(r, base, busy, 1.0).reason == rejection::free_zone));
  // a point matched below the base would give a clockwise triangle
  const std::vector<point2> below{{0.5, -0.2}};
  res = apply(s.front.rules[1], base, below, 1.0);
  BOOST_TEST((res.reason == rejection::orientation));
  BOOST_TEST(res.detail == "element (a b q) is not positively oriented");
}

BOOST_AUTO_TEST_CASE(convex_piece_test) {
  const std::vector<point3> sq{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  BOOST_TEST(in_convex_piece(2, sq, {0.5, 0.2, 0}, 1e-9));
  BOOST_TEST(!in_convex_piece(2, sq, {0.5, 0, 0}, 1e-9));  // on the boundary: not strictly inside
  BOOST_TEST(in_convex_piece(2, sq, {0.5, 0, 0}, -1e-9));
  BOOST_TEST(!in_convex_piece(2, sq, {1.5, 0.5, 0}, 0));
  const std::vector<point3> cube{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                                 {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  BOOST_TEST(in_convex_piece(3, cube, {0.5, 0.5, 0.5}, 1e-9));
  BOOST_TEST(!in_convex_piece(3, cube, {0.5, 0.5, 1.01}, 0));
  BOOST_TEST(!in_convex_piece(3, cube, {1.01, 0.5, 0.5}, 0));
}

// The prepared path the mesher takes (one unit frame per face rotation for all rules, the free
// zones made ready, only the cloud within the rules' reach mapped) decides as apply(r, base,
// cloud, h) does: random faces and clouds, points put in and next to the free zones, at the base
// vertices and next to the matched points' references. (A rejection's reason may differ in one
// way: a matched point whose nearest cloud point lies beyond reach is "no match" where the full
// mapping says "tolerance exceeded".)
template <std::size_t D>
void prepared_agrees(const std::vector<const front_rule*>& rules, unsigned seed, std::size_t& accepted, std::size_t& rejected) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  double reach_all = 0;
  for (const auto* r : rules) reach_all = std::max(reach_all, reach(*r));
  for (int trial = 0; trial < 4000; ++trial) {
    const double h = std::ldexp(1.0, static_cast<int>(g() % 7) - 3) * (1 + 0.1 * u(g));
    point<D> origin;
    for (auto& x : origin) x = 10 * u(g);
    // a face near the reference base, turned (3D: about a random axis), scaled by h
    std::array<point<D>, D> base;
    std::array<point3, 3> ref{base_reference(static_cast<int>(D), 0), base_reference(static_cast<int>(D), 1), base_reference(static_cast<int>(D), 2)};
    const double a = 3.2 * u(g), b = 3.2 * u(g);
    auto turn = [&](point3 v) {
      point3 w{std::cos(a) * v[0] - std::sin(a) * v[1], std::sin(a) * v[0] + std::cos(a) * v[1], v[2]};
      if constexpr (D == 3) w = {w[0], std::cos(b) * w[1] - std::sin(b) * w[2], std::sin(b) * w[1] + std::cos(b) * w[2]};
      return w;
    };
    auto world = [&](point3 v) {
      const point3 w = turn(v);
      point<D> q;
      for (std::size_t k = 0; k < D; ++k) q[k] = origin[k] + h * w[k];
      return q;
    };
    for (std::size_t i = 0; i < D; ++i) {
      point3 v = ref[i];
      for (std::size_t k = 0; k < D; ++k) v[k] += 0.15 * u(g);
      base[i] = world(v);
    }
    std::vector<point<D>> cloud(base.begin(), base.end());
    const std::size_t n = g() % 24;
    for (std::size_t j = 0; j < n; ++j) {
      point3 v{};
      const auto* r = rules[g() % rules.size()];
      switch (g() % 4) {
        case 0:  // anywhere within 3.5 h, most of it beyond every rule's reach
          for (std::size_t k = 0; k < D; ++k) v[k] = 3.5 * u(g);
          break;
        case 1:  // next to a free-zone vertex
          if (!r->free_zone.empty()) {
            const auto& piece = r->free_zone[g() % r->free_zone.size()];
            v = piece[g() % piece.size()];
          }
          for (std::size_t k = 0; k < D; ++k) v[k] += 0.3 * u(g);
          break;
        case 2:  // next to a matched point's reference, or a created point's
          if (r->vertex_count() > D) v = r->reference(D + g() % (r->vertex_count() - D));
          for (std::size_t k = 0; k < D; ++k) v[k] += 0.4 * u(g);
          break;
        default:  // just beyond the reach of the farthest rule
          for (std::size_t k = 0; k < D; ++k) v[k] = u(g);
          v = (reach_all * (1 + 1e-3 * (1 + u(g))) / std::sqrt(dot(v, v) + 1e-300)) * v;
          break;
      }
      if constexpr (D == 2) v[2] = 0;
      cloud.push_back(world(v));
    }
    constexpr std::size_t rotations = D == 3 ? 3 : 1;
    std::array<std::array<point<D>, D>, rotations> turned;
    std::array<front_frame<D>, rotations> frames;
    for (std::size_t rot = 0; rot < rotations; ++rot) {
      for (std::size_t i = 0; i < D; ++i) turned[rot][i] = base[(i + rot) % D];
      frames[rot] = prepare(std::span<const point<D>, D>(turned[rot]), std::span<const point<D>>(cloud), h, reach_all);
    }
    for (const auto* r : rules) {
      const auto zone = zone_of(*r);
      for (std::size_t rot = 0; rot < rotations; ++rot) {
        const auto full = apply(*r, std::span<const point<D>, D>(turned[rot]), std::span<const point<D>>(cloud), h);
        const auto fast = apply(*r, zone, frames[rot]);
        BOOST_REQUIRE_EQUAL(static_cast<bool>(full), static_cast<bool>(fast));
        if (full) {
          ++accepted;
          BOOST_REQUIRE(full.matched == fast.matched);
          BOOST_REQUIRE_EQUAL(full.error, fast.error);
          BOOST_REQUIRE(full.vertices == fast.vertices);
        } else {
          ++rejected;
          if (full.reason != fast.reason)
            BOOST_REQUIRE((full.reason == rejection::tolerance && fast.reason == rejection::no_match));
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(prepared_frames_decide_as_apply) {
  std::size_t accepted = 0, rejected = 0;
  std::vector<const front_rule*> r2 = f2().front.eligible(1000);
  for (const auto& r : matching_rules().front.rules) r2.push_back(&r);
  prepared_agrees<2>(r2, 7, accepted, rejected);
  prepared_agrees<3>(f3().front.eligible(1000), 11, accepted, rejected);
  BOOST_TEST_MESSAGE("accepted " << accepted << ", rejected " << rejected);
  // both outcomes are exercised, many times
  BOOST_TEST(accepted > 2000u);
  BOOST_TEST(rejected > 2000u);
}

// The worked example of docs/rules.md.
BOOST_AUTO_TEST_CASE(worked_example_tall2d) {
  const auto s = load_rules(default_rules_path("examples/tall2d.rules"));
  BOOST_TEST(validate(s).empty());
  const std::array<point2, 2> base{{{0, 0}, {1, 0}}};
  // empty neighbourhood: nothing to reuse, the tall apex is created
  auto [rule, res] = first_accepted<2>(s, base, {}, 1.0);
  BOOST_REQUIRE(rule);
  BOOST_TEST(rule->name == "tall-triangle");
  BOOST_TEST(near(res.created(*rule)[0], point2{0.5, 1.3}));
  // an existing point near the apex is reused
  const std::vector<point2> near_apex{{0.45, 1.2}};
  std::tie(rule, res) = first_accepted<2>(s, base, near_apex, 1.0);
  BOOST_REQUIRE(rule);
  BOOST_TEST(rule->name == "reuse-apex");
  BOOST_TEST(res.matched == std::vector<std::size_t>{0});
  // a point low above the base blocks both class-1 rules; the fallback fits below it
  const std::vector<point2> low{{0.5, 0.7}};
  std::tie(rule, res) = first_accepted<2>(s, base, low, 1.0);
  BOOST_REQUIRE(rule);
  BOOST_TEST(rule->name == "fallback");
  BOOST_TEST(near(res.created(*rule)[0], point2{0.5, 0.5}));
}
