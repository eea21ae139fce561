#pragma once
// Two unit axes across a unit normal: with it, an orthonormal frame of the plane it is normal to.
#include <array>
#include <cmath>
#include <cstddef>

#include "gsse/geometry/point.hpp"

namespace gsse::geometry {

/// e1, e2 with (e1, e2, unit) orthonormal up to rounding and right-handed: e1 = unit x (the axis
/// most across the plane, which keeps it well conditioned), normalised, and e2 = unit x e1. Used
/// by the conformer's slanted facets and the size field's groups of slanted pieces.
inline std::array<point3, 2> plane_axes(const point3& unit) {
  std::size_t least = 0;
  for (std::size_t k = 1; k < 3; ++k)
    if (std::abs(unit[k]) < std::abs(unit[least])) least = k;
  point3 axis{};
  axis[least] = 1;
  point3 e1 = cross(unit, axis);
  e1 = (1.0 / std::sqrt(dot(e1, e1))) * e1;
  return {e1, cross(unit, e1)};
}

}  // namespace gsse::geometry
