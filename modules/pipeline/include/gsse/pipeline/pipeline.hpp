#pragma once
// The meshing pipeline as composed stages. Each stage is a function object with typed input and
// output, so a research code can replace one (e.g. its own sizing) and keep the others:
//
//   plc --size_points--> volume points --conform--> boundary --label--> labelled boundary
//       --mesh_segments (parallel over segments)--> domain --verify::check (against the plc)--> report
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "gsse/conformer/conformer.hpp"
#include "gsse/conformer/regions.hpp"
#include "gsse/container/domain.hpp"
#include "gsse/container/plc.hpp"
#include "gsse/front/point_creation.hpp"
#include "gsse/refinement/refinement.hpp"
#include "gsse/sizing/fit.hpp"
#include "gsse/sizing/size_field.hpp"
#include "gsse/verify/verify.hpp"

namespace gsse::pipeline {

/// How interior points are placed when a size is given: a lattice before meshing (sizing stage),
/// or by the front rules while meshing (point creation, see front/point_creation.hpp).
enum class fill { lattice, rules };

struct options {
  double size = 0;       // target element size H; 0: no sizing (boundary conforming only)
  // graded sizing (modules/sizing): the size field is the minimum of `size`, the local feature
  // size (sizing2/3.feature_size), the PLC regions' maximum volumes and the constraints in
  // sizing2 (2D) or sizing3 (3D), graded by their `grade`. On when `graded` is set or a region
  // has a maximum volume (else `size` alone is the uniform lattice); where nothing binds below
  // `size`, the uniform lattice paths run as without it
  bool graded = false;
  sizing::spec<2> sizing2;
  sizing::spec<3> sizing3;
  fill interior = fill::lattice;
  const rules::front_rule_set* front_rules = nullptr;  // fill::rules; nullptr: the embedded default
  double too_far = front::creation_options{}.too_far;  // fill::rules: create points for faces whose apex ball exceeds too_far*H
  // Delaunay refinement for quality (modules/refinement): 3D radius-edge bound, 2D smallest angle
  // in degrees; 0: the default (2.0, 20.7 degrees)
  bool quality = false;
  double quality_bound = 0;
  double sliver_angle = refinement::options{}.sliver_angle;  // 3D, with quality: see refinement::options
  refinement::cavity_fill cavity_fill = refinement::cavity_fill::insertion;  // 3D rounds: see refinement::cavity_fill
  double acute_guard = refinement::options{}.acute_guard;  // 3D, with quality: see refinement::options
  std::size_t quality_rounds = 0;  // with quality: the round cap (0: refinement::options default)
  // a size (`size` or a graded field) without `quality`: rounds of the refinement for size
  // alone (no shape bound, no sliver rule) until no edge is longer than 1.5 h at its midpoint
  // (report::size_rounds; the placement alone left up to 25 edges of about 1.3e5 above it on the
  // 3D benchmark structures, up to 1.65 h, and with --grade up to 198 of about 7.9e4 on the 2D
  // ones; docs/benchmarks.md, forty-fifth and forty-sixth parts). false: the mesh as the
  // placement makes it
  bool size_rounds = true;
  // 3D: every boundary and interface face with an empty equatorial ball (Gabriel). Off,
  // encroached faces that are faces of the Delaunay tetrahedralization all the same are kept
  // (conformer::options::delaunay_faces), and the refinement's rounds and the front's point
  // creation (fill::rules) test their spheres: the same conforming Delaunay guarantee with fewer
  // points (docs/design-decisions.md, "Boundary faces need to be Delaunay, not Gabriel")
  bool gabriel = false;
  unsigned threads = 1;  // threads shared by the stages (0: every hardware thread, execution::thread_count)
  bool verify = false;   // run the library verifier (gsse::verify::check against the input PLC) at the end
  // measure every edge against the size at its midpoint at the end (report::size_fit; timed as
  // "size fit"): with a size field or --size only
  bool size_fit = false;
  double verify_tolerance = verify::options{}.facet_tolerance;  // the verifier's facet tolerance
  conformer::options conform{};
  // stage messages, may be empty; called from the calling thread or, while the size field is built,
  // from a worker thread (one call at a time: a callback that only prints needs no lock of its own)
  std::function<void(const std::string&)> progress;
};

struct stage_time {
  std::string stage;
  double seconds;
};

struct report {
  std::vector<stage_time> times;
  std::size_t volume_points = 0, dropped_points = 0, steiner = 0;
  bool uniform_size = true;     // the size field was one number (or there was none)
  double min_size = 0;          // the size field's smallest value (0: no sizing)
  std::size_t size_sources = 0;  // boundary pieces carrying the field's local terms
  front::creation_stats creation{};  // fill::rules
  bool quality = false;              // options::quality was set
  bool size_rounds = false;          // the refinement ran for size alone (options::size_rounds)
  bool delaunay_faces = false;       // 3D: encroached Delaunay faces were kept (options::gabriel off)
  refinement::stats refinement{};    // its rounds, insertions and the elements left above the bound
  bool size_measured = false;        // options::size_fit was set and there was a size to fit
  sizing::fit size_fit{};            // then: the edges against the size at their midpoints
  std::vector<std::string> problems;  // from the verifier, when options::verify
};

/// Stage: interior points about H apart (BCC lattice in 3D, triangular in 2D; only if `lattice`),
/// clipped to the segments (not holes) and kept at least H/2 from boundary faces, plus the user's
/// cloud points that lie inside a segment (the others are counted in `dropped`).
template <std::size_t D>
struct size_points {
  std::vector<point<D>> operator()(const plc<D>& p, double h, const std::vector<point<D>>& cloud, std::size_t& dropped,
                                   const conformer::options& co, bool lattice = true) const;
  /// For a size field: the lattice of its global size if it is uniform, else the graded
  /// placement of sizing::place_points (spacing following h, kept h/2-ish off the boundary).
  std::vector<point<D>> operator()(const plc<D>& p, const sizing::size_field<D>& h, const std::vector<point<D>>& cloud,
                                   std::size_t& dropped, const conformer::options& co) const;
};

/// Stage: conform the boundary with respect to the volume points.
template <std::size_t D>
struct conform {
  conformer::boundary<D> operator()(const plc<D>& p, const std::vector<point<D>>& volume,
                                    const conformer::options& co) const {
    return conformer::conform(p, volume, co);
  }
};

/// Stage: fill every segment by the front mesher, segments in parallel; merged deterministically
/// (segments in number order, cells in front order), unused points dropped. With `create`, the
/// front rules add interior points while meshing; since one segment's new points may lie in the
/// circumspheres of another's cells, the segments are then meshed again with all points (no
/// creation), which makes the union exactly Delaunay.
template <std::size_t D>
struct mesh_segments {
  const front::creation_options* create = nullptr;
  front::creation_stats* created = nullptr;  // filled when create is set
  domain<D> operator()(const conformer::boundary<D>& b, const conformer::labelling& l, unsigned threads) const;
  /// The two halves without point creation, for a caller that keeps the cells between meshings
  /// (modules/refinement): every region's cells in the boundary's point ids (labelling order),
  /// and the domain made from such cells (points of `pts` used by no cell dropped).
  static std::vector<std::vector<std::array<vertex_id, D + 1>>> wrap(const conformer::boundary<D>& b,
                                                                      const conformer::labelling& l, unsigned threads);
  static domain<D> assemble(const std::vector<point<D>>& pts, const conformer::labelling& l,
                            std::vector<std::vector<std::array<vertex_id, D + 1>>> cells, unsigned threads);
};

/// Element quality: radius-edge ratio (circumradius / shortest edge; 0.577 for the equilateral
/// triangle, 0.612 for the regular tetrahedron) and angles (dihedral in 3D, plane in 2D), degrees.
struct quality {
  double min_ratio = 0, median_ratio = 0, max_ratio = 0;
  double min_angle = 0, max_angle = 0;
  double shortest_edge = 0;  // the shortest edge of any element
  std::size_t elements = 0;
  // elements with an angle (dihedral in 3D, plane in 2D) below 5 or 10 degrees, or above 170
  std::size_t below5 = 0, below10 = 0, above170 = 0;
  // radius-edge ratios: elements below each bound in ratio_bounds, and above the last
  static constexpr std::array<double, 7> ratio_bounds{0.7, 0.8, 1.0, 1.2, 1.414, 2.0, 4.0};
  std::array<std::size_t, 8> ratio_histogram{};
  // smallest angle of each element, in 10-degree bins from 0 (the last: 60 and above; the regular
  // tetrahedron's dihedral angle is 70.5, the equilateral triangle's 60)
  std::array<std::size_t, 7> angle_histogram{};
};
/// The quality of every element of d, measured on `threads` threads (the same result for any).
template <std::size_t D>
quality measure(const domain<D>& d, unsigned threads = 1);

/// All stages in order.
template <std::size_t D>
domain<D> mesh(const plc<D>& p, const std::vector<point<D>>& cloud, const options& o, report& r);

}  // namespace gsse::pipeline
