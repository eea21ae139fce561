#pragma once
// Internal: checks a domain before it is written, and finds its boundary and interface facets
// without requiring finalize() (writers take const domains that may not be finalized).
#include <algorithm>
#include <array>
#include <cstdlib>
#include <numeric>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "gsse/container/domain.hpp"
#include "gsse/traversal/for_each.hpp"
#include "gsse/traversal/parallel_sort.hpp"
#include "gsse/io/error.hpp"

namespace gsse::io::detail {

template <std::size_t D>
void check_domain(const domain<D>& d, const std::string& file) {
  std::unordered_set<int> numbers;
  const auto n = d.points().size();
  for (const auto& s : d.segments()) {
    if (!numbers.insert(s.number()).second)
      throw io_error::whole(file, "two segments have number " + std::to_string(s.number()) +
                                      "; segment numbers must be unique to be written");
    for (const auto& c : s.cell_data())
      for (auto v : c)
        if (v >= n)
          throw io_error::whole(file, "segment '" + s.name() + "' refers to vertex " + std::to_string(v) + " of " +
                                          std::to_string(n) + " points");
  }
}

struct key_hash {
  template <std::size_t N>
  std::size_t operator()(const std::array<vertex_id, N>& k) const {
    std::size_t h = 1469598103934665603ull;
    for (auto v : k) h = (h ^ v) * 1099511628211ull;
    return h;
  }
};

template <std::size_t D>
struct outer_facet {
  std::array<vertex_id, D> vertices;  // oriented into segment `first`
  std::size_t first;                  // segment index (lower number for an interface)
  long second;                        // segment index on the other side, -1 outside
};

/// Every facet on the boundary of a segment, once: boundary facets of the domain, and interface
/// facets oriented into the segment of lower number. Deterministic order (segments, cells, facets).
template <std::size_t D>
std::vector<outer_facet<D>> outer_facets(const domain<D>& d, const std::string& file, unsigned threads = 1) {
  struct use {
    std::size_t seg, cell;
    int index;
    int count = 0;
    std::size_t other_seg = 0;
  };
  auto facet_of = [](const auto& c, int i) {
    std::array<vertex_id, D> f;
    for (std::size_t j = 0; j < D; ++j)
      f[j] = c[static_cast<std::size_t>(reference_simplex<D>::facet_vertices[static_cast<std::size_t>(i)][j])];
    return f;
  };
  const auto& segs = d.segments();
  if (std::all_of(segs.begin(), segs.end(), [](const auto& s) { return s.finalized(); })) {
    // fast path: a finalized segment knows its boundary facets (those without a neighbour); only
    // they are matched across segments, by sorting. Same facets, same order as the general path.
    struct candidate {
      std::array<vertex_id, D> f;  // oriented into segment k
      std::size_t k;
    };
    // pieces of each segment's cells, in parallel; concatenated in (segment, cell) order
    constexpr std::size_t piece = 1 << 13;
    struct range {
      std::size_t k, c0, c1;
    };
    std::vector<range> ranges;
    for (std::size_t k = 0; k < segs.size(); ++k)
      for (std::size_t c = 0; c < segs[k].num_cells(); c += piece)
        ranges.push_back({k, c, std::min(segs[k].num_cells(), c + piece)});
    std::vector<std::vector<candidate>> per(ranges.size());
    for_each(execution::par(threads), ranges, [&](const range& r) {
      const auto cells = segs[r.k].cell_data();
      std::vector<candidate> mine;  // moved into per[] at the end: no shared cache lines meanwhile
      for (std::size_t c = r.c0; c < r.c1; ++c)
        for (int i = 0; i <= static_cast<int>(D); ++i)
          if (segs[r.k].neighbour(static_cast<cell_id>(c), i) == no_cell) mine.push_back({facet_of(cells[c], i), r.k});
      per[static_cast<std::size_t>(&r - ranges.data())] = std::move(mine);
    });
    std::vector<candidate> all;
    for (auto& v : per) all.insert(all.end(), v.begin(), v.end());
    using key = std::pair<std::array<vertex_id, D>, std::uint32_t>;
    std::vector<key> keys(all.size());
    for (std::size_t i = 0; i < all.size(); ++i) {
      keys[i] = {all[i].f, static_cast<std::uint32_t>(i)};
      std::sort(keys[i].first.begin(), keys[i].first.end());
    }
    gsse::stable_sort(execution::par(threads), keys.begin(), keys.end());
    std::vector<long> other(all.size(), -1);  // the candidate on the other side, if any
    for (std::size_t i = 0; i < keys.size();) {
      std::size_t j = i + 1;
      while (j < keys.size() && keys[j].first == keys[i].first) ++j;
      if (j - i > 2) throw io_error::whole(file, "a facet is shared by more than two cells");
      if (j - i == 2) other[keys[i].second] = keys[i + 1].second, other[keys[i + 1].second] = keys[i].second;
      i = j;
    }
    std::vector<outer_facet<D>> r;
    for (std::size_t i = 0; i < all.size(); ++i) {
      const std::size_t k = all[i].k;
      if (other[i] < 0) {
        r.push_back({all[i].f, k, -1});
        continue;
      }
      const std::size_t o = all[static_cast<std::size_t>(other[i])].k;
      if (o == k) throw io_error::whole(file, "a facet is shared by more than two cells");
      const auto na = segs[k].number(), nb = segs[o].number();
      if (na < nb || (na == nb && k < o)) r.push_back({all[i].f, k, static_cast<long>(o)});
    }
    return r;
  }
  std::unordered_map<std::array<vertex_id, D>, use, key_hash> map;
  for (std::size_t k = 0; k < segs.size(); ++k) {
    const auto cells = segs[k].cell_data();
    for (std::size_t c = 0; c < cells.size(); ++c)
      for (int i = 0; i <= static_cast<int>(D); ++i) {
        auto key = facet_of(cells[c], i);
        std::sort(key.begin(), key.end());
        auto [it, fresh] = map.try_emplace(key, use{k, c, i});
        auto& u = it->second;
        if (++u.count > 2) throw io_error::whole(file, "a facet is shared by more than two cells");
        if (!fresh) u.other_seg = k;
      }
  }
  std::vector<outer_facet<D>> r;
  for (std::size_t k = 0; k < segs.size(); ++k) {
    const auto cells = segs[k].cell_data();
    for (std::size_t c = 0; c < cells.size(); ++c)
      for (int i = 0; i <= static_cast<int>(D); ++i) {
        auto f = facet_of(cells[c], i);
        auto key = f;
        std::sort(key.begin(), key.end());
        const auto& u = map.at(key);
        if (u.count == 1) {
          r.push_back({f, k, -1});
        } else if (u.other_seg != u.seg) {
          // emit from the side of the lower number (ties: earlier segment)
          const std::size_t other = k == u.seg ? u.other_seg : u.seg;
          const auto a = segs[k].number(), b = segs[other].number();
          if (a < b || (a == b && k < other)) r.push_back({f, k, static_cast<long>(other)});
        }
      }
  }
  return r;
}

/// A face's vertices in increasing order: its key whatever its orientation.
template <std::size_t D>
std::array<vertex_id, D> sorted_face(std::array<vertex_id, D> f) {
  std::sort(f.begin(), f.end());
  return f;
}

/// The markers of the outer facets and the marked faces inside a segment.
template <std::size_t D>
struct facet_markers {
  // per outer facet: the marker of the earliest marked face with its vertices, 0 if none
  std::vector<int> outer;
  // the marked faces that are not outer facets, each set of vertices once (at its earliest
  // listing), in the domain's order
  std::vector<std::pair<std::array<vertex_id, D>, int>> inner;
};

/// facet_markers of d's outer facets `outer`: the marked faces sorted once by vertices (in
/// parallel; the keys are distinct, so the order is the same for any thread count) and each outer
/// facet looked up in parallel. Per marked face, whether an outer facet has its vertices is then
/// known without a second sorted list (a rotated trench's 2-thread run waited 20 ms for the two
/// serial sorts and the searches this replaces).
template <std::size_t D>
facet_markers<D> mark_facets(const domain<D>& d, const std::vector<outer_facet<D>>& outer, unsigned threads = 1) {
  facet_markers<D> r;
  r.outer.assign(outer.size(), 0);
  const auto& m = d.marked_faces();
  if (m.empty()) return r;
  using key = std::pair<std::array<vertex_id, D>, std::uint32_t>;
  std::vector<key> keys(m.size());
  for (std::uint32_t i = 0; i < m.size(); ++i) keys[i] = {sorted_face<D>(m[i].vertices), i};
  gsse::stable_sort(execution::par(threads), keys.begin(), keys.end());
  // the earliest listing of each set of vertices: the first of its run
  std::vector<char> earliest(m.size(), 0), on_outer(m.size(), 0);
  for (std::size_t j = 0; j < keys.size(); ++j)
    if (j == 0 || keys[j].first != keys[j - 1].first) earliest[keys[j].second] = 1;
  constexpr std::size_t piece = 4096;
  std::vector<std::size_t> pieces((outer.size() + piece - 1) / piece);
  std::iota(pieces.begin(), pieces.end(), std::size_t{0});
  for_each(execution::par(threads), pieces, [&](std::size_t k) {
    for (std::size_t f = k * piece; f < std::min(outer.size(), (k + 1) * piece); ++f) {
      const auto s = sorted_face<D>(outer[f].vertices);
      const auto it = std::lower_bound(keys.begin(), keys.end(), key{s, 0});
      if (it == keys.end() || it->first != s) continue;
      r.outer[f] = m[it->second].marker;
      on_outer[it->second] = 1;  // outer facets are distinct: each marked face is set by one piece at most
    }
  });
  for (std::size_t i = 0; i < m.size(); ++i)
    if (earliest[i] && !on_outer[i]) r.inner.push_back({m[i].vertices, m[i].marker});
  return r;
}

/// finalize() of every segment; a facet shared by more than two cells becomes an io_error.
template <std::size_t D>
void finalize_all(domain<D>& d, const std::string& file) {
  for (auto& s : d.segments()) {
    try {
      s.finalize();
    } catch (const std::runtime_error& e) {
      throw io_error::whole(file, "segment '" + s.name() + "' is not a valid mesh: " + e.what());
    }
  }
}

}  // namespace gsse::io::detail
