#include "gsse/io/boundary.hpp"

#include "facets.hpp"

namespace gsse::io {

template <std::size_t D>
std::vector<boundary_face<D>> boundary_faces(const domain<D>& d, const std::string& what) {
  const auto outer = detail::outer_facets(d, what);
  const auto marks = detail::mark_facets(d, outer);
  const auto& segs = d.segments();
  std::vector<boundary_face<D>> r;
  r.reserve(outer.size() + marks.inner.size());
  for (std::size_t i = 0; i < outer.size(); ++i) {
    const auto& f = outer[i];
    r.push_back({f.vertices, marks.outer[i], segs[f.first].number(),
                 f.second < 0 ? 0 : segs[static_cast<std::size_t>(f.second)].number()});
  }
  // a marked face inside a segment: the segment of one of its cells is not at hand here; 0, 0
  for (const auto& [f, m] : marks.inner) r.push_back({f, m, 0, 0});
  return r;
}

template std::vector<boundary_face<2>> boundary_faces(const domain<2>&, const std::string&);
template std::vector<boundary_face<3>> boundary_faces(const domain<3>&, const std::string&);

}  // namespace gsse::io
