#pragma once
// Internal: shortest decimal text that reads back to the same double (std::to_chars), so
// coordinates survive a write/read cycle through any text format bit for bit.
#include <charconv>
#include <string>

namespace gsse::io::detail {
inline void append_real(std::string& s, double x) {
  char buf[32];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, x);
  s.append(buf, p);
}
}  // namespace gsse::io::detail
