#pragma once
// Front mesher: fills a region from its boundary by gift-wrapping (see gift_wrap.hpp).
// Instantiated once in the library for 3D tetrahedra, 2D triangles and planar facets of 3D PLCs.
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gsse/geometry/point_grid.hpp"
#include "gsse/geometry/point.hpp"

namespace gsse::front {

using geometry::point_grid;  // the candidate index (gsse/geometry/point_grid.hpp)

struct wrap_stats;

/// Grid over all points, shared read-only by every region meshed with them.
point_grid<3> make_grid(std::span<const point3> pts);
point_grid<2> make_grid(std::span<const point2> pts);
/// Grid over points projected by dropping `axis` (facets of a 3D PLC).
point_grid<2> make_grid(std::span<const point3> pts, int axis, std::span<const vertex_id> subset);

/// wrap() meshes a region whose bounding box holds more than this many points piece by piece,
/// split by DeWall walls (gift_wrapper::run_blocked): each piece's open faces and points then fit
/// in a core's cache. Measured on 1e6 uniform points: 0.86M tets/s as one front, 1.1-1.2M blocked
/// at 4096-16384 points (docs/benchmarks.md); the pipeline's pieces are mostly smaller already.
inline constexpr std::size_t block_points = 16384;

/// wrap() for a cavity of a Delaunay mesh (the quality refinement's): the points of `grid` below
/// `first_added` are the mesh's, those from it on (also in `added`, a grid of those only) were
/// added since; the cells are wrap()'s, and a face of old vertices searches `added` only (no
/// cell of the new mesh has only old vertices: gift_wrapper::old_faces_from).
std::vector<std::array<vertex_id, 4>> wrap_cavity(std::span<const point3> pts, const point_grid<3>& grid,
                                                  const point_grid<3>& added, vertex_id first_added,
                                                  const std::vector<std::array<vertex_id, 3>>& boundary,
                                                  const std::string& label);
std::vector<std::array<vertex_id, 3>> wrap_cavity(std::span<const point2> pts, const point_grid<2>& grid,
                                                  const point_grid<2>& added, vertex_id first_added,
                                                  const std::vector<std::array<vertex_id, 2>>& boundary,
                                                  const std::string& label);
/// Tetrahedra filling the region bounded by `boundary` (triangles oriented so that the region lies
/// on their positive side: orient3d(a,b,c,inside) > 0). Candidates are all points of `grid`.
std::vector<std::array<vertex_id, 4>> wrap(std::span<const point3> pts, const point_grid<3>& grid,
                                           const std::vector<std::array<vertex_id, 3>>& boundary,
                                           const std::string& label, wrap_stats* stats = nullptr,
                                           std::size_t max_cells = 0);
/// Triangles filling the region bounded by `boundary` (edges with the region on their left).
std::vector<std::array<vertex_id, 3>> wrap(std::span<const point2> pts, const point_grid<2>& grid,
                                           const std::vector<std::array<vertex_id, 2>>& boundary,
                                           const std::string& label, wrap_stats* stats = nullptr,
                                           std::size_t max_cells = 0);
/// A region split in two by the plane coordinate[axis] = x0 (DeWall): returns the cells with
/// vertices on both sides (a vertex with coordinate < x0 is on side 0) and leaves in `sides[k]` the
/// boundary of the rest of the region on side k, which wrap() can then mesh independently, e.g.
/// in parallel. Wall cells + side cells = the cells wrap() makes for the whole region.
std::vector<std::array<vertex_id, 4>> wrap_wall(std::span<const point3> pts, const point_grid<3>& grid,
                                                const std::vector<std::array<vertex_id, 3>>& boundary,
                                                const std::string& label, std::size_t axis, double x0,
                                                std::array<std::vector<std::array<vertex_id, 3>>, 2>& sides);
std::vector<std::array<vertex_id, 3>> wrap_wall(std::span<const point2> pts, const point_grid<2>& grid,
                                                const std::vector<std::array<vertex_id, 2>>& boundary,
                                                const std::string& label, std::size_t axis, double x0,
                                                std::array<std::vector<std::array<vertex_id, 2>>, 2>& sides);
/// A facet wrapped again after points were added: the triangles of its last wrap (all of whose
/// points are still in the grid) and the points of the grid added since (gift_wrapper::reuse).
struct facet_rewrap {
  std::span<const std::array<vertex_id, 3>> previous;
  std::span<const vertex_id> added;
};

struct facet_lines;
/// A facet triangulated again where points came (rewrap_facet_local, rewrap_frame_local): its last
/// triangles, the vertices added since and the boundary edges it was last wrapped with.
struct facet_change {
  std::span<const std::array<vertex_id, 3>> previous;
  std::span<const vertex_id> added;
  std::span<const std::array<vertex_id, 2>> old_boundary;
  /// Optional: the circles of `previous` in the kernel's coordinates (centre u, v, radius), by
  /// place, kept by the caller across calls; a NaN radius is unknown (computed here and stored),
  /// a negative one no circle (a degenerate triangle). Ignored unless its size is previous's.
  std::vector<std::array<double, 3>>* circles = nullptr;
};

/// Triangles of a planar facet of 3D points: edges with the facet on their left in the projection
/// dropping `axis`; the grid must be built with the same axis. `coplanar`: the points are exactly
/// coplanar (e.g. all share the dropped coordinate), which allows the faster exact search and,
/// with `again`, keeps every triangle of the last wrap that no added point disturbs without a
/// search (the same triangles in the same order as without it). `lines`: which points lie on
/// which PLC edge (kernels.hpp): three points of one edge are taken as collinear.
std::vector<std::array<vertex_id, 3>> wrap_facet(std::span<const point3> pts, int axis, const point_grid<2>& grid,
                                                 const std::vector<std::array<vertex_id, 2>>& boundary,
                                                 const std::string& label, wrap_stats* stats = nullptr,
                                                 std::size_t max_cells = 0, bool coplanar = false,
                                                 const facet_rewrap* again = nullptr, const facet_lines* lines = nullptr);

/// Triangles of a slanted facet: `ids` (ascending) are its points and `uv` their coordinates in
/// an orthonormal frame of its plane, right-handed about the side the boundary edges turn around
/// (the facet lies on their left in the frame). Exact 2D predicates on the frame coordinates
/// decide everything (see frame_kernel); `lines` and `again` as for wrap_facet.
std::vector<std::array<vertex_id, 3>> wrap_frame(std::span<const vertex_id> ids, std::span<const point2> uv,
                                                 const std::vector<std::array<vertex_id, 2>>& boundary,
                                                 const std::string& label, const facet_lines* lines = nullptr,
                                                 const facet_rewrap* again = nullptr);

/// The same triangles as wrap_facet / wrap_frame with `again`, by re-wrapping only the cavity: the
/// previous triangles whose (perturbed) circle holds an added point or that rest on a boundary
/// edge split since. The kept triangles keep their places; the new ones take the dead ones' places
/// in order, and the rest follow at the end.
/// Empty (no value) when the cavity is a large part of the facet or anything does not add up:
/// the caller then wraps the whole facet.
std::optional<std::vector<std::array<vertex_id, 3>>> rewrap_facet_local(std::span<const point3> pts, int axis,
                                                                        const std::vector<std::array<vertex_id, 2>>& boundary,
                                                                        const facet_change& change, const std::string& label,
                                                                        const facet_lines* lines = nullptr);
/// For a slanted facet: `ids` (ascending) and `uv` as for wrap_frame.
std::optional<std::vector<std::array<vertex_id, 3>>> rewrap_frame_local(std::span<const vertex_id> ids, std::span<const point2> uv,
                                                                        const std::vector<std::array<vertex_id, 2>>& boundary,
                                                                        const facet_change& change, const std::string& label,
                                                                        const facet_lines* lines = nullptr);

}  // namespace gsse::front
