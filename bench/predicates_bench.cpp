// Exact predicates: the project's (gsse/geometry/predicates.hpp, which asks fixed_predicates.hpp
// first) against CGAL's Epick filtered predicates alone, in nanoseconds a call.
// usage: predicates_bench [REPEAT]   (default 20; prints one JSON line per case)
// Cases: "lattice ties": 10,000 cubes of side h = 0.0442 at random places of a 40^3 lattice, the
// in-sphere test of four corners against the opposite one and the equatorial test of three
// corners against a fourth (all exact ties: every filter fails); "near ties at generic places":
// the same cubes with their low corner between h/16 and h from the origin on each axis (their
// differences rarely doubles, the ties an ulp off: fixed_predicates' moved integers, CGAL's Mpzf
// before 2026-12-03); "generic": 100,000 sets of
// uniform random points in [1, 2)^3 (the filters decide). [gsse, CGAL] per predicate; the signs
// are compared one by one outside the timing (signs_differing must be 0).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "gsse/geometry/predicates.hpp"

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using gsse::point3;
K::Point_3 cg(const point3& p) { return {p[0], p[1], p[2]}; }
volatile long sink = 0;  // the untimed passes' sums land here

template <class F>
double ns_per_call(const std::vector<std::array<point3, 5>>& qs, int repeat, F&& f, long& sum) {
  // one pass untimed first: with 2 passes of the 12 MB generic set, the first pass's cold
  // memory had doubled the figure (72 ns against 24 ns once warm)
  long warm = 0;
  for (const auto& q : qs) warm += f(q);
  sink = warm;  // keeps the pass
  const auto t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < repeat; ++r)
    for (const auto& q : qs) sum += f(q);
  const auto t1 = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::nano>(t1 - t0).count() / (static_cast<double>(repeat) * static_cast<double>(qs.size()));
}
}  // namespace

int main(int argc, char** argv) {
  const int repeat = argc > 1 ? std::atoi(argv[1]) : 20;
  std::mt19937 g(1);
  std::vector<std::array<point3, 5>> ties, generic;
  std::uniform_int_distribution<int> cell(0, 40);
  const double h = 0.0442;
  for (int i = 0; i < 10000; ++i) {
    const double x = cell(g) * h, y = cell(g) * h, z = cell(g) * h;
    ties.push_back({point3{x, y, z}, point3{x + h, y, z}, point3{x, y + h, z}, point3{x, y, z + h}, point3{x + h, y + h, z + h}});
  }
  // near ties at generic places: the same cube's corners with its low corner between h/16 and h
  // from the origin on each axis, so that the coordinates' differences are rarely doubles and
  // the far corners' rounding leaves the ties an ulp off (front-rule points, circumcentres)
  std::vector<std::array<point3, 5>> moved;
  std::uniform_real_distribution<double> frac(1.0 / 16, 1.0);
  for (int i = 0; i < 10000; ++i) {
    const double x = frac(g) * h, y = frac(g) * h, z = frac(g) * h;
    moved.push_back({point3{x, y, z}, point3{x + h, y, z}, point3{x, y + h, z}, point3{x, y, z + h}, point3{x + h, y + h, z + h}});
  }
  std::uniform_real_distribution<double> u(1.0, 2.0);
  for (int i = 0; i < 100000; ++i) {
    std::array<point3, 5> q;
    for (auto& p : q)
      for (auto& c : p) c = u(g);
    generic.push_back(q);
  }
  const K k;
  const auto sphere = k.side_of_oriented_sphere_3_object();
  const auto equatorial = k.side_of_bounded_sphere_3_object();
  const auto orient = k.orientation_3_object();
  struct which {
    const char* name;
    const std::vector<std::array<point3, 5>>* qs;
  };
  for (const which& w : {which{"lattice ties", &ties}, which{"near ties at generic places", &moved}, which{"generic", &generic}}) {
    const int r = w.qs != &generic ? repeat : std::max(1, repeat / 10);
    long a = 0, b = 0;
    const double s_gsse = ns_per_call(*w.qs, r, [](const auto& q) { return gsse::geometry::in_sphere(q[0], q[1], q[2], q[3], q[4]); }, a);
    const double s_cgal = ns_per_call(*w.qs, r, [&](const auto& q) { return static_cast<int>(sphere(cg(q[0]), cg(q[1]), cg(q[2]), cg(q[3]), cg(q[4]))); }, b);
    long c = 0, d = 0;
    const double e_gsse = ns_per_call(*w.qs, r, [](const auto& q) { return gsse::geometry::in_equatorial(q[0], q[1], q[2], q[3]); }, c);
    const double e_cgal = ns_per_call(*w.qs, r, [&](const auto& q) { return static_cast<int>(equatorial(cg(q[0]), cg(q[1]), cg(q[2]), cg(q[3]))); }, d);
    long e = 0, f = 0;
    const double o_gsse = ns_per_call(*w.qs, r, [](const auto& q) { return gsse::geometry::orient3d(q[0], q[1], q[2], q[3]); }, e);
    const double o_cgal = ns_per_call(*w.qs, r, [&](const auto& q) { return static_cast<int>(orient(cg(q[0]), cg(q[1]), cg(q[2]), cg(q[3]))); }, f);
    long differ = 0;  // untimed: sign by sign
    for (const auto& q : *w.qs) {
      differ += gsse::geometry::in_sphere(q[0], q[1], q[2], q[3], q[4]) != static_cast<int>(sphere(cg(q[0]), cg(q[1]), cg(q[2]), cg(q[3]), cg(q[4])));
      differ += gsse::geometry::in_equatorial(q[0], q[1], q[2], q[3]) != static_cast<int>(equatorial(cg(q[0]), cg(q[1]), cg(q[2]), cg(q[3])));
      differ += gsse::geometry::orient3d(q[0], q[1], q[2], q[3]) != static_cast<int>(orient(cg(q[0]), cg(q[1]), cg(q[2]), cg(q[3])));
    }
    std::printf("{\"case\": \"%s\", \"in_sphere_ns\": [%.1f, %.1f], \"in_equatorial_ns\": [%.1f, %.1f], \"orient3d_ns\": [%.1f, %.1f], "
                "\"sign_sums\": [%ld, %ld, %ld, %ld, %ld, %ld], \"signs_differing\": %ld}\n",
                w.name, s_gsse, s_cgal, e_gsse, e_cgal, o_gsse, o_cgal, a, b, c, d, e, f, differ);
  }
}
