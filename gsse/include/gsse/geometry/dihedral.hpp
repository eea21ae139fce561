#pragma once
// Dihedral angles by their cosines, in double precision (a shape measure, no topology). One copy
// for the library: the refinement's sliver test and the quality summary use it.
#include <algorithm>
#include <cmath>
#include <utility>

#include "gsse/geometry/point.hpp"

namespace gsse::geometry {

/// The largest and smallest cosine of the six dihedral angles of tetrahedron c (vertex ids into
/// p): an angle below A degrees has a cosine above cos A. A NaN cosine (a degenerate element) is
/// passed over.
template <class Points, class Cell>
std::pair<double, double> dihedral_cosines(const Points& p, const Cell& c) {
  double most = -1, least = 1;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j) {
      std::size_t k = 0;
      while (k == i || k == j) ++k;
      const std::size_t l = 6 - i - j - k;
      const point3 e = p[c[j]] - p[c[i]];
      const point3 n1 = cross(e, p[c[k]] - p[c[i]]), n2 = cross(e, p[c[l]] - p[c[i]]);
      const double cosv = std::clamp(dot(n1, n2) / std::sqrt(dot(n1, n1) * dot(n2, n2)), -1.0, 1.0);
      most = std::max(most, cosv), least = std::min(least, cosv);
    }
  return {most, least};
}

}  // namespace gsse::geometry
