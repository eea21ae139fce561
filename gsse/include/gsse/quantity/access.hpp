#pragma once
// Free-function access to the quantities of the default segment and domain models.
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "gsse/container/domain.hpp"
#include "gsse/quantity/quantity.hpp"

namespace gsse {

namespace detail {
template <std::size_t D, class Loc>
std::size_t slots(const segment<D>& s, Loc) {
  if constexpr (Loc::cells)
    return s.num_cells();
  else
    return s.vertex_slots();
}
}  // namespace detail

/// Adds a quantity of T on the vertices or cells of s; values start at `init`.
template <class T, std::size_t D, class Loc>
quantity<T, Loc> add_quantity(segment<D>& s, Loc loc, std::string name, T init = T{}) {
  return s.quantities().template add<T, Loc>(std::move(name), detail::slots(s, loc), init);
}
/// Adds the quantity to every segment of d with the same slot, so one handle serves them all.
template <class T, std::size_t D, class Loc>
quantity<T, Loc> add_quantity(domain<D>& d, Loc loc, const std::string& name, T init = T{}) {
  std::optional<quantity<T, Loc>> h;
  for (auto& s : d.segments()) {
    if (s.quantities().size() != (h ? h->slot : d.segments().front().quantities().size()))
      throw std::logic_error("gsse: segments' quantity slots diverged; add per segment instead");
    auto q = add_quantity<T>(s, loc, name, init);
    h = q;
  }
  if (!h) throw std::logic_error("gsse: add_quantity on a domain without segments");
  return *h;
}
template <class T, std::size_t D, class Loc>
std::optional<quantity<T, Loc>> find_quantity(const segment<D>& s, Loc, std::string_view name) {
  return s.quantities().template find<T, Loc>(name);
}
/// All values of q on s, indexed by vertex id (on_vertices) or cell id (on_cells).
template <class T, class Loc, std::size_t D>
std::span<T> values(segment<D>& s, quantity<T, Loc> q) {
  return s.quantities().column_of(q, detail::slots(s, Loc{}));
}
template <class T, class Loc, std::size_t D>
std::span<const T> values(const segment<D>& s, quantity<T, Loc> q) {
  return s.quantities().column_of(q);
}
template <class T, class Loc, std::size_t D>
const T& get(const segment<D>& s, quantity<T, Loc> q, std::size_t i) {
  return s.quantities().column_of(q)[i];
}
template <class T, class Loc, std::size_t D>
void put(segment<D>& s, quantity<T, Loc> q, std::size_t i, const T& v) {
  values(s, q)[i] = v;
}
template <class T, class Loc, std::size_t D>
std::string_view quantity_name(const segment<D>& s, quantity<T, Loc> q) {
  return s.quantities().meta(q.slot).name;
}

}  // namespace gsse
