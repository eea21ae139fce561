#pragma once
// Region points for surface models. A Gmsh surface mesh names its volumes by their bounding
// surfaces but gives no point inside them; the labelling (modules/conformer) locates segments by
// region points. interior_points finds, for each volume, a point strictly inside it and on no
// facet, deciding with exact predicates only (the I/O module that reads the files has none).
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gsse/container/plc.hpp"

namespace gsse::plc_tools {

/// One point strictly inside each volume, or nullopt where none was found (a volume too thin for
/// a double between its walls, or a boundary that is not closed). `volumes[k]` lists the facets
/// (indices into p.facets) bounding volume k: a closed surface, every edge in an even number of
/// them. Facet polygons are fanned into triangles (even-odd over the fan is the polygon).
///
/// For the largest triangles of the volume first, a ray leaves the triangle's centroid along its
/// normal to one side, then the other; the first facet of p it crosses (exact segment/triangle
/// tests; a ray through an edge or vertex is tilted and cast again) ends a segment that crosses no
/// facet, and its midpoint is the candidate. A candidate is kept if a ray from it crosses the
/// volume's boundary an odd number of times, touches no edge or vertex (else another direction),
/// and it lies on no facet of p. `threads` share the volumes; the result does not depend on them.
std::vector<std::optional<point3>> interior_points(const plc<3>& p,
                                                   const std::vector<std::vector<std::size_t>>& volumes,
                                                   unsigned threads = 1);

/// A connected piece of facets bounding no volume, left out by drop_stray_facets.
struct stray_piece {
  std::size_t facet = 0;   // its first facet (index before the removal)
  std::size_t facets = 0;  // how many
  std::size_t line = 0;    // the first facet's input line
};

/// Gmsh writes every surface of a model, also those that bound no volume and lie outside them
/// all (a surface left over from construction, a cut face). Such pieces (facets of no volume in
/// `volumes`, connected through shared edges) are removed from p with the points only they use,
/// and the volumes' facet indices renumbered. A piece counts as outside when sample points of it
/// (triangle centroids of its first, middle and last facets) are strictly outside every volume
/// by exact ray parity; pieces partly or wholly inside a volume (embedded surfaces) stay.
std::vector<stray_piece> drop_stray_facets(plc<3>& p, std::vector<std::vector<std::size_t>>& volumes,
                                           unsigned threads = 1);
/// The same for volume records (a type with `facets`, such as gsse::io::plc_volume).
template <class Volume>
std::vector<stray_piece> drop_stray_facets(plc<3>& p, std::vector<Volume>& volumes, unsigned threads = 1) {
  std::vector<std::vector<std::size_t>> facets;
  for (const auto& v : volumes) facets.push_back(v.facets);
  auto out = drop_stray_facets(p, facets, threads);
  for (std::size_t k = 0; k < volumes.size(); ++k) volumes[k].facets = std::move(facets[k]);
  return out;
}

/// Facets of no volume inside one (a surface embedded in it, or one Gmsh wrote but did not embed)
/// can cut a volume into several cells: for each such facet, the points just off it on either
/// side that lie strictly inside a volume, with that volume's index, so that every cell of the
/// volume gets a region point of its own (the cells inside a volume are that volume's material).
std::vector<std::pair<std::size_t, point3>> embedded_region_points(const plc<3>& p,
                                                                   const std::vector<std::vector<std::size_t>>& volumes,
                                                                   unsigned threads = 1);

/// Appends a region point to p.regions for every volume (a type with `facets`, `number`, `name`
/// and `entity`, such as gsse::io::plc_volume), in order. Throws std::runtime_error naming the
/// first volume that has no interior point.
template <class Volume>
void add_region_points(plc<3>& p, const std::vector<Volume>& volumes, unsigned threads = 1) {
  std::vector<std::vector<std::size_t>> facets;
  for (const auto& v : volumes) facets.push_back(v.facets);
  const auto at = interior_points(p, facets, threads);
  for (std::size_t k = 0; k < volumes.size(); ++k) {
    if (!at[k])
      throw std::runtime_error(p.source + ": volume " + std::to_string(volumes[k].entity) + " (segment " +
                               std::to_string(volumes[k].number) + ", '" + volumes[k].name +
                               "'): no point strictly inside it was found (a volume thinner than double precision "
                               "resolves, or a boundary that does not enclose it)");
    plc_region<3> g;
    g.at = *at[k];
    g.number = volumes[k].number;
    g.name = volumes[k].name;
    p.regions.push_back(std::move(g));
  }
  for (const auto& [k, x] : embedded_region_points(p, facets, threads)) {
    plc_region<3> g;
    g.at = x;
    g.number = volumes[k].number;
    g.name = volumes[k].name;
    p.regions.push_back(std::move(g));
  }
}

}  // namespace gsse::plc_tools
