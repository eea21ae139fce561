#pragma once
// Internal: bounds-checked little-endian reads from an in-memory file; every failure is an
// io_error naming the byte offset.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>

#include "gsse/io/error.hpp"

namespace gsse::io::detail {

class binary_cursor {
 public:
  binary_cursor(const std::string& file, std::string_view data, std::size_t pos = 0) : file_(file), data_(data), pos_(pos) {}
  std::size_t pos() const { return pos_; }
  void seek(std::size_t p) { pos_ = p; }
  std::size_t left() const { return pos_ < data_.size() ? data_.size() - pos_ : 0; }
  [[noreturn]] void fail(const std::string& what) const { throw io_error::at_byte(file_, pos_, what); }
  void need(std::size_t n, const std::string& expected) const {
    if (left() < n)
      fail("unexpected end of file, expected " + expected + " (" + std::to_string(n) + " bytes, " +
           std::to_string(left()) + " left)");
  }
  template <class T>
  T get(const std::string& expected) {
    need(sizeof(T), expected);
    T v;
    std::memcpy(&v, data_.data() + pos_, sizeof(T));
    if constexpr (std::endian::native == std::endian::big && sizeof(T) > 1) v = swap(v);
    pos_ += sizeof(T);
    return v;
  }
  /// Checks that `count` items of `item_bytes` each fit in the rest of the file before any
  /// allocation for them.
  void check_count(std::uint64_t count, std::size_t item_bytes, const std::string& what) const {
    if (item_bytes && count > left() / item_bytes)
      fail(what + " " + std::to_string(count) + " needs " + std::to_string(item_bytes) + " bytes each, only " +
           std::to_string(left()) + " bytes left");
  }

 private:
  template <class T>
  static T swap(T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    std::memcpy(&v, b, sizeof(T));
    return v;
  }
  const std::string& file_;
  std::string_view data_;
  std::size_t pos_;
};

std::string slurp(const std::string& path);

}  // namespace gsse::io::detail
