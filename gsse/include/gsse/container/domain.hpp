#pragma once
// Default domain model: the global points and a list of named, numbered segments.
#include <algorithm>
#include <array>
#include <deque>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "gsse/container/segment.hpp"
#include "gsse/geometry/point.hpp"

namespace gsse {

template <std::size_t D>
class domain {
 public:
  static constexpr std::size_t dimension = D;
  using point_type = point<D>;
  using segment_type = segment<D>;

  vertex_id add_point(const point_type& p) {
    points_.push_back(p);
    sync_slots();
    return static_cast<vertex_id>(points_.size() - 1);
  }
  /// A research code's own point type, adapted with BOOST_FUSION_ADAPT_STRUCT (its D members in
  /// order x, y[, z]; see gsse/geometry/point.hpp), added as it is.
  template <class P>
    requires fusion_point<P, D> && (!std::is_same_v<std::remove_cvref_t<P>, point_type>)
  vertex_id add_point(const P& p) {
    return add_point(to_point<D>(p));
  }
  void reserve_points(std::size_t n) { points_.reserve(n); }
  std::vector<point_type>& mutable_points() { return points_; }
  const std::vector<point_type>& points() const { return points_; }
  const point_type& position(vertex_id v) const { return points_[v]; }

  segment_type& add_segment(std::string name, int number) {
    if (find(name)) throw std::invalid_argument("gsse: segment '" + name + "' exists already");
    segments_.emplace_back(std::move(name), number);
    segments_.back().set_vertex_slots(points_.size());
    return segments_.back();
  }
  std::deque<segment_type>& segments() { return segments_; }
  const std::deque<segment_type>& segments() const { return segments_; }
  segment_type* find(std::string_view name) {
    for (auto& s : segments_)
      if (s.name() == name) return &s;
    return nullptr;
  }
  const segment_type* find(std::string_view name) const {
    for (auto& s : segments_)
      if (s.name() == name) return &s;
    return nullptr;
  }
  /// Faces (3D: triangles; 2D: edges) of the mesh that lie on a marked input facet (2D: segment),
  /// with that marker: data beside the topology, which the writers carry into every format
  /// (docs/io.md). Faces on unmarked (marker 0) input facets are not listed.
  struct marked_face {
    std::array<vertex_id, D> vertices;
    int marker;
  };
  std::vector<marked_face>& marked_faces() { return marked_; }
  const std::vector<marked_face>& marked_faces() const { return marked_; }
  /// Names of facet markers (from the input's sidecar, {"facets": {"77": "drain"}}).
  std::map<int, std::string>& marker_names() { return marker_names_; }
  const std::map<int, std::string>& marker_names() const { return marker_names_; }

  /// Propagates the point count to the segments' vertex-quantity slots (after bulk edits).
  void sync_slots() {
    for (auto& s : segments_) s.set_vertex_slots(points_.size());
  }

 private:
  std::vector<point_type> points_;
  std::deque<segment_type> segments_;  // deque: references stay valid as segments are added
  std::vector<marked_face> marked_;
  std::map<int, std::string> marker_names_;
};

}  // namespace gsse
