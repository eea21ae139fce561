#pragma once
// Delaunay refinement for element quality that keeps the mesh conforming Delaunay (issue 17).
//
// Ruppert's and Shewchuk's algorithm, by rounds over the whole mesh: every element whose
// radius-edge ratio exceeds the bound (2D: whose smallest angle is below it) proposes its
// circumcentre. A circumcentre inside the diametral (2D) or equatorial (3D) ball of a boundary
// face is not inserted; that face is split instead, as a too large one is (midpoint, shell,
// circumcentre or the subsegment it encroaches: the conformer's rules). The others are inserted
// free, in order of decreasing circumradius r, each at least `apart` x r from the ones taken
// before it in the round (2D: apart = 1, a batch some sequential order of Ruppert's insertions
// could have made, and so in 3D about small input angles; 3D without any: 0.9, at least
// 1.1 / bound, so the insertion radius of an element above the bound still exceeds 1.1 x its
// shortest edge; modules/refinement/README.md). The boundary is then resumed, never rebuilt
// (conformer::resume: every boundary point stays, the new free points are conformed to like
// any), labelled and meshed again.
// Decisions on the mesh (encroachment) are exact predicates; the quality test itself compares
// doubles, which only selects which points are proposed.
#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "gsse/conformer/conformer.hpp"
#include "gsse/conformer/regions.hpp"
#include "gsse/container/domain.hpp"
#include "gsse/container/plc.hpp"
#include "gsse/sizing/box_tree.hpp"

namespace gsse::refinement {

/// 3D: a graded size field for the edge rule (options::graded3): an edge of a segment longer than
/// 1.5 h at its midpoint, h the smaller of h(x) and the segment's own maximum, as the issue
/// measures it (sizing::edge_fit). Asking h at every edge's midpoint costs a microsecond or more
/// a query (millions of edges); so h is asked at the vertices (a lower bound kept across rounds,
/// vertex_sizes) and at an edge's midpoint only where the bound the Lipschitz constant gives from
/// its ends, h(m) >= h(u) - slope |uv| / 2, does not clear it. Every query is capped (h asked only
/// up to what the edges there need: sizing::size_field::capped), which keeps its search local.
struct edge_sizes {
  std::function<double(const point3&, double cap)> h;  // min(h(x), cap), without the segments' own maxima
  double slope = std::numeric_limits<double>::infinity();  // h's Lipschitz constant; infinity: ask every edge
  std::function<double(int)> segment_maximum;          // by segment number; may be empty (none)
  // a lower bound of h at each volume point of the boundary (ids plc_points + i), as the graded
  // placement knows it (sizing::place_points): those points need no query of their own. May be
  // empty
  std::vector<double> volume_lower;
};
/// plan_round's values of the graded h at the points (edge_sizes), kept across rounds as the
/// points grow: a lower bound of h at each point, h itself where `exact`.
struct vertex_sizes {
  std::vector<double> lower;
  std::vector<char> exact;
};

/// How a round re-fills its cavities (3D; 2D always uses the front mesher). insertion: each
/// segment's cavities by inserting the round's new points into its dead cells one at a time
/// (Bowyer and Watson; a new point on a facet removes the faces it splits), the front mesher only
/// for a segment where that does not end with the boundary the conformer made; front: the front
/// mesher from each cavity's boundary. The cells are the same (the perturbed Delaunay
/// triangulation is unique); their order in the mesh is not.
enum class cavity_fill { insertion, front };

struct options {
  // 3D: the radius-edge bound (circumradius / shortest edge), 2.0 by default, at least
  // min_ratio3; 2D: the smallest angle in degrees, 20.7 by default, at most max_angle2
  double bound = 0;
  // rounds before giving up (the elements left are reported); 0: 250 (cheap rounds: 2D above 30
  // degrees takes its last fixes a few per round; in 3D below 1.414 a refinement wave runs along a
  // thin layer one element a round, the FinFET at 1.2 converging in 118 rounds of about 7 ms.
  // 3D was 60 until 2026-11-28, 100 until 2026-11-29)
  std::size_t max_rounds = 0;
  std::size_t max_points = 20'000'000;  // points in the mesh before giving up
  // 3D slivers: a tetrahedron with a dihedral angle below sliver_angle or above 180 - 2 x
  // sliver_angle (5: below 5 or above 170 degrees) is refined like a bad one, by its circumcentre
  // (0: radius-edge only). Not in the theory's guarantee; converges on the benchmark structures
  double sliver_angle = 5;
  // a size field: an element too large for h(circumcentre) is refined too, whatever its shape: 2D
  // a circumradius above h / sqrt 3 (the equilateral triangle of side h), 3D an edge longer than
  // 1.5 h (the bound; the BCC lattice's own tetrahedra, edges h and 1.15 h, stay).
  // Size alone (bound = +infinity, the size rounds): 2D too measures each edge against 1.5 h at
  // its midpoint (the lattice's equilateral triangles sit exactly on the circumradius rule).
  // Empty: shape only
  std::function<double(const point2&)> size2;
  std::function<double(const point3&)> size3;
  // 2D, with size2: each segment's own maximum size, by its number (h in a segment is the smaller
  // of size2 and it, as sizing::size_field(x, number) and sizing::edge_fit have it). May be empty
  std::function<double(int)> segment_maximum2;
  // 3D, a graded size field (size3 empty): an element with an edge longer than 1.5 h at the
  // edge's midpoint is refined by its circumcentre, as a bad one (edge_sizes)
  std::shared_ptr<const edge_sizes> graded3;
  // 3D small input angles: a bad element whose circumcentre lies within acute_guard x the
  // protecting ball of an acute PLC vertex (the conformer's; shells about it) is excepted: left
  // as it is and counted (stats::excepted); so is one near a sharp input edge, one encroaching a
  // boundary face whose circumcentre lies in such a guard, and one below the spacing floor
  // (spacing_floor; stats::below_floor). 0: none
  double acute_guard = 1;
  unsigned threads = 1;
  cavity_fill fill = cavity_fill::insertion;  // how rounds re-fill their cavities (cavity_fill)
  std::function<void(const std::string&)> progress;  // one line per round, may be empty
  // called once, between rounds, when the elements above the bound have grown in `growth_rounds`
  // of the last `growth_rounds` + 2 rounds (the count of bad elements and the rounds so far;
  // a dip or two among the rises does not hide the trend): a feasibility check that
  // may throw to end the refinement with its own error. The pipeline asks the local feature size
  // whether the input's features fit the budget (a layer 5e-6 thick in a unit model does not: the
  // bad elements grew every round for 30 rounds and more, to 857,737 in 40 s). May be empty
  std::function<void(std::size_t bad, std::size_t rounds)> on_growth;
  // at 1.414 only occ_pump_nut (12 of 12 rounds) and scad_example009 (11 of 12) of the corpus
  // reach 10 of 12; they pay one field build and go on. Then scad_example001 and 004 (9 of 12).
  // 0: never asked
  std::size_t growth_rounds = 10;
};

inline constexpr double default_ratio3 = 2.0, min_ratio3 = 1.0;
inline constexpr double default_angle2 = 20.7, max_angle2 = 33.0;

/// The radius-edge bound an options::bound means in dimension D.
double ratio_bound(std::size_t dimension, double bound);

struct stats {
  std::size_t rounds = 0;
  std::size_t inserted = 0;        // free points inserted (circumcentres)
  std::size_t split_requests = 0;  // boundary faces split because a circumcentre encroached them
  std::size_t bad_left = 0;        // elements above the bound at the end (0 when it converged)
  std::size_t excepted = 0;        // of those, at a small input angle (see README)
  std::size_t below_floor = 0;     // of the excepted, those below the spacing floor (spacing_floor)
  // where: per acute PLC vertex (its index in the PLC's points), the elements excepted about it
  std::vector<std::pair<vertex_id, std::size_t>> excepted_near;
  std::size_t outside = 0;         // circumcentres left out because they lie outside every segment
  bool converged = false;
  // wall seconds spent in each step, summed over the rounds
  double plan_seconds = 0, conform_seconds = 0, label_seconds = 0, mesh_seconds = 0;
  // cells deleted and made by the rounds' cavity re-meshing; rounds meshed from scratch instead
  // (a cavity that did not close or fill its volume: a safety net, 0 on every input measured)
  std::size_t cavity_cells = 0, cavity_made = 0, full_remeshes = 0;
  // segments whose cavities the front mesher filled, a round's each counted (options::fill
  // insertion: where insertion did not give the conformer's boundary)
  std::size_t cavity_front_regions = 0;
  // each round, in order: what its plan found and chose, and its steps' wall seconds (the sums
  // above but for the plan, whose total also holds the last plan, the one no round follows). A
  // run's tail of small rounds shows here, without instrumenting the code (--stats
  // quality.refinement.per_round)
  struct round_record {
    std::size_t bad = 0, inserted = 0, split_requests = 0, cavity_cells = 0, cavity_made = 0, cavity_front_regions = 0;
    double plan_seconds = 0, conform_seconds = 0, label_seconds = 0, mesh_seconds = 0;
  };
  std::vector<round_record> per_round;
  // not empty: a round failed (its error); the mesh is the last good round's. Seen on the rotated
  // MOSFET and FinFET: after round 2 the labelling finds a region point outside the domain
  std::string failure;
};

/// Cells of every region of a labelling (in its order), in the boundary's point ids.
template <std::size_t D>
using cells_by_region = std::vector<std::vector<std::array<vertex_id, D + 1>>>;

/// What one round decides from a conforming Delaunay mesh (`cells` on the points of `b`).
/// `todo` (optional, one flag per cell): only cells flagged nonzero are measured, and the flag of
/// every one found good is cleared (remesh_cavities carries the flags of the cells that stay).
/// `balls` (optional, one per cell, those remesh_cavities keeps): the circumball of every cell
/// measured is stored, so that the cavity search does not compute it again.
template <std::size_t D>
struct plan {
  std::vector<point<D>> add;       // free points to insert
  std::vector<std::size_t> split;  // faces of b to split
  std::size_t bad = 0;             // elements above the bound (or slivers, options::sliver_angle)
  std::size_t large = 0;           // others too large for the size field (options::size2/3)
  std::size_t outside = 0;         // circumcentres outside every segment, not inserted (labels given)
  std::size_t excepted = 0;        // of those, excepted (small input angle)
  std::vector<std::pair<vertex_id, std::size_t>> excepted_near;  // per acute PLC vertex, ascending
  std::size_t below_floor = 0;     // of the excepted, those below the spacing floor (spacing_floor)
};
/// The first boundary's local spacing as a floor (3D): f(x) = min(cap, min over the vertices v of
/// the boundary the refinement starts from of (nn(v) + |x - v|)), nn(v) the shortest boundary edge
/// at v and cap the largest nn: positive and 1-Lipschitz, a stand-in for the local feature size
/// (the conformed boundary's spacing follows the features it had to resolve). A bad element whose
/// circumradius is below ratio x f(its circumcentre) is excepted and counted (below_floor).
/// Delaunay refinement at a radius-edge bound below 2, or near input angles under 90 degrees, has
/// no termination guarantee, and there boundary splits cascaded on CAD input: runs of 60 rounds
/// and points 3e-12 apart (docs/benchmarks.md, nineteenth part). With the floor, every
/// circumcentre a round inserts is at least ratio x f from every other point (its circumradius),
/// and every boundary point split for it at least 1/sqrt 2 of that; f is bounded below: a packing
/// argument ends the rounds. The circumradius, not the shortest edge: an element with a short
/// edge and a large ball (a short edge the conformer left, which refinement must grade away from)
/// is refined as before. 1/64 lies below what converging refinement reaches: the benchmark
/// structures' meshes and the refinement tests' are unchanged by it.
template <std::size_t D>
struct spacing_floor {
  sizing::box_tree<D> spacing;  // the first boundary's vertices, valued nn(v)
  sizing::box_tree<D> inputs;   // the PLC points, for reporting where
  static constexpr double default_ratio = 1.0 / 64;  // docs/benchmarks.md, nineteenth part
  double ratio = 0;
  double cap = 0;  // f's cap: the largest nn(v)
  spacing_floor(const conformer::boundary<D>& b, double ratio);
  /// Whether an element with circumcentre x and circumradius r is below the floor.
  bool below(const point<D>& x, double r) const { return r < ratio * cap && r < ratio * spacing.graded_min(x, 1.0, cap); }
  vertex_id nearest_input(const point<D>& x) const;
};
/// A cell's circumball as the cavity search bounds it (see remesh_cavities).
template <std::size_t D>
struct cell_ball {
  static constexpr double unknown = -1, flat = -2;
  point<D> at{};
  double pad = unknown;  // the ball's radius padded by its rounding; unknown or flat
};
template <std::size_t D>
using balls_by_region = std::vector<std::vector<cell_ball<D>>>;
template <std::size_t D>
plan<D> plan_round(const cells_by_region<D>& cells, const conformer::boundary<D>& b, double ratio_bound, unsigned threads,
                   const std::function<double(const point<D>&)>& size = {}, double sliver_angle = 0,
                   const conformer::labelling* labels = nullptr, std::vector<std::vector<char>>* todo = nullptr,
                   double acute_guard = 0, balls_by_region<D>* balls = nullptr,
                   const spacing_floor<D>* floor = nullptr, const edge_sizes* graded = nullptr,
                   vertex_sizes* vertex_h = nullptr, const std::function<double(int)>* segment_maximum2 = nullptr);

/// How the refinement meshes (the pipeline's mesh_segments::wrap and ::assemble): every region of
/// a labelled boundary from scratch (the first mesh, and the fallback when a round's cavities do
/// not close), and the domain made from the final cells.
template <std::size_t D>
struct meshers {
  std::function<cells_by_region<D>(const conformer::boundary<D>&, const conformer::labelling&)> wrap;
  std::function<domain<D>(const conformer::boundary<D>&, const conformer::labelling&, cells_by_region<D>)> assemble;
};

/// Meshes again only where the points of `after` that `before` lacks changed the mesh: the cells
/// of `cells` (a conforming Delaunay mesh of `before`) whose perturbed circumball holds a new
/// point or that rest on a boundary face `after` no longer has are the cavities, which the front
/// mesher fills from their boundary (with `after`'s new faces). Every cell outside them stays
/// Delaunay, so the result is the mesh a full meshing of `after` makes. Requires that `after`
/// keeps every point id of `before` (conformer::resume) and that both labellings list the same
/// regions. Returns false and leaves `cells` alone when a cavity does not close or fill its
/// volume (the caller then meshes from scratch). `removed`: cells deleted, `made`: cells made.
/// `flags` (one per cell, optional) follow their cells; every new cell gets 1.
/// `balls` (optional, one per cell): each cell's circumball as the cavity search bounds it,
/// kept from round to round (a cell never changes); a new cell gets ball::unknown.
/// `runs` (optional): per run of `cell_run` consecutive cells, the box of their
/// balls and whether one is flat, kept from round to round until a cell of the run changes: a
/// round then reads a box per run, not every cell, to find the runs no new point and no vertex of
/// a split face comes near.
inline constexpr std::size_t cell_run = 64;
template <std::size_t D>
struct run_box {
  point<D> lo{}, hi{};
  bool flat = false, valid = false;
};
template <std::size_t D>
using runs_by_region = std::vector<std::vector<run_box<D>>>;

/// A cavity boundary (`front`: faces facing into the dead cells) split into the pieces the front
/// mesher may fill apart: faces connected through shared vertices, in order of their first face;
/// then an island's piece (cells that survive with every neighbour dead, which a round of many
/// points can leave: its faces face out of it, the volume it encloses has the sign opposite to
/// that of the piece enclosing the most) joined with
/// every piece whose bounding box holds its own, the piece around it among them. Each with its
/// faces' bounding box. (Used by remesh_cavities; exposed for its tests.)
template <std::size_t D>
struct cavity_piece {
  std::vector<std::array<vertex_id, D>> faces;
  point<D> lo{}, hi{};
};
template <std::size_t D>
std::vector<cavity_piece<D>> cavity_pieces(const std::vector<point<D>>& p, const std::vector<std::array<vertex_id, D>>& front);

/// Re-meshes the cavities the points `after` adds to `before` (the cells whose circumball holds
/// one) in `cells`; false (and `cells` unchanged) where a cavity does not close or fill its
/// volume. The cavity boundary's pieces (cavity_pieces) go to the front mesher in tasks of about
/// `batch_faces` faces (a test lowers it to put every piece in a task of its own).
/// `fill` (cavity_fill, above). `front_regions` (optional): the regions the front mesher filled.
inline constexpr std::size_t default_batch_faces = 4096;
template <std::size_t D>
bool remesh_cavities(const conformer::boundary<D>& before, const conformer::boundary<D>& after,
                     const conformer::labelling& labels_before, const conformer::labelling& labels_after,
                     cells_by_region<D>& cells, unsigned threads, std::size_t* removed = nullptr, std::size_t* made = nullptr,
                     std::vector<std::vector<char>>* flags = nullptr, balls_by_region<D>* balls = nullptr,
                     runs_by_region<D>* runs = nullptr, std::size_t batch_faces = default_batch_faces,
                     cavity_fill fill = cavity_fill::insertion, std::size_t* front_regions = nullptr);

/// Refines `cells`, the mesh of boundary `b` (labelled `l`) of PLC `p`, until no element exceeds
/// the bound except the excepted ones, or the round or point cap is reached (stats says which).
/// `b` and `l` are updated with the mesh. `co`: the conformer options `b` was made with.
/// `rounds`: the conformer session that made `b` (its start()), if the caller kept one; the first
/// round then goes on from it. Without one (or handed another boundary) the first round resumes
/// the conformer from `b`.
template <std::size_t D>
domain<D> refine(const plc<D>& p, conformer::boundary<D>& b, conformer::labelling& l, cells_by_region<D> cells,
                 const conformer::options& co, const options& o, const meshers<D>& mesh, stats& st,
                 conformer::session<D>* rounds = nullptr);

}  // namespace gsse::refinement
