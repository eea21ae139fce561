#pragma once
// The size field h(x): the target edge length at x, which the conformer (boundary elements), the
// interior point placement and the quality refinement all obey. It is the minimum of
//
//   - the local feature size across: each face of the (unsized) conformed boundary carries
//     feature_factor * (distance to the nearest face of a facet region it does not touch whose
//     nearest point lies at least 30 degrees out of its plane: the other side of a layer, the
//     other wall of a gap; not the next-but-one facet of a tessellated curved surface), minus its
//     own radius, subdivided until no larger than that value, so a thin layer or a narrow gap gets
//     over two elements across without any user input;
//   - per segment: a maximum size (the .poly region's maximum volume, TetGen's convention, as the
//     edge of the regular tetrahedron (3D) or equilateral triangle (2D) of that volume or area,
//     or the sidecar's "sizes"), carried by the segment's boundary faces and applied inside it;
//   - interface layers: a size on the faces between two named segments;
//   - refinement boxes: a size inside an axis-aligned box;
//   - the global size (--size);
//
// each graded: a constraint of size s at a place grows by (grade - 1) per unit of distance away
// from it, so h is Lipschitz with constant grade - 1 and neighbouring elements' sizes differ by
// at most about the factor `grade`. A background mesh (nodes, cells and a size per node,
// interpolated linearly in its cells) is applied as given, not graded.
//
// Sizing only: the values are doubles that place points; they decide no topology.
#include <algorithm>
#include <array>
#include <functional>
#include <cstddef>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <span>

#include "gsse/container/plc.hpp"
#include "gsse/sizing/box_tree.hpp"

namespace gsse::sizing {

inline constexpr double unbounded = std::numeric_limits<double>::infinity();

/// What the user asked for. Segments are named by their numbers (the .poly region attribute).
template <std::size_t D>
struct spec {
  double global = 0;                    // --size; 0: none
  double grade = 1.3;                   // --grade: neighbouring sizes differ by at most this factor (> 1)
  bool feature_size = true;             // the local feature size term
  double feature_factor = 0.45;         // h = factor * local feature size (0.45: over 2 elements across)
  std::map<int, double> segment_size;   // segment number -> maximum size (sidecar "sizes", .poly volumes)
  struct box {
    point<D> lo, hi;
    double size;
    double grade = 0;  // its own growth rate away from the box (> 1); 0: `grade`
  };
  std::vector<box> boxes;               // sidecar "refine"
  struct interface_layer {
    int a, b;  // segment numbers
    double size;
    double grade = 0;  // its own growth rate away from the interface (> 1); 0: `grade`
  };
  std::vector<interface_layer> interfaces;  // sidecar "interfaces"
  struct background_mesh {
    std::vector<point<D>> points;
    std::vector<std::array<vertex_id, D + 1>> cells;
    std::vector<double> size;  // per point
    std::string source;
  };
  std::shared_ptr<const background_mesh> background;  // sidecar "background" (.node/.ele + .mtr)
  // the boundary pieces the field may cut the faces into (a piece kept counts one, a piece cut its children) before `build`
  // gives up: features far below the model's size (a 1e-8 layer) would need far more
  std::size_t max_pieces = 20'000'000;
  // a face whose pieces held while `build` cuts it reach this many has the rest of its pieces
  // counted first (depth first, holding none) against `max_pieces`: a field over the budget is
  // refused with about this many held per thread, not the whole budget (80 bytes a piece: 1.57
  // GB for a thin layer before). The field and the verdict are the same either way
  std::size_t held_face = std::size_t{1} << 21;
};

/// The maximum size of a .poly region's maximum volume (3D) or area (2D): the edge of the regular
/// simplex of that measure.
double size_of_measure(double measure, std::size_t dimension);

/// Sets spec.segment_size from the PLC's region maximum volumes (where larger than what is set).
template <std::size_t D>
void add_region_volumes(spec<D>& s, const plc<D>& p);

template <std::size_t D>
class size_field {
 public:
  size_field() = default;  // no sizing: unbounded everywhere
  /// h at x, without the per-segment interior constraint (boundary elements: the segments on both
  /// sides carry theirs through their boundary faces).
  double operator()(const point<D>& x) const;
  /// h at x inside segment `number` (also its own maximum size).
  double operator()(const point<D>& x, int number) const;
  /// min(h(x), cap): h(x) itself where it lies below cap; the search skips every term that cannot
  /// go below cap, so a small cap asks far less than h(x) does (the refinement's edge rule).
  double capped(const point<D>& x, double cap) const;
  /// min(h(x, number), cap), the same search (the placement's cubes).
  double capped(const point<D>& x, int number, double cap) const;
  /// True if h is the global size everywhere (no other term binds anywhere): the lattice paths.
  bool uniform() const { return uniform_; }
  double global() const { return global_; }
  /// The smallest value of the field (over its sources and the global size).
  double minimum() const { return minimum_; }
  /// The field's Lipschitz constant: the largest growth rate of any term, less 1 (a background
  /// mesh, applied as given, has none it knows of: infinity then).
  double slope() const { return background_ ? unbounded : max_slope_; }
  /// Segment `number`'s own maximum size (unbounded if it has none): h(x, number) is the smaller
  /// of it and h(x).
  double segment_maximum(int number) const {
    const auto it = segment_size_.find(number);
    return it == segment_size_.end() ? unbounded : it->second;
  }
  /// h(x) by visiting every term, the pieces one by one (no tree): what operator() must give, bit
  /// for bit (tests).
  double exhaustive(const point<D>& x) const;
  /// How many groups of face pieces the field searches in a frame of their own (pieces whose
  /// plane is slanted the same way; the rest are searched in the model's axes).
  std::size_t turned_groups() const {
    return static_cast<std::size_t>(std::count_if(groups_.begin(), groups_.end(), [](const face_group& g) { return g.turned; }));
  }
  /// Sources of the graded minimum (boundary face pieces), for statistics and tests.
  std::size_t sources() const {
    std::size_t n = face_pieces_.size();
    for (const auto& L : layers_) n += L.tree.size();
    return n;
  }

 private:
  template <std::size_t E>
  friend struct field_builder;
  double global_ = unbounded, slope_ = 0.3, max_slope_ = 0.3, minimum_ = unbounded;
  bool uniform_ = true;
  // boundary face pieces with their values (a term's distance is to its piece, not to the piece's
  // box: a slanted piece's box reaches up to its radius off it, and the field came out smaller on a
  // structure merely turned off the axes), and trees over their boxes in groups: pieces whose plane
  // is slanted the same way (a turned box's walls) in a tree of their own whose boxes are taken in
  // that plane's frame, where they are as tight as an axis-aligned wall's; the rest in one tree in
  // the model's axes. The boxes only prune: the distances asked are the pieces' own
  struct face_group {
    std::array<point<D>, D> axes{};  // orthonormal rows, the plane's normal last (when turned)
    bool turned = false;
    aabb<D> box = aabb<D>::empty();  // the group's pieces' box, in the model's axes
    double min_value = unbounded;
    box_tree<D> tree;                   // the pieces' boxes in the frame, padded over its rounding
    std::vector<std::uint32_t> items;  // tree item i is face_pieces_[items[i]]
  };
  std::vector<face_group> groups_;
  std::vector<std::array<point<D>, D>> face_pieces_;
  std::vector<double> face_values_;
  void group_faces();
  // v lowered by the refinement boxes' terms at x (capped and exhaustive share them)
  double box_terms(const point<D>& x, double v) const;
  // interface layers with a growth rate of their own, by slope
  struct layer {
    double slope;
    box_tree<D> tree;
    std::vector<std::array<point<D>, D>> pieces;
  };
  std::vector<layer> layers_;
  std::vector<typename spec<D>::box> boxes_;
  std::map<int, double> segment_size_;
  std::shared_ptr<const typename spec<D>::background_mesh> background_;
  box_tree<D> background_cells_;
  double background_value(const point<D>& x) const;
};

/// What the field needs of a conformed boundary (the conformer's, unsized: PLC facets conformed,
/// no size splits): its points (the PLC's first), its faces (segments in 2D, triangles in 3D),
/// the PLC facet (2D: edge) or merged facet region each face comes from, and the segment numbers
/// on its two sides (0: outside every segment).
template <std::size_t D>
struct boundary_view {
  std::span<const point<D>> points;
  std::size_t plc_points = 0;
  std::span<const std::array<vertex_id, D>> faces;
  std::span<const std::uint32_t> face_source;
  std::span<const std::array<int, 2>> sides;
  std::string source;  // the input file, for messages
};

/// What `build` throws when the features are so far below the model's size that the field would
/// need more than `spec::max_pieces` pieces; `closest` names the closest features found ("the
/// closest 5.33e-06 apart (3.08e-06 of the model's extent) at (x, y, z), facet 5 and facet 34"),
/// or is empty. Which features: the closest the faces found as far as they got, which may differ
/// between thread counts (whether the budget is exceeded does not).
struct too_fine : std::runtime_error {
  too_fine(const std::string& message, std::string closest_features)
      : std::runtime_error(message), closest(std::move(closest_features)) {}
  std::string closest;
};

/// Builds the field from the boundary. Parallel over faces; the same field for any thread count.
/// Throws too_fine when the features are so small that the field would need more than
/// `s.max_pieces` pieces (2e7), naming the closest features found. `progress` (optional) is called now and then with the faces done and their total
/// (from any worker thread, one call at a time).
template <std::size_t D>
size_field<D> build(const boundary_view<D>& b, const spec<D>& s, unsigned threads = 1,
                    const std::function<void(std::size_t, std::size_t)>& progress = {});

/// Throws too_fine exactly when `build` of the local feature size alone (spec defaults but
/// `max_pieces`) would, and keeps nothing: the pieces are counted, not stored (memory: a short
/// stack per face, where build holds every piece). For a verdict without the field: can the
/// input's features be met at all (the quality refinement asks when its bad elements keep growing).
template <std::size_t D>
void check_feature_size(const boundary_view<D>& b, std::size_t max_pieces, unsigned threads = 1);

}  // namespace gsse::sizing
