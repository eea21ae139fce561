#pragma once
// Internal: text files of many similar lines (points, elements, faces) formatted in parallel. Lines
// are formatted in chunks and written in order: the bytes are the same for any thread count.
#include <algorithm>
#include <charconv>
#include <condition_variable>
#include <mutex>
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
/// Threads take chunks of lines in turn and format them into a ring of buffers; whichever thread
/// completes the chunk next in line writes it, and any chunks after it already done, while the
/// others go on formatting. Writing thus overlaps formatting, and memory stays at the ring's size.
template <class Line>
void write_lines(std::ostream& o, std::size_t n, unsigned threads, Line&& line) {
  threads = execution::thread_count(threads);  // 0: every hardware thread, as everywhere
  // chunks of up to 8192 lines, smaller when that would leave threads idle (a 2e4-point .node
  // is three chunks of 8192); not below 1024 lines, where handing over a chunk would dominate
  const std::size_t chunk = std::clamp<std::size_t>(n / (4 * std::size_t{std::max(1u, threads)}), 1 << 10, 1 << 13);
  const std::size_t chunks = (n + chunk - 1) / chunk;
  auto format = [&](std::size_t k, std::string& b) {
    b.clear();
    for (std::size_t i = k * chunk, end = std::min(n, i + chunk); i < end; ++i) line(i, b);
  };
  threads = static_cast<unsigned>(std::min<std::size_t>(std::max(1u, threads), std::max<std::size_t>(1, chunks)));
  if (threads == 1) {
    std::string b;
    for (std::size_t k = 0; k < chunks; ++k) {
      format(k, b);
      o.write(b.data(), static_cast<std::streamsize>(b.size()));
    }
    return;
  }
  const std::size_t ring = 4 * std::size_t{threads};
  // one cache line each: strings side by side would share lines, and every append of one thread
  // would then invalidate the other's (measured: formatting twice as slow per line with 2 threads)
  struct alignas(64) slot {
    std::string text;
  };
  std::vector<slot> buf(ring);
  std::vector<char> ready(ring, 0);
  std::mutex m;
  std::condition_variable cv;
  std::size_t next = 0, written = 0;  // next chunk to format; chunks written
  bool writing = false, failed = false;
  auto work = [&](unsigned) {
    std::unique_lock lock(m);
    for (;;) {
      // chunk `next` takes slot next % ring once the chunk that held it has been written
      cv.wait(lock, [&] { return failed || next >= chunks || next < written + ring; });
      if (failed || next >= chunks) return;
      const std::size_t k = next++;
      lock.unlock();
      try {
        format(k, buf[k % ring].text);
      } catch (...) {
        lock.lock();
        failed = true;  // the waiting threads must not wait for this chunk
        cv.notify_all();
        throw;
      }
      lock.lock();
      ready[k % ring] = 1;
      if (writing) continue;  // the writer will find it
      writing = true;
      while (written < chunks && ready[written % ring]) {
        const std::string& b = buf[written % ring].text;
        lock.unlock();
        o.write(b.data(), static_cast<std::streamsize>(b.size()));
        lock.lock();
        ready[written % ring] = 0;
        ++written;
        cv.notify_all();
      }
      writing = false;
    }
  };
  std::vector<unsigned> ts(threads);
  std::iota(ts.begin(), ts.end(), 0u);
  for_each(execution::par(threads), ts, work);
}

}  // namespace gsse::io::detail
