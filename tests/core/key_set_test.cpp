#define BOOST_TEST_MODULE key_set
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <array>
#include <random>
#include <set>
#include <vector>

#include "gsse/container/key_set.hpp"

// key_set answers "is this simplex in the set?" exactly as a std::set of the same keys does: for
// keys inserted (with repeats), for keys never inserted, for keys that share all but one vertex
// with an inserted one, and when the table is empty.

using namespace gsse;

namespace {

template <std::size_t N>
void check(std::size_t count, vertex_id range, unsigned seed) {
  std::mt19937_64 g(seed);
  std::uniform_int_distribution<vertex_id> pick(0, range);
  auto random_key = [&] {
    std::array<vertex_id, N> k;
    for (auto& v : k) v = pick(g);
    std::sort(k.begin(), k.end());
    return k;
  };
  std::vector<std::array<vertex_id, N>> keys;
  for (std::size_t i = 0; i < count; ++i) keys.push_back(random_key());
  for (std::size_t i = 0; i < count / 4; ++i) keys.push_back(keys[i]);  // repeats
  const std::set<std::array<vertex_id, N>> truth(keys.begin(), keys.end());
  const key_set<N> set(keys);
  BOOST_TEST(set.empty() == keys.empty());
  std::size_t wrong = 0, asked_absent = 0;
  for (const auto& k : keys) wrong += !set.contains(k);
  for (std::size_t i = 0; i < 4 * count + 16; ++i) {
    auto k = random_key();
    if (i % 2 == 0 && !keys.empty()) {  // a neighbour of an inserted key: one vertex moved
      k = keys[i % keys.size()];
      k[i % N] += 1;
      std::sort(k.begin(), k.end());
    }
    const bool in = truth.count(k) != 0;
    asked_absent += !in;
    wrong += set.contains(k) != in;
  }
  BOOST_TEST(wrong == 0u);
  BOOST_TEST(asked_absent > 0u);
}

}  // namespace

BOOST_AUTO_TEST_CASE(matches_a_set) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    check<3>(5000, 3000, seed);   // many shared vertices: long probe runs
    check<3>(5000, 1u << 30, seed);
    check<2>(5000, 500, seed);
    check<2>(3, 10, seed);
  }
}

BOOST_AUTO_TEST_CASE(empty_set_holds_nothing) {
  const key_set<3> none;
  BOOST_TEST(none.empty());
  BOOST_TEST(!none.contains({0, 1, 2}));
  const key_set<2> built_empty(std::vector<std::array<vertex_id, 2>>{});
  BOOST_TEST(built_empty.empty());
  BOOST_TEST(!built_empty.contains({0, 1}));
}
