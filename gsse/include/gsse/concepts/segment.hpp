#pragma once
// Concept Segment: a CellComplex that is one named, numbered material region.
// See docs/concepts/segment.md.
#include <string_view>

#include "gsse/concepts/cell_complex.hpp"

namespace gsse {

template <class S>
concept segment_model = cell_complex<S> && requires(const S& s) {
  { name(s) } -> std::convertible_to<std::string_view>;
  { number(s) } -> std::convertible_to<int>;
};

namespace archetypes {
template <std::size_t D>
struct segment : cell_complex<D> {
  friend std::string_view name(const segment&) { return "archetype"; }
  friend int number(const segment&) { return 1; }
};
}  // namespace archetypes

static_assert(segment_model<archetypes::segment<2>>);
static_assert(segment_model<archetypes::segment<3>>);
static_assert(!segment_model<archetypes::cell_complex<3>>);

}  // namespace gsse
