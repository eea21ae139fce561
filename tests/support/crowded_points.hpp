#pragma once
// Points crowded as a conforming mesh crowds them near a small input angle: the point-grid and
// front-mesher tests' worst case for a uniform grid.
#include <cmath>
#include <random>
#include <vector>

#include "gsse/geometry/point.hpp"

namespace gsse::testing {

/// The unit cube's corners and n random points crowded towards the corner 0 as a conforming
/// mesh grades towards a small input angle: at distance 2^-k (k uniform in 0..20) in a random
/// direction of the positive octant.
inline std::vector<point3> crowded_cube_points(std::size_t n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> shell(0, 20);
  std::vector<point3> p;
  for (int i = 0; i < 8; ++i) p.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  while (p.size() < n + 8) {
    const point3 d{u(rng), u(rng), u(rng)};
    const double l = std::sqrt(dot(d, d));
    if (!(l > 1e-3 && l <= 1)) continue;
    const double s = std::ldexp(1.0, -shell(rng)) * u(rng) / l;
    p.push_back({s * d[0], s * d[1], s * d[2]});
  }
  return p;
}

}  // namespace gsse::testing
