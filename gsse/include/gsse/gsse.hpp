#pragma once
// Umbrella header of the gsse core.
#include "gsse/concepts/cell_complex.hpp"
#include "gsse/concepts/domain.hpp"
#include "gsse/concepts/quantity.hpp"
#include "gsse/concepts/segment.hpp"
#include "gsse/container/domain.hpp"
#include "gsse/geometry/point.hpp"
#include "gsse/geometry/predicates.hpp"
#include "gsse/quantity/access.hpp"
#include "gsse/topology/incidence.hpp"
#include "gsse/traversal/for_each.hpp"

namespace gsse {
static_assert(domain_model<domain<2>> && domain_model<domain<3>>);
static_assert(segment_model<segment<2>> && segment_model<segment<3>>);
static_assert(quantity_of<quantity<double, on_vertices_t>, segment<3>>);
static_assert(quantity_of<quantity<int, on_cells_t>, segment<2>>);
}  // namespace gsse
