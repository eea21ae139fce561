#pragma once
// Region labelling of a conformed boundary: which segment lies on each side of each boundary face.
//
// Sides of faces are glued into shells by sorting the faces around every edge (2D: the segments
// around every vertex) with exact orientation tests: the two sides facing into each wedge between
// consecutive faces belong to the same region. A shell's side is linked to the shell its interior
// ray hits first (cells with inner shells), or marked unbounded. Region and hole points are then
// located by ray casting. Ray hits are exact segment/face crossing tests; a ray through an edge or
// vertex is re-cast in another fixed direction.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "gsse/conformer/conformer.hpp"

namespace gsse::conformer {

inline constexpr int exterior = -1;  // unbounded cell or hole: not meshed

struct labelling {
  /// Region index (into `regions`) on the positive and negative side of every face, or exterior.
  std::vector<std::array<int, 2>> side;
  struct region {
    int number;
    std::string name;
  };
  std::vector<region> regions;
};

/// Labels the faces of b using the PLC's region and hole points. Throws conform_error for a
/// non-closed boundary, overlapping faces, a region point on the boundary or outside the domain,
/// a bounded region without a region point (when some region points are given), or two
/// different region numbers in one region. `threads` share the work; the result (and the error,
/// if any) is the same for any number.
labelling label(const boundary<2>& b, const plc<2>& p, unsigned threads = 1);
labelling label(const boundary<3>& b, const plc<3>& p, unsigned threads = 1);

/// Labels b, a refinement of `before` (a resume() of it: the same PLC edges and facets, split
/// finer), from before's labelling l: where all faces of a PLC edge (2D) or facet (3D) had the
/// same sides, the new faces of it take them (every point of the facet had them); if any source
/// had faces with different sides (a facet with another standing on it), label(b, p, threads).
/// The result is label(b, p, threads)'s, without its shell building and ray casting.
labelling label_refined(const boundary<2>& b, const plc<2>& p, const boundary<2>& before, const labelling& l,
                        unsigned threads = 1);
labelling label_refined(const boundary<3>& b, const plc<3>& p, const boundary<3>& before, const labelling& l,
                        unsigned threads = 1);

/// Region index of each query point (exterior if outside every segment or in a hole), for
/// classifying volume points; exact ray casting against the labelled faces.
std::vector<int> locate(const boundary<2>& b, const labelling& l, const std::vector<point2>& q);
std::vector<int> locate(const boundary<3>& b, const labelling& l, const std::vector<point3>& q);

}  // namespace gsse::conformer
