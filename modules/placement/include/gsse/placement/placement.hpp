#pragma once
// Where the interior (volume) points go before the boundary is conformed
// (modules/placement/README.md): a uniform lattice about H apart kept off the boundary, or the
// graded points a size field asks for (sizing::place_points), and the user's cloud; every point
// kept only inside a segment, as an exact look-up in a mesh of the segments says
// (location::locator). Doubles place points (distances to faces, lattice coordinates); they decide
// no topology.
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "gsse/geometry/point.hpp"
#include "gsse/location/locator.hpp"
#include "gsse/sizing/size_field.hpp"
#include "gsse/topology/simplex.hpp"

namespace gsse::placement {

/// The boundary the points keep off: its points and faces (D vertices each).
template <std::size_t D>
struct surface {
  std::span<const point<D>> points;
  std::span<const std::array<vertex_id, D>> faces;
};

/// Lattice points about h apart inside the segments `at` holds: BCC in 3D (nearest neighbours h
/// apart), triangular in 2D, the origin shifted by odd fractions of a step so that points rarely
/// sit on axis-aligned input planes; each a hair over h/2 from every face of `b` (a point nearer
/// a facet would be projected onto it, leaving a very short edge). Located exactly once per set
/// of clear lattice neighbours (no face passes between two of them). Then the band the h/2 leaves
/// next to the boundary: each lattice point dropped there moved to 0.6 h off its nearest face, and
/// added when clear, in a segment and 0.65 h from every point kept so far (README, step 4). In
/// lattice order, the same for any thread count. None when h <= 0.
template <std::size_t D>
std::vector<point<D>> lattice_points(const surface<D>& b, const location::locator<D>& at, double h, unsigned threads);

/// The points the size field h asks for (sizing::place_points over the box of `at`): a candidate
/// counts for the segment `numbers[region]` that holds it (sizing::no_segment outside), and keeps
/// the distance the placement asks from every face of `b`. `lower`: per point, a lower bound of h
/// there (sizing::place_points), if given.
template <std::size_t D>
std::vector<point<D>> field_points(const surface<D>& b, const location::locator<D>& at, const std::vector<int>& numbers,
                                   const sizing::size_field<D>& h, unsigned threads, std::vector<double>* lower = nullptr);

/// The user's cloud points that lie in a segment appended to `out` (the others counted in
/// `dropped`); then `out` sorted (lexicographically) and its duplicates removed (a cloud point may
/// repeat a lattice point or another one). `values`, if given, holds one number per point of `out`
/// and goes along: 0 for a cloud point, the largest of a repeated point's.
template <std::size_t D>
void add_cloud(std::vector<point<D>>& out, const std::vector<point<D>>& cloud, const location::locator<D>& at,
               std::size_t& dropped, unsigned threads, std::vector<double>* values = nullptr);

}  // namespace gsse::placement
