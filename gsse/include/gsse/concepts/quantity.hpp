#pragma once
// Concept Quantity: a typed handle Q giving access to values of Q::value_type on the vertices or
// cells (Q::location) of a segment S. See docs/concepts/quantity.md.
#include <concepts>
#include <cstddef>
#include <ranges>
#include <string_view>

#include "gsse/quantity/quantity.hpp"

namespace gsse {

template <class Q, class S>
concept quantity_of = requires(S& s, const S& cs, Q q, std::size_t i, typename Q::value_type x) {
  typename Q::value_type;
  typename Q::location;
  requires std::same_as<typename Q::location, on_vertices_t> || std::same_as<typename Q::location, on_cells_t>;
  { values(s, q) } -> std::ranges::random_access_range;
  { get(cs, q, i) } -> std::convertible_to<typename Q::value_type>;
  put(s, q, i, x);
  { quantity_name(cs, q) } -> std::convertible_to<std::string_view>;
};

namespace archetypes {
struct quantity_segment {
  friend std::span<double> values(quantity_segment&, quantity<double, on_cells_t>) { return {}; }
  friend double get(const quantity_segment&, quantity<double, on_cells_t>, std::size_t) { return 0; }
  friend void put(quantity_segment&, quantity<double, on_cells_t>, std::size_t, double) {}
  friend std::string_view quantity_name(const quantity_segment&, quantity<double, on_cells_t>) { return "q"; }
};
}  // namespace archetypes

static_assert(quantity_of<quantity<double, on_cells_t>, archetypes::quantity_segment>);
static_assert(!quantity_of<quantity<int, on_cells_t>, archetypes::quantity_segment>);

}  // namespace gsse
