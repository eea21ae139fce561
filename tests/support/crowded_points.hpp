#pragma once
// Points crowded as a conforming mesh crowds them near a small input angle: the point-grid and
// front-mesher tests' worst case for a uniform grid.
#include <cmath>
#include <random>
#include <vector>

#include "gsse/geometry/point.hpp"

namespace gsse::testing {

/// The unit box's 2^D corners and n random points crowded towards the corner 0 as a conforming
/// mesh grades towards a small input angle: at a distance uniform in (0, 2^-k] (k uniform in
/// 0..20) in a random direction of the positive orthant.
template <std::size_t D>
std::vector<point<D>> crowded_points(std::size_t n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> shell(0, 20);
  std::vector<point<D>> p;
  for (std::size_t i = 0; i < (std::size_t{1} << D); ++i) {
    point<D> c;
    for (std::size_t k = 0; k < D; ++k) c[k] = double((i >> k) & 1);
    p.push_back(c);
  }
  while (p.size() < n + (std::size_t{1} << D)) {
    point<D> d;
    for (auto& x : d) x = u(rng);
    const double l = std::sqrt(dot(d, d));
    if (!(l > 1e-3 && l <= 1)) continue;
    const double s = std::ldexp(1.0, -shell(rng)) * u(rng) / l;
    for (auto& x : d) x *= s;
    p.push_back(d);
  }
  return p;
}

/// The unit cube's corners (ids 0-7, x + 2y + 4z) and n crowded points (crowded_points<3>).
inline std::vector<point3> crowded_cube_points(std::size_t n, std::mt19937_64& rng) { return crowded_points<3>(n, rng); }

}  // namespace gsse::testing
