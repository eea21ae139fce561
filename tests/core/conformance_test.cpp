#define BOOST_TEST_MODULE conformance
#include <boost/test/unit_test.hpp>

#include "support/conformance.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

#include <boost/fusion/include/adapt_struct.hpp>

// a research code's point struct, float coordinates, adapted for GSSE by one macro
namespace research {
struct node {
  float x, y, z;
};
}  // namespace research
BOOST_FUSION_ADAPT_STRUCT(research::node, x, y, z)

using namespace gsse;

namespace {
template <std::size_t D>
legacy::mesh<D> to_legacy(std::array<int, D> n, double split) {
  auto g = test::make_kuhn_grid<D>(n);
  legacy::mesh<D> m;
  for (const auto& p : g.points)
    for (double x : p) m.xyz.push_back(x);
  for (std::size_t c = 0; c < g.cells.size(); ++c) {
    for (auto v : g.cells[c]) m.conn.push_back(static_cast<int>(v));
    m.region.push_back(g.centre_x[c] < split ? 7 : 9);
  }
  return m;
}
}  // namespace

BOOST_AUTO_TEST_CASE(fusion_adapted_points_are_added_as_they_are) {
  gsse::domain<3> d;
  const research::node n{0.5f, -1.25f, 3.0f};
  const auto v = d.add_point(n);
  BOOST_TEST((d.position(v) == gsse::point3{0.5, -1.25, 3.0}));
  static_assert(gsse::fusion_point<research::node, 3> && !gsse::fusion_point<research::node, 2>);
}

BOOST_AUTO_TEST_CASE(default_model_2d) {
  auto d = test::make_two_segment_domain<2>({4, 3}, 2.0);
  test::check_domain(d);
  BOOST_TEST(interface_facets(d, 0, 1).size() == 3u);  // x = 2 crosses 3 unit squares
  BOOST_TEST(boundary_facets(d.segments()[0]).size() == 2u * 2 + 3 + 3);
}

BOOST_AUTO_TEST_CASE(default_model_3d) {
  auto d = test::make_two_segment_domain<3>({3, 2, 2}, 1.0);
  test::check_domain(d);
  BOOST_TEST(interface_facets(d, 0, 1).size() == 2u * 2 * 2);  // 4 unit squares, 2 triangles each
  BOOST_TEST(d.segments()[0].num_cells() == 6u * 4);
}

BOOST_AUTO_TEST_CASE(adapted_foreign_model_2d) {
  const auto m = to_legacy<2>({3, 3}, 1.0);
  const legacy::adapted<2> a(m);
  test::check_domain(a);
  BOOST_TEST(interface_facets(a, 0, 1).size() == 3u);
}

BOOST_AUTO_TEST_CASE(adapted_foreign_model_3d) {
  const auto m = to_legacy<3>({2, 2, 2}, 1.0);
  const legacy::adapted<3> a(m);
  test::check_domain(a);
  BOOST_TEST(interface_facets(a, 0, 1).size() == 8u);
}

BOOST_AUTO_TEST_CASE(models_agree) {
  // The same mesh through both models gives the same interface.
  auto d = test::make_two_segment_domain<3>({2, 2, 1}, 1.0);
  const auto m = to_legacy<3>({2, 2, 1}, 1.0);
  const legacy::adapted<3> a(m);
  BOOST_TEST(interface_facets(d, 0, 1).size() == interface_facets(a, 0, 1).size());
  BOOST_TEST(boundary_facets(d.segments()[1]).size() == boundary_facets(segments(a)[1]).size());
}

BOOST_AUTO_TEST_CASE(non_manifold_complex_is_rejected) {
  simplicial_complex<2> x;
  x.add_cell({0, 1, 2});
  x.add_cell({1, 0, 3});
  x.add_cell({0, 1, 4});
  BOOST_CHECK_THROW(x.finalize(), std::runtime_error);
  simplicial_complex<3> z;  // three tetrahedra on triangle 012
  z.add_cell({0, 1, 2, 3});
  z.add_cell({1, 0, 2, 4});
  z.add_cell({0, 1, 2, 5});
  BOOST_CHECK_THROW(z.finalize(), std::runtime_error);
  simplicial_complex<2> y;
  y.add_cell({0, 1, 2});
  BOOST_CHECK_THROW((void)y.neighbour(0, 0), std::logic_error);  // incidence before finalize()
}
