#include "gsse/sizing/fit.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

#include "gsse/traversal/for_each.hpp"

namespace gsse::sizing {

template <std::size_t D>
fit edge_fit(const domain<D>& d, const size_field<D>* h, double uniform, unsigned threads) {
  const auto& p = d.points();
  const std::size_t n = p.size();
  // each segment's edges once: per vertex, its (segment, neighbour of larger id) pairs in a
  // compressed table (counted, then filled), sorted and made unique per vertex
  using link = std::pair<std::uint32_t, vertex_id>;  // (segment index, neighbour)
  std::vector<int> number;
  std::vector<std::size_t> first(n + 1, 0);
  for (const auto& s : d.segments()) {
    number.push_back(s.number());
    for (const auto& c : s.cell_data())
      for (std::size_t i = 0; i <= D; ++i)
        for (std::size_t j = 0; j <= D; ++j)
          if (c[i] < c[j]) ++first[c[i] + 1];
  }
  for (std::size_t v = 0; v < n; ++v) first[v + 1] += first[v];
  std::vector<link> to(first[n]);
  {
    std::vector<std::size_t> at(first.begin(), first.end() - 1);
    std::uint32_t k = 0;
    for (const auto& s : d.segments()) {
      for (const auto& c : s.cell_data())
        for (std::size_t i = 0; i <= D; ++i)
          for (std::size_t j = 0; j <= D; ++j)
            if (c[i] < c[j]) to[at[c[i]]++] = {k, c[j]};
      ++k;
    }
  }
  // per block of vertices (in parallel): the ratios of its edges, in vertex and link order
  constexpr std::size_t block = 2048;
  std::vector<std::size_t> blocks((n + block - 1) / block);
  std::iota(blocks.begin(), blocks.end(), std::size_t{0});
  std::vector<std::vector<double>> part(blocks.size());
  for_each(execution::par(threads), blocks, [&](std::size_t k) {
    auto& out = part[k];
    for (std::size_t v = k * block; v < std::min(n, (k + 1) * block); ++v) {
      auto b = to.begin() + static_cast<long>(first[v]), e = to.begin() + static_cast<long>(first[v + 1]);
      if (b == e) continue;
      std::sort(b, e);
      e = std::unique(b, e);
      for (auto it = b; it != e; ++it) {
        const point<D>& w = p[it->second];
        const double length = distance(p[v], w);
        const double size = h ? (*h)(0.5 * (p[v] + w), number[it->first]) : uniform;
        if (std::isfinite(size) && size > 0) out.push_back(length / size);  // else no target there
      }
    }
  }, [&](std::size_t k) { return static_cast<double>(first[std::min(n, (k + 1) * block)] - first[k * block]); });
  fit f;
  std::vector<double> all;
  for (const auto& x : part) all.insert(all.end(), x.begin(), x.end());
  f.edges = all.size();
  if (all.empty()) return f;
  for (double r : all) {
    f.below_half += r < 0.5, f.above += r > 1.5;
    std::size_t bin = 0;
    while (bin < fit::bounds.size() && !(r < fit::bounds[bin])) ++bin;
    ++f.histogram[bin];
  }
  f.within = f.edges - f.below_half - f.above;
  const auto [lo, hi] = std::minmax_element(all.begin(), all.end());
  f.min_ratio = *lo, f.max_ratio = *hi;
  std::nth_element(all.begin(), all.begin() + static_cast<long>(all.size() / 2), all.end());
  f.median_ratio = all[all.size() / 2];
  return f;
}

template fit edge_fit<2>(const domain<2>&, const size_field<2>*, double, unsigned);
template fit edge_fit<3>(const domain<3>&, const size_field<3>*, double, unsigned);

}  // namespace gsse::sizing
