#pragma once
// Ray directions for exact ray-parity tests, tried in turn when a ray touches an edge or vertex:
// fixed and "irrational", so axis-aligned input rarely meets one exactly in an edge or vertex.
// The first four are small (added to a direction, the ray stays close to it).
#include <array>

#include "gsse/geometry/point.hpp"

namespace gsse::geometry {

inline constexpr std::array<point3, 8> ray_tilts{{{0.0123, 0.0271, 0.0389},
                                                  {-0.0331, 0.0217, 0.0113},
                                                  {0.0411, -0.0193, 0.0277},
                                                  {0.0157, 0.0353, -0.0241},
                                                  {0.6123, 0.5271, 0.4389},
                                                  {-0.5331, 0.7217, 0.3113},
                                                  {0.3411, -0.6193, 0.7277},
                                                  {0.4157, 0.2353, -0.8241}}};

}  // namespace gsse::geometry
