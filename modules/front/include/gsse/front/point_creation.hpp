#pragma once
// Rule-driven point creation in the front mesher. When the Delaunay apex of a front face is too
// far for the target size h (the circumradius of face+apex exceeds too_far*h), the front rules
// (rules/front2d.rules, front3d.rules or a user's set) propose new points in the face's unit
// frame. A proposed point is inserted only if
//   - it lies inside the region (the segment from the face's centroid to it crosses no boundary
//     face of the domain),
//   - it encroaches no boundary face of the domain (outside every diametral ball, closed), and
//   - it lies in no existing cell's perturbed circumsphere,
// so every cell already made stays Delaunay, the conformed boundary stays a subcomplex of the
// Delaunay triangulation, and the gift-wrapping continues with the larger point set. The element
// itself is still the empty-sphere choice: with the new point inserted the apex search runs again.
#include <array>
#include <span>
#include <string>
#include <vector>

#include "gsse/geometry/point_grid.hpp"
#include "gsse/geometry/point.hpp"

namespace gsse::rules {
struct front_rule_set;
}

namespace gsse::front {

using geometry::point_grid;  // the candidate index (gsse/geometry/point_grid.hpp)

struct wrap_stats;

struct creation_options {
  const rules::front_rule_set* rules = nullptr;  // required
  double h = 0;                                  // target size (> 0)
  double too_far = 0.8;            // create when the apex's circumradius exceeds too_far * h
  std::size_t max_points = 50'000'000;  // per region; beyond it the region is meshed without new points
};

struct creation_stats {
  std::size_t too_far = 0;        // faces whose apex was too far
  std::size_t created = 0;        // points inserted
  std::size_t no_rule = 0;        // no rule accepted the configuration (tolerance, free zone, orientation)
  std::size_t outside = 0;        // proposed point outside the region
  std::size_t encroaching = 0;    // proposed point in a boundary face's diametral ball
  std::size_t in_circumball = 0;  // proposed point in an existing cell's circumsphere
  std::size_t not_needed = 0;     // the accepted rule creates no point (it reuses existing ones)
  creation_stats& operator+=(const creation_stats& o);
};

/// The boundary faces of the whole domain (all segments), bucketed for the encroachment and
/// crossing tests. Built once, shared read-only by regions meshed in parallel.
template <std::size_t D>
class boundary_faces {
 public:
  /// `apex` (3D, optional): per face, the apex of a face kept as a Delaunay face that is not
  /// Gabriel (conformer::boundary::face_apex), or no_vertex; such a face is broken by a point in
  /// its closed equatorial ball or, across from the apex, in the closed sphere through it and the
  /// apex (geometry::breaks_face_with_apex).
  boundary_faces(std::span<const point<D>> pts, std::span<const std::array<vertex_id, D>> faces,
                 std::span<const vertex_id> apex = {});
  ~boundary_faces();
  boundary_faces(const boundary_faces&) = delete;
  boundary_faces& operator=(const boundary_faces&) = delete;
  /// True if q lies in the closed diametral ball of some face (or breaks a kept face, above).
  bool encroached_by(const point<D>& q) const;
  /// True if the closed segment [s, q] meets some face other than `except` (same vertex set).
  bool crossed(const point<D>& s, const point<D>& q, const std::array<vertex_id, D>& except) const;

 private:
  struct impl;
  impl* impl_;
};

/// Tetrahedra filling the region bounded by `boundary` (as wrap()), creating points by the front
/// rules. `pts` holds the points of `grid` and receives the created points at its end; cells use
/// their indices.
std::vector<std::array<vertex_id, 4>> wrap_creating(std::vector<point3>& pts, const point_grid<3>& grid,
                                                    const boundary_faces<3>& faces,
                                                    const std::vector<std::array<vertex_id, 3>>& boundary,
                                                    const std::string& label, const creation_options& o,
                                                    creation_stats* cstats = nullptr, wrap_stats* stats = nullptr);
/// Triangles, 2D.
std::vector<std::array<vertex_id, 3>> wrap_creating(std::vector<point2>& pts, const point_grid<2>& grid,
                                                    const boundary_faces<2>& faces,
                                                    const std::vector<std::array<vertex_id, 2>>& boundary,
                                                    const std::string& label, const creation_options& o,
                                                    creation_stats* cstats = nullptr, wrap_stats* stats = nullptr);

}  // namespace gsse::front
