#pragma once
// Interior points for a size field: a dyadic hierarchy of lattices (BCC in 3D: cube corners and
// centres, nearest-neighbour distance d; triangular in 2D, which nests as BCC does: the lattice
// of spacing d/2 holds that of d), each cube at the coarsest level
// whose spacing d is at most h at its centre and at its parent cube's centre (one of its corners:
// where h dips across a cube, the centre alone left edges up to 1.63 h) (spacings in (h/2, h],
// BCC edges up to 1.15 h; a
// stretch of 1.2 made the edges next to the boundary reach 1.9 h), so where h is one number
// (and d0 is it) the points are the BCC
// lattice of that spacing and where it varies the spacing follows it in steps of two. Candidates
// (deduplicated: levels share corners exactly, every coordinate, a cube's centre included, being
// computed by one formula as the origin plus a dyadic multiple of one spacing, so points on one
// lattice plane are exactly coplanar) are then taken greedily, coarse levels first, dropping a point that lies in no segment,
// nearer than half its spacing or graded_keep h to the boundary, or nearer to a point already taken than 0.8 of the
// smaller spacing or 0.55 h at its cube's centre (2D 0.5 h: without it a finer level's points
// crowded a coarser one's, edges below h/2). A candidate dropped by graded_keep h alone is, where
// the placement has `away`, moved graded_lift h off its nearest face and taken after the others when clear, in a segment and
// 0.65 h from every point taken. Where h is the global size, a candidate nearer than
// half its spacing to the boundary is moved 0.6 d off its nearest face instead and taken after all
// those when clear, in a segment and 0.65 h from every point taken (the uniform lattice's
// band, modules/placement/README.md step 4). The classification is parallel; the greedy pass is sequential, in a fixed
// order, so the points are the same for any thread count.
#include <functional>
#include <optional>
#include <limits>
#include <vector>

#include "gsse/sizing/size_field.hpp"

namespace gsse::sizing {

inline constexpr int no_segment = std::numeric_limits<int>::min();

/// The band next to the boundary (modules/placement/README.md, step 4), for the uniform lattice
/// and the graded points alike: a point dropped as too near a face is moved `band_lift` times the
/// spacing off it, and taken when `band_gap` times the size from every point taken.
inline constexpr double band_lift = 0.6, band_gap = 0.65;

/// Graded points keep `graded_keep` h (h at their cube's centre) off every face as well as half
/// their spacing d (in (h/2, h], so half of it alone let a point come a quarter of h near a
/// slanted facet); a candidate too near by that rule only is moved `graded_lift` h off its nearest
/// face and taken, as a band point is, when clear and band_gap h from every point taken. Chosen
/// on the benchmark structures, each also rotated, the stack and the 2D MOSFET with --grade 1.3
/// (docs/benchmarks.md, forty-third part). 3D, edges below h/2: half the spacing alone 0.8-5.0%;
/// 0.4/0.45 0.5-1.6%; 0.45/0.5 0.4-1.1%; 0.45/0.55, taken, 0.4-1.0% with at most 4 of about 2
/// million edges above 1.5 h; 0.45 h without the move left up to 119 above 1.5 h (the MOSFET).
/// 2D: 0.4/0.45, taken, 3.2% below half and 1 edge above 1.5 h on the 2D MOSFET (half the
/// spacing alone: 6.0%, 1); 0.45/0.55 1.6% but 4 of 4,077 above.
template <std::size_t D>
inline constexpr double graded_keep = D == 3 ? 0.45 : 0.4;
template <std::size_t D>
inline constexpr double graded_lift = D == 3 ? 0.55 : 0.45;

template <std::size_t D>
struct placement {
  /// Segment number containing q, or no_segment (outside every segment, in a hole).
  std::function<int(const point<D>&)> segment_of;
  /// True if q is at least `keep` from every boundary face.
  std::function<bool(const point<D>&, double keep)> clear;
  /// Optional: q moved to `lift` off its nearest face (from the closest point of it, through q)
  /// if a face lies within `keep` of q; nothing otherwise.
  std::function<std::optional<point<D>>(const point<D>&, double keep, double lift)> away;
  /// How far `segment_of` may see the boundary from where `clear` sees it (0: the same boundary;
  /// the conformer's facet seeding locates its points shifted by a facet's wall shear). A cube
  /// whose centre is in no segment and which is clear by its circumradius plus this lies wholly
  /// in no segment: it is skipped, neither asked for h nor divided.
  double slack = 0;
};

/// `lower`, if given: per point returned, a lower bound of h there (h at the centre of the cube
/// that gave it, less the field's slope times the point's distance from that centre at most), for
/// the refinement's edge rule (refinement::edge_sizes). Filled only where the slope is finite.
template <std::size_t D>
std::vector<point<D>> place_points(const size_field<D>& h, const aabb<D>& box, const placement<D>& where,
                                   unsigned threads = 1, std::vector<double>* lower = nullptr);

/// The same for any size function h(x, segment, cap) = min(h(x, segment), cap) (segment: no_segment
/// where unknown; cap: infinity where h itself is asked, else a bound h does not reach, which lets
/// a search skip more: size_field::capped); `d0` is the
/// coarsest spacing (the largest size that matters). The conformer seeds graded facets with it in
/// each facet's plane. `parent`: a cube's spacing also at most stretch * h at its parent cube's
/// centre (one of its corners), as the size field's placement asks; off, h at its centre alone.
/// `band_from`: a candidate too near a face whose cube's size is at least this (the size field's
/// placement: its global size, where h is flat) is moved off the face (`placement::away`) and
/// taken when clear, as the uniform lattice's band (modules/placement/README.md, step 4).
/// `slope`: h's Lipschitz constant where known (0: unknown); then a cube's query is capped by its
/// parent's value (in the same segment) plus slope times their centres' distance.
/// `lower`, if given: per point returned, h at its cube's centre less `slope` times the point's
/// distance from that centre at most (a lower bound of h there when h is Lipschitz with `slope`).
template <std::size_t D>
std::vector<point<D>> place_points(const std::function<double(const point<D>&, int, double)>& h, double d0, const aabb<D>& box,
                                   const placement<D>& where, unsigned threads = 1, double stretch = 1.0,
                                   bool parent = false, double band_from = unbounded, double slope = 0,
                                   std::vector<double>* lower = nullptr);

}  // namespace gsse::sizing
