#define BOOST_TEST_MODULE conformer_thin_layers
// Thin layers seeded at their gap's scale (conformer::options::thin_layer, the conformer's
// src/thin_layers.hpp): which facet pairs count as a layer's two walls, what the conformer seeds
// on them, and what the refinement then has left to do.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "gsse/conformer/conformer.hpp"
#include "gsse/pipeline/pipeline.hpp"
#include "support/stack.hpp"
#include "thin_layers.hpp"

using namespace gsse;
namespace th = gsse::conformer::thin;
namespace pl = gsse::pipeline;

namespace {

point3 unit(const point3& a) { return (1.0 / std::sqrt(dot(a, a))) * a; }

/// The parallelogram o, o + u, o + u + v, o + v as a facet with corner ids from `first`.
th::facet quad(const point3& o, const point3& u, const point3& v, std::uint32_t first) {
  th::facet f;
  f.unit = unit(cross(u, v));
  f.e1 = unit(u);
  f.e2 = unit(cross(f.unit, f.e1));
  f.corners = {o, o + u, o + u + v, o + v};
  for (std::size_t k = 0; k < 4; ++k) f.sides.push_back({f.corners[k], f.corners[(k + 1) % 4]});
  f.corner_ids = {first, first + 1, first + 2, first + 3};
  return f;
}

const point3 ex{1, 0, 0}, ey{0, 1, 0};
const double model = std::sqrt(3.0), inf = std::numeric_limits<double>::infinity();

}  // namespace

BOOST_AUTO_TEST_CASE(facing_parallel_walls_are_a_layer) {
  // two unit squares 0.01 apart, facing: each finds the other
  {
    const auto g = th::layer_gaps({quad({0, 0, 0}, ex, ey, 0), quad({0, 0, 0.01}, ex, ey, 4)}, model, 0.05);
    BOOST_TEST(g[0] == 0.01, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(g[1] == 0.01, boost::test_tools::tolerance(1e-12));
  }
  // the other wall's normal the other way round (its facet listed in the opposite order)
  {
    const auto g = th::layer_gaps({quad({0, 0, 0}, ex, ey, 0), quad({0, 0, 0.01}, ey, ex, 4)}, model, 0.05);
    BOOST_TEST(g[0] == 0.01, boost::test_tools::tolerance(1e-12));
  }
  // a smaller square over the middle of a larger one: each centroid projects into the other
  {
    const auto g = th::layer_gaps({quad({0, 0, 0}, ex, ey, 0), quad({0.3, 0.3, 0.01}, 0.4 * ex, 0.4 * ey, 4)}, model, 0.05);
    BOOST_TEST(g[0] == 0.01, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(g[1] == 0.01, boost::test_tools::tolerance(1e-12));
  }
  // turned off the axes (the stack's generic rotation): the same gap, to rounding
  {
    auto t = [](const point3& q) { return test::turn(q); };
    const auto g = th::layer_gaps({quad(t({0, 0, 0}), t(ex), t(ey), 0), quad(t({0, 0, 0.01}), t(ex), t(ey), 4)}, model, 0.05);
    BOOST_TEST(g[0] == 0.01, boost::test_tools::tolerance(1e-9));
    BOOST_TEST(g[1] == 0.01, boost::test_tools::tolerance(1e-9));
  }
}

BOOST_AUTO_TEST_CASE(what_is_not_a_layer) {
  auto gaps = [](const th::facet& b, double max_gap = 0.05) { return th::layer_gaps({quad({0, 0, 0}, ex, ey, 0), b}, model, max_gap); };
  // side by side, not facing
  BOOST_TEST(gaps(quad({1.5, 0, 0.01}, ex, ey, 4))[0] == inf);
  // facing in part only: a small square over one corner (the large one's centroid is not over
  // it), for neither of the two
  {
    const auto g = gaps(quad({0.05, 0.05, 0.01}, 0.1 * ex, 0.1 * ey, 4));
    BOOST_TEST(g[0] == inf);
    BOOST_TEST(g[1] == inf);
  }
  // farther apart than max_gap
  BOOST_TEST(gaps(quad({0, 0, 0.01}, ex, ey, 4), 0.005)[0] == inf);
  // tilted by 1e-6 radians: not parallel (1e-9)
  BOOST_TEST(gaps(quad({0, 0, 0.01}, ex + point3{0, 0, 1e-6}, ey, 4))[0] == inf);
  // a plane 1e-12 away: the same plane (below 2e-8 of the model's size), not a layer
  BOOST_TEST(gaps(quad({0, 0, 1e-12}, ex, ey, 4))[0] == inf);
  // sharing a corner: a fold, not a layer
  BOOST_TEST(gaps(quad({0, 0, 0.01}, ex, ey, 3))[0] == inf);
  // perpendicular
  BOOST_TEST(gaps(quad({0, 0, 0.01}, ex, point3{0, 0, 1}, 4))[0] == inf);
  // the least of two gaps
  const auto g = th::layer_gaps({quad({0, 0, 0}, ex, ey, 0), quad({0, 0, 0.02}, ex, ey, 4), quad({0, 0, -0.01}, ex, ey, 8)}, model, 0.05);
  BOOST_TEST(g[0] == 0.01, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(g[1] == 0.02, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(g[2] == 0.01, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(layer_walls_are_seeded_at_the_gap_scale) {
  // a 0.01 layer between two 0.5 boxes, size 0.1: with thin_layer 2.2 its two walls (facets 1
  // and 2, z = 0 and 0.01) carry the same lattice at 0.022, point over point; without, at 0.1
  const auto p = test::stack(1.0, {-0.5, 0.0, 0.01, 0.5});
  auto walls = [&](double ratio, double& longest, std::size_t& unmatched, std::size_t& on_walls) {
    conformer::options o;
    o.size = 0.1;
    o.thin_layer = ratio;
    const auto b = conformer::conform(p, {}, o);
    BOOST_TEST(conformer::encroached(b).empty());
    longest = 0;
    std::map<std::uint32_t, std::set<std::pair<double, double>>> at;
    for (std::size_t f = 0; f < b.faces.size(); ++f) {
      const auto src = b.face_source[f];
      if (src != 1 && src != 2) continue;
      for (std::size_t k = 0; k < 3; ++k) {
        const auto &x = b.points[b.faces[f][k]], &y = b.points[b.faces[f][(k + 1) % 3]];
        longest = std::max(longest, std::sqrt(dot(x - y, x - y)));
        at[src].insert({x[0], x[1]});
      }
    }
    unmatched = 0;
    for (const auto& q : at[2]) unmatched += at[1].count(q) ? 0 : 1;
    on_walls = at[1].size() + at[2].size();
  };
  double fine = 0, coarse = 0;
  std::size_t unmatched = 0, unmatched_coarse = 0, n_fine = 0, n_coarse = 0;
  walls(2.2, fine, unmatched, n_fine);
  walls(0, coarse, unmatched_coarse, n_coarse);
  BOOST_TEST_MESSAGE("walls: " << n_fine << " points, longest edge " << fine << " (without: " << n_coarse << ", " << coarse << ")");
  BOOST_TEST(fine <= 2 * 0.022);
  BOOST_TEST(coarse >= 0.09);
  BOOST_TEST(n_fine > 10 * n_coarse);
  BOOST_TEST(unmatched == 0u, unmatched << " points of the upper wall have no image on the lower one");
}

BOOST_AUTO_TEST_CASE(quality_rounds_have_little_left_on_seeded_walls) {
  // --quality 1.414 with a uniform size: the pipeline seeds the layer's walls (thin_layer_ratio)
  // and the rounds split far fewer boundary faces than from walls at the size (thin_layer < 0:
  // off); both meshes meet the bound
  for (bool rotated : {false, true}) {
    const auto p = test::stack(1.0, {-0.5, 0.0, 0.01, 0.5}, {}, rotated);
    auto run = [&](double ratio, std::size_t& splits, std::size_t& points) {
      pl::options o;
      o.size = 0.1;
      o.quality = true;
      o.quality_bound = 1.414;
      o.threads = 2;
      o.conform.thin_layer = ratio;
      pl::report r;
      const auto d = pl::mesh(p, {}, o, r);
      BOOST_TEST(r.problems.empty());
      BOOST_TEST(r.refinement.converged);
      BOOST_TEST(pl::measure(d).max_ratio <= 1.414 * (1 + 1e-9));
      splits = r.refinement.split_requests;
      points = d.points().size();
    };
    std::size_t with = 0, without = 0, p_with = 0, p_without = 0;
    run(0, with, p_with);
    run(-1, without, p_without);
    BOOST_TEST_MESSAGE((rotated ? "rotated " : "") << "layer: " << with << " boundary splits, " << p_with << " points (walls at the size: "
                                                   << without << ", " << p_without << ")");
    BOOST_TEST(2 * with < without, (rotated ? "rotated: " : "") << with << " splits against " << without);
  }
}

BOOST_AUTO_TEST_CASE(ratio_follows_the_bound) {
  BOOST_TEST(conformer::thin_layer_ratio(1.414) == 0.96 * std::sqrt(3 * 1.414 * 1.414 - 0.75), boost::test_tools::tolerance(1e-12));
  BOOST_TEST(conformer::thin_layer_ratio(2.0) > conformer::thin_layer_ratio(1.414));
  BOOST_TEST(conformer::thin_layer_ratio(1.3) == 0.0);
}
