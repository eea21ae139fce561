#pragma once
// The unit frame of a front element. 2D: base edge p1 -> p2 along +x, unmeshed side at y > 0.
// 3D: p1 at the origin, p1 -> p2 along +x, p3 in the xy-plane at y > 0, unmeshed side at z > 0.
// Lengths are divided by the local target size h (not by the base length), so a base that is
// longer or shorter than h shows up as a deviation of its vertices from their reference position.
#include <array>
#include <cmath>
#include <cstddef>
#include <span>

#include "gsse/geometry/point.hpp"

namespace gsse::rules {

template <std::size_t D>
struct unit_frame {
  static_assert(D == 2 || D == 3);
  point<D> origin{};
  std::array<point<D>, D> axes{};  // orthonormal, right-handed
  double h = 1;

  point<D> to_unit(const point<D>& p) const {
    const point<D> d = p - origin;
    point<D> r{};
    for (std::size_t i = 0; i < D; ++i) r[i] = dot(d, axes[i]) / h;
    return r;
  }
  point<D> to_world(const point<D>& u) const {
    point<D> r = origin;
    for (std::size_t i = 0; i < D; ++i) r = r + (u[i] * h) * axes[i];
    return r;
  }
};

/// The frame of a front element given by its D vertices (edge in 2D, triangle in 3D).
/// A degenerate base yields non-finite axes; callers check with is_finite(frame.axes[0]).
template <std::size_t D>
unit_frame<D> make_unit_frame(std::span<const point<D>, D> base, double h) {
  unit_frame<D> f;
  f.origin = base[0];
  f.h = h;
  const point<D> ex = base[1] - base[0];
  f.axes[0] = (1.0 / std::sqrt(dot(ex, ex))) * ex;
  if constexpr (D == 2) {
    f.axes[1] = {-f.axes[0][1], f.axes[0][0]};
  } else {
    point3 ey = base[2] - base[0];
    ey = ey - dot(ey, f.axes[0]) * f.axes[0];  // Gram-Schmidt
    f.axes[1] = (1.0 / std::sqrt(dot(ey, ey))) * ey;
    f.axes[2] = cross(f.axes[0], f.axes[1]);
  }
  return f;
}

}  // namespace gsse::rules
