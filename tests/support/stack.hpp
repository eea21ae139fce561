#pragma once
// A test PLC shared by the sizing and refinement suites: boxes stacked in z.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "gsse/container/plc.hpp"

namespace gsse::test {

/// A generic rotation (no facet of an axis-aligned box stays parallel to an axis).
inline point3 turn(const point3& q) {
  const double a = 0.61, b = 0.37, c = 0.23;
  const point3 x{q[0], std::cos(a) * q[1] - std::sin(a) * q[2], std::sin(a) * q[1] + std::cos(a) * q[2]};
  const point3 y{std::cos(b) * x[0] + std::sin(b) * x[2], x[1], -std::sin(b) * x[0] + std::cos(b) * x[2]};
  return {std::cos(c) * y[0] - std::sin(c) * y[1], std::sin(c) * y[0] + std::cos(c) * y[1], y[2]};
}

/// turn()'s inverse (the rotations undone in reverse order): a turned stack's points in its own
/// frame, for tests that measure along the layers.
inline point3 unturn(const point3& q) {
  const double a = 0.61, b = 0.37, c = 0.23;
  const point3 y{std::cos(c) * q[0] + std::sin(c) * q[1], -std::sin(c) * q[0] + std::cos(c) * q[1], q[2]};
  const point3 x{std::cos(b) * y[0] - std::sin(b) * y[2], y[1], std::sin(b) * y[0] + std::cos(b) * y[2]};
  return {x[0], std::cos(a) * x[1] + std::sin(a) * x[2], -std::sin(a) * x[1] + std::cos(a) * x[2]};
}

/// Boxes stacked in z over [0, w] x [0, w]: layer k spans z[k]..z[k+1] and is segment k+1 (named
/// layerK+1, maximum volume max_volume[k] if given). The interfaces are shared facets; each layer
/// has its own four side facets. `rotated`: everything turned by turn().
inline plc<3> stack(double w, const std::vector<double>& z, const std::vector<double>& max_volume = {},
                    bool rotated = false) {
  plc<3> p;
  p.source = rotated ? "rotated stack" : "stack";
  const std::size_t n = z.size();
  for (double zk : z)
    for (auto [x, y] : {std::pair{0.0, 0.0}, {w, 0.0}, {w, w}, {0.0, w}}) p.points.push_back({x, y, zk});
  auto ring = [](std::size_t k) { return static_cast<vertex_id>(4 * k); };
  for (std::size_t k = 0; k < n; ++k) {
    plc_facet f;
    f.polygons.push_back({ring(k), ring(k) + 1, ring(k) + 2, ring(k) + 3});
    p.facets.push_back(f);
  }
  for (std::size_t k = 0; k + 1 < n; ++k)
    for (vertex_id s = 0; s < 4; ++s) {
      plc_facet f;
      f.polygons.push_back({ring(k) + s, ring(k) + (s + 1) % 4, ring(k + 1) + (s + 1) % 4, ring(k + 1) + s});
      p.facets.push_back(f);
    }
  for (std::size_t k = 0; k + 1 < n; ++k) {
    plc_region<3> r;
    r.at = {0.37 * w, 0.41 * w, 0.5 * (z[k] + z[k + 1])};
    r.number = static_cast<int>(k + 1);
    r.name = "layer" + std::to_string(k + 1);
    if (k < max_volume.size()) r.max_volume = max_volume[k];
    p.regions.push_back(r);
  }
  if (rotated) {
    for (auto& q : p.points) q = turn(q);
    for (auto& r : p.regions) r.at = turn(r.at);
  }
  return p;
}

}  // namespace gsse::test
