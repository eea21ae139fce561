#pragma once
// Internal: text files of many similar lines (points, elements, faces) formatted in parallel. Lines
// are formatted in chunks, one chunk per thread at a time, and written in order: the bytes are the
// same for any thread count.
#include <algorithm>
#include <charconv>
#include <ostream>
#include <string>
#include <numeric>
#include <vector>

#include "gsse/traversal/for_each.hpp"

namespace gsse::io::detail {

inline void append_int(std::string& s, long long x) {
  char buf[24];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, x);
  s.append(buf, p);
}

/// Writes lines 0..n-1 to o, line i formatted by line(i, out) (appending, with its newline).
template <class Line>
void write_lines(std::ostream& o, std::size_t n, unsigned threads, Line&& line) {
  constexpr std::size_t chunk = 1 << 15;
  threads = std::max(1u, threads);
  std::vector<std::string> buf(threads);
  std::vector<unsigned> ts(threads);
  std::iota(ts.begin(), ts.end(), 0u);
  for (std::size_t start = 0; start < n; start += chunk * threads) {
    auto fill = [&](unsigned t) {
      buf[t].clear();
      const std::size_t a = std::min(n, start + t * chunk), b = std::min(n, a + chunk);
      for (std::size_t i = a; i < b; ++i) line(i, buf[t]);
    };
    for_each(execution::par(threads), ts, fill);
    for (const auto& b : buf) o.write(b.data(), static_cast<std::streamsize>(b.size()));
    for (auto& b : buf) b.clear();
  }
}

}  // namespace gsse::io::detail
