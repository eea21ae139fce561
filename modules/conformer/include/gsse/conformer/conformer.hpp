#pragma once
// Surface conformer: refines the boundary of a PLC (plus volume points) until no subsegment has a
// vertex in its diametral ball and no subfacet has a vertex in its equatorial ball. A vertex on
// such a sphere counts as encroaching unless the element is a face of the perturbed Delaunay
// triangulation of its own vertices and all vertices on that sphere (see encroachment.hpp), so the
// conformed boundary is a subcomplex of the project's Delaunay triangulation of all vertices.
#include <array>
#include <cstddef>
#include <stdexcept>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gsse/container/plc.hpp"
#include "gsse/rules/rule_set.hpp"

namespace gsse::conformer {

template <std::size_t D>
struct boundary;
struct labelling;

class conform_error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct options {
  double size = 0;                   // > 0: also split boundary elements longer than this
  // a size that varies (the size field of modules/sizing): min(h(x), cap) at a point x of the
  // boundary (sizing::size_field::capped; the conformer passes infinity where it needs h itself,
  // a cap where it only compares h with a bound, which a capped search answers far sooner). Set,
  // it replaces `size`: PLC edges are split so that their pieces follow it, subfacets are split
  // while their circumradius exceeds h(circumcentre)/sqrt 3, and no facet lattice is seeded
  std::function<double(const point2&, double cap)> local_size2;
  std::function<double(const point3&, double cap)> local_size3;
  // the size's Lipschitz constant where known (0: unknown): the graded facet seeding then caps its
  // queries by the parent cube's value (sizing::place_points)
  double local_slope = 0;
  std::size_t max_steiner = 2'000'000;  // cap on inserted boundary points: a runaway becomes an error
  const rules::rule_set* rules = nullptr;  // nullptr: the embedded default conformer rules
  unsigned threads = 1;                    // subfacet encroachment checks run in parallel
  // 3D: a subfacet whose equatorial ball holds points is not split while it is a face of the
  // perturbed Delaunay tetrahedralization of all points (an empty sphere through it, found from
  // the points in its ball, all on one side); boundary::face_apex records the sphere. The boundary
  // is then conforming Delaunay but not Gabriel: a new point must be tested with
  // face_encroached(), not the equatorial ball alone (Delaunay refinement does; the front's point
  // creation does not, and the pipeline leaves the option off for it). encroached() still
  // reports those subfacets
  bool delaunay_faces = false;
  bool merge_coplanar = true;  // 3D: merge coplanar facets of one marker (see gsse/plc/facet_regions.hpp)
  // 3D, a uniform `size` (no local size): a facet facing a parallel facet t away across a thin
  // layer (src/thin_layers.hpp says what counts), with thin_layer x t < size, is seeded and its
  // PLC edges are split at thin_layer x t instead of `size`. 0: off. The pipeline sets it with
  // --quality from the radius-edge bound (thin_layer_ratio) unless it is set already (a negative
  // value: off): the layer's right prisms then meet the bound in the first mesh
  // (docs/design-decisions.md, "Thin layers are seeded at the gap's scale under --quality")
  double thin_layer = 0;
  // receives, per conformer round, the number of splits and which rule and action fired how
  // often (one line each); empty: no trace. The library prints nothing itself (gsse-mesh passes
  // one that prints to stderr when GSSE_CONFORM_TRACE=1).
  std::function<void(const std::string&)> trace;
  // 3D: a labelled boundary of the same PLC, if the caller has one (the pipeline's coarse model,
  // kept alive while this options object is used): which sides of each facet lie in a segment
  // (the flat-pair check on slanted facets needs it) is read from it (label_refined) instead of
  // labelling the boundary being built (15 rays over 9,800 faces and the shells: 4.5 ms of the
  // rotated MOSFET's conform stage)
  const boundary<3>* sides_from = nullptr;
  const labelling* sides_labels = nullptr;
};

/// options::thin_layer for a radius-edge bound B (3D): a right prism of height t over an
/// equilateral triangle of side a has circumradius sqrt(a^2/3 + t^2/4), so its tetrahedra's
/// radius-edge ratio is at most B while a <= t sqrt(3 B^2 - 3/4) (2.29 at B = 1.414); the spacing
/// is 0.96 of that (2.2 t at 1.414). 0 (off) below B = 1.4: at 1.2 and 1.3 the rounds took longer
/// from such walls on some benchmark structures (the trench at 1.2 did not converge in 100
/// rounds; docs/benchmarks.md, seventy-fourth part).
double thin_layer_ratio(double bound);

/// Where a vertex lies: on a PLC vertex, on a PLC edge, inside a facet (3D), or free (volume).
struct home {
  enum kind_t : unsigned char { vertex, edge, facet, free } kind = free;
  std::uint32_t id = 0;
};

template <std::size_t D>
struct boundary {
  std::vector<point<D>> points;                   // PLC points, volume points, then Steiner points
  std::vector<home> homes;                        // per point
  std::vector<std::array<vertex_id, D>> faces;    // subsegments (2D) or subfacets (3D)
  std::vector<std::uint32_t> face_source;         // PLC edge (2D) or facet (3D) of each face
  std::size_t plc_points = 0, volume_points = 0;  // the first points are the PLC's, then volume ones
  std::size_t steiner = 0;                        // boundary points inserted
  std::size_t rounds = 0;
  // 3D: per PLC point, the radius of its protecting ball (an acute vertex: no point is inserted
  // inside, shells go on outside), 0 for none; empty in 2D. A vertex inside a smooth surface
  // (facets folding by less than 15 degrees at each of its edges) where a small angle meets has
  // no ball, only shells, and here the radius its ball would have: the refinement's guard
  // (modules/refinement) excepts about it as about a ball
  std::vector<double> protect;
  // 3D: per facet of the conformer (input facets merged as by options::merge_coplanar), whether
  // its positive / negative side lies in a segment, if the conformer needed to know (slanted
  // facets); resume() takes it over instead of labelling again. Empty otherwise.
  std::vector<std::array<bool, 2>> meshed_sides;
  // 3D, options::delaunay_faces: per face, no_vertex if its closed equatorial ball holds no point;
  // else x, the apex on the side of the points in it: the sphere through the face and x is empty,
  // so the face is a Delaunay face. A new point on x's side can break it only inside the
  // equatorial ball, one on the other side only inside that sphere (face_encroached). Empty
  // without the option (every face's ball empty)
  std::vector<vertex_id> face_apex;
};

/// Whether a new point q would make face f of `b` no Delaunay face (as far as the face's
/// certificate tells; a tie counts): q in the closed equatorial ball, or, for a face kept with an
/// apex x (boundary::face_apex), q strictly on the other side in the closed sphere through the face
/// and x. Exact.
bool face_encroached(const boundary<3>& b, std::size_t f, const point3& q);

/// Conforms the PLC's boundary with respect to itself and `volume` points (which are kept as
/// given; points on the boundary become boundary vertices). Throws conform_error on invalid
/// input (degenerate elements, unsupported facet shapes) or when max_steiner is exceeded.
boundary<2> conform(const plc<2>& p, const std::vector<point2>& volume, const options& o = {});
boundary<3> conform(const plc<3>& p, const std::vector<point3>& volume, const options& o = {});

/// Resumes conforming from `previous`, a result of conform() or resume() for the same PLC, volume
/// points and options: its points keep their ids and homes, the `added` free points follow them,
/// and its faces listed in `split` (indices into previous.faces) are split as too large ones are
/// (2D: the midpoint, or a shell about a small-angle end; 3D: the circumcentre, or the subsegment
/// of its facet that it encroaches; a face no longer there is skipped). Then the usual rounds
/// until nothing is encroached. Every boundary point of `previous` stays one: the boundary is
/// only ever refined, which is what Delaunay refinement (modules/refinement) needs.
boundary<2> resume(const plc<2>& p, const boundary<2>& previous, const std::vector<point2>& added,
                   const std::vector<std::size_t>& split, const options& o = {});
boundary<3> resume(const plc<3>& p, const boundary<3>& previous, const std::vector<point3>& added,
                   const std::vector<std::size_t>& split, const options& o = {});

/// A conformer kept alive between resumes: Delaunay refinement's rounds (modules/refinement).
/// next(previous, added, split) returns a boundary as resume(p, previous, added, split, o) does.
/// Its first call is a resume(); while each next call is handed what the last one returned, the
/// conformer goes on from the state it ended in (3D: grids of the points, edge chains, facet
/// triangulations, what its last check found clean) instead of rebuilding it from `previous`:
/// a round's cost follows the points it adds, not the size of the boundary. The result is a
/// conforming refinement of `previous` like resume()'s; the two can differ in which encroacher
/// a search meets first (the grids differ), so not byte for byte. Handed another boundary, it
/// resumes from that one. After next() throws, the next call resumes afresh. 2D: resume() each
/// time (its rebuild is cheap). Keeps a reference to p: p must outlive the session.
/// start(volume) is conform(p, volume, o) itself (the same boundary), with its state kept for the
/// first next(): the first round then goes on from the conformer's own run instead of rebuilding
/// it from the boundary (on the 1e5 MOSFET that rebuild was 10 of the round's 24 ms).
template <std::size_t D>
class session {
 public:
  session(const plc<D>& p, const options& o);
  ~session();
  session(const session&) = delete;
  session& operator=(const session&) = delete;
  boundary<D> start(const std::vector<point<D>>& volume);
  boundary<D> next(const boundary<D>& previous, const std::vector<point<D>>& added, const std::vector<std::size_t>& split);
  /// Frees the kept state (the refinement calls it after its last round, before the mesh is
  /// assembled: the state is the size of the boundary); a later next() resumes afresh.
  void end();

 private:
  struct impl;
  std::unique_ptr<impl> impl_;
};

/// Post-check: every encroached element of `b`, as (face index, encroaching vertex). Empty means
/// the boundary is conforming. Decided with exact predicates and the tie rule above. In 3D it
/// checks the subfacets only: a subfacet of the Delaunay triangulation brings its edges along, so
/// that is what conformity needs. The tests hold it against an oracle that shares none of its
/// code (tests/conformer/encroachment_oracle.hpp: CGAL's predicates and Delaunay_triangulation_3,
/// brute force), which also finds no encroached subsegment on any conformed test boundary.
std::vector<std::pair<std::size_t, vertex_id>> encroached(const boundary<2>& b);
std::vector<std::pair<std::size_t, vertex_id>> encroached(const boundary<3>& b);

}  // namespace gsse::conformer
