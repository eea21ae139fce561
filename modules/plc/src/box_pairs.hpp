#pragma once
// Broad phase: all pairs of intersecting closed axis-aligned boxes from different groups, on a
// uniform grid. Cells are about the median box size per axis (at most about two cells per box),
// so a typical box covers a few cells and a long thin one (a facet of a layer) a row of them; a
// pair is reported in the one cell that holds the lower corner of the two boxes' intersection,
// hence once. Cell indices are monotone in the coordinate, so overlapping boxes share a cell.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace gsse::plc_check::detail {

template <std::size_t D>
struct box {
  std::array<double, D> lo, hi;
  std::uint32_t group;  // boxes of one group are never paired
};

template <std::size_t D>
bool overlap(const box<D>& a, const box<D>& b) {
  for (std::size_t k = 0; k < D; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

/// Pairs (i, j), i < j, of overlapping boxes of different groups, in an order that depends on
/// the boxes only.
template <std::size_t D>
std::vector<std::pair<std::uint32_t, std::uint32_t>> box_pairs(const std::vector<box<D>>& boxes) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  const std::size_t n = boxes.size();
  if (n < 2) return out;
  std::array<double, D> lo, hi, inv;
  std::array<std::size_t, D> cells;
  lo = boxes[0].lo, hi = boxes[0].hi;
  for (const auto& b : boxes)
    for (std::size_t k = 0; k < D; ++k) lo[k] = std::min(lo[k], b.lo[k]), hi[k] = std::max(hi[k], b.hi[k]);
  std::vector<double> ext(n);
  for (std::size_t k = 0; k < D; ++k) {
    for (std::size_t i = 0; i < n; ++i) ext[i] = boxes[i].hi[k] - boxes[i].lo[k];
    std::nth_element(ext.begin(), ext.begin() + static_cast<std::ptrdiff_t>(n / 2), ext.end());
    const double width = hi[k] - lo[k], median = ext[n / 2];
    const double c = median > 0 ? width / median : static_cast<double>(n);
    cells[k] = width > 0 ? static_cast<std::size_t>(std::clamp(c, 1.0, static_cast<double>(n))) : 1;
  }
  auto total = [&] {
    std::size_t t = 1;
    for (auto c : cells) t *= c;
    return t;
  };
  while (total() > 2 * n) *std::max_element(cells.begin(), cells.end()) /= 2;
  for (std::size_t k = 0; k < D; ++k) inv[k] = hi[k] > lo[k] ? static_cast<double>(cells[k]) / (hi[k] - lo[k]) : 0;
  auto cell = [&](std::size_t k, double x) {
    const auto c = static_cast<std::size_t>((x - lo[k]) * inv[k]);
    return std::min(c, cells[k] - 1);
  };
  // boxes per cell, in box order (CSR)
  std::vector<std::uint32_t> start(total() + 1, 0), items;
  auto for_cells = [&](const box<D>& b, auto&& f) {
    std::array<std::size_t, D> a, z, c;
    for (std::size_t k = 0; k < D; ++k) a[k] = cell(k, b.lo[k]), z[k] = cell(k, b.hi[k]);
    c = a;
    for (;;) {
      std::size_t id = 0;
      for (std::size_t k = D; k-- > 0;) id = id * cells[k] + c[k];
      f(id);
      std::size_t k = 0;
      while (k < D && c[k] == z[k]) c[k] = a[k], ++k;
      if (k == D) break;
      ++c[k];
    }
  };
  for (const auto& b : boxes) for_cells(b, [&](std::size_t id) { ++start[id + 1]; });
  for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  items.resize(start.back());
  {
    auto fill = start;
    for (std::uint32_t i = 0; i < n; ++i) for_cells(boxes[i], [&](std::size_t id) { items[fill[id]++] = i; });
  }
  for (std::size_t id = 0; id + 1 < start.size(); ++id) {
    std::array<std::size_t, D> c;
    for (std::size_t k = 0, r = id; k < D; ++k) c[k] = r % cells[k], r /= cells[k];
    for (auto x = start[id]; x < start[id + 1]; ++x)
      for (auto y = x + 1; y < start[id + 1]; ++y) {
        const auto &A = boxes[items[x]], &B = boxes[items[y]];
        if (A.group == B.group || !overlap(A, B)) continue;
        bool here = true;
        for (std::size_t k = 0; k < D && here; ++k) here = cell(k, std::max(A.lo[k], B.lo[k])) == c[k];
        if (here) out.push_back({items[x], items[y]});
      }
  }
  return out;
}

}  // namespace gsse::plc_check::detail
