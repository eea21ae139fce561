#pragma once
// How well a mesh's edges fit its size: every edge uv of a segment measured against the size at
// its midpoint inside that segment, |uv| / h((u + v) / 2). Issue 17 asks for edges within
// [0.5, 1.5] x h(x), apart from where the geometry forces smaller; this counts how many are, and
// how many are shorter or longer, so that a run can say it (gsse-mesh --stats:
// quality.size_fit). Doubles throughout: a report, no decision.
#include <array>
#include <cstddef>

#include "gsse/container/domain.hpp"
#include "gsse/sizing/size_field.hpp"

namespace gsse::sizing {

struct fit {
  std::size_t edges = 0;       // the edges of each segment (one on an interface counts in both)
  std::size_t below_half = 0;  // |uv| < 0.5 h(mid)
  std::size_t within = 0;      // 0.5 h(mid) <= |uv| <= 1.5 h(mid)
  std::size_t above = 0;       // |uv| > 1.5 h(mid)
  double min_ratio = 0, median_ratio = 0, max_ratio = 0;  // of |uv| / h(mid)
  // edges with a ratio below each bound, and (last) at or above the last
  static constexpr std::array<double, 7> bounds{0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0};
  std::array<std::size_t, 8> histogram{};
};

/// The fit of the edges of `d` to the size field `h` (h(mid, segment number): its segment's own
/// maximum counts), or where `h` is null to the uniform size `uniform`. Edges where the size is
/// not finite (no term reaches there) are left out. The same result for any number of threads.
template <std::size_t D>
fit edge_fit(const domain<D>& d, const size_field<D>* h, double uniform, unsigned threads = 1);

}  // namespace gsse::sizing
