#define BOOST_TEST_MODULE quantity
#include <boost/test/unit_test.hpp>

#include <atomic>
#include <mutex>
#include <set>
#include <thread>

#include "support/fixtures.hpp"

using namespace gsse;

BOOST_AUTO_TEST_CASE(typed_vertex_and_cell_quantities) {
  auto d = test::make_two_segment_domain<2>({2, 2}, 1.0);
  auto& s = d.segments()[0];
  auto pot = add_quantity<double>(s, on_vertices, "potential", -1.0);
  auto mat = add_quantity<int>(s, on_cells, "material", 0);
  BOOST_TEST(values(s, pot).size() == d.points().size());  // indexed by domain vertex id
  BOOST_TEST(values(s, mat).size() == s.num_cells());
  for (vertex_id v : s.used_vertices()) put(s, pot, v, position(d, v)[0] + 10 * position(d, v)[1]);
  for (cell_id c : cells(s)) put(s, mat, c, static_cast<int>(c) * 3);
  BOOST_TEST(get(s, pot, 4) == 11.0);  // vertex 4 is (1,1) in a 3x3 point grid
  BOOST_TEST(get(s, mat, 2) == 6);
  BOOST_TEST(quantity_name(s, pot) == "potential");
  // find by name once, then access through the handle
  auto again = find_quantity<double>(s, on_vertices, "potential");
  BOOST_TEST_REQUIRE(again.has_value());
  BOOST_TEST(get(s, *again, 4) == 11.0);
  BOOST_TEST(!find_quantity<int>(s, on_vertices, "potential").has_value());  // wrong type
  BOOST_TEST(!find_quantity<double>(s, on_cells, "potential").has_value());  // wrong location
  BOOST_CHECK_THROW(add_quantity<double>(s, on_vertices, "potential"), std::invalid_argument);
  // vertex quantities grow with the domain's points, new slots hold the initial value
  d.add_point({5.0, 5.0});
  BOOST_TEST(values(s, pot).size() == d.points().size());
  BOOST_TEST(get(s, pot, static_cast<std::size_t>(d.points().size() - 1)) == -1.0);
  // segments copy their quantities
  segment<2> copy = s;
  put(copy, mat, 2, 99);
  BOOST_TEST(get(s, mat, 2) == 6);
  BOOST_TEST(get(copy, mat, 2) == 99);
}

BOOST_AUTO_TEST_CASE(domain_wide_handle) {
  auto d = test::make_two_segment_domain<3>({2, 1, 1}, 1.0);
  auto t = add_quantity<double>(d, on_cells, "temperature", 300.0);
  for (auto& s : d.segments()) {
    BOOST_TEST(values(s, t).size() == s.num_cells());
    BOOST_TEST(get(s, t, 0) == 300.0);
  }
}

BOOST_AUTO_TEST_CASE(parallel_for_each_visits_every_segment_once) {
  domain<2> d;
  for (int k = 0; k < 9; ++k) d.add_segment("s" + std::to_string(k), k + 1);
  std::vector<std::atomic<int>> hits(9);
  std::mutex m;
  std::set<std::thread::id> ids;
  for_each(execution::par(2), segments(d), [&](segment<2>& s) {
    ++hits[static_cast<std::size_t>(s.number() - 1)];
    std::lock_guard l(m);
    ids.insert(std::this_thread::get_id());
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  });
  for (auto& h : hits) BOOST_TEST(h.load() == 1);
  BOOST_TEST(ids.size() == 2u);  // the range really was split over two threads
  int seen = 0;
  for_each(execution::seq, segments(d), [&](const segment<2>&) { ++seen; });
  BOOST_TEST(seen == 9);
  // exceptions from workers reach the caller
  BOOST_CHECK_THROW(for_each(execution::par(2), segments(d),
                             [](const segment<2>& s) {
                               if (s.number() == 5) throw std::runtime_error("boom");
                             }),
                    std::runtime_error);
}
