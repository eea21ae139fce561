#pragma once
// Concept Domain: global points plus a random-access range of segments sharing them.
// See docs/concepts/domain.md.
#include <array>
#include <vector>

#include "gsse/concepts/segment.hpp"
#include "gsse/geometry/point.hpp"

namespace gsse {

template <class Dm>
concept domain_model = requires(const Dm& d, vertex_id v) {
  requires dimension_v<Dm> == 2 || dimension_v<Dm> == 3;
  { num_points(d) } -> std::convertible_to<std::size_t>;
  { position(d, v) } -> std::convertible_to<point<dimension_v<Dm>>>;
  { segments(d) } -> std::ranges::random_access_range;
  requires segment_model<std::ranges::range_value_t<decltype(segments(d))>>;
  requires dimension_v<std::ranges::range_value_t<decltype(segments(d))>> == dimension_v<Dm>;
};

namespace archetypes {
template <std::size_t D>
struct domain {
  static constexpr std::size_t dimension = D;
  friend std::size_t num_points(const domain&) { return 0; }
  friend point<D> position(const domain&, vertex_id) { return {}; }
  friend const std::vector<segment<D>>& segments(const domain&) {
    static const std::vector<segment<D>> none;
    return none;
  }
};
}  // namespace archetypes

static_assert(domain_model<archetypes::domain<2>>);
static_assert(domain_model<archetypes::domain<3>>);

}  // namespace gsse
