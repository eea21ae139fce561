#pragma once
// Errors of the readers and writers. The message always names the file and the line (text) or
// byte offset (binary), and says what was expected.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace gsse::io {

class io_error : public std::runtime_error {
 public:
  io_error(const std::string& file, std::size_t line, const std::string& what)
      : std::runtime_error(file + ":" + std::to_string(line) + ": " + what), file_(file), line_(line) {}
  /// For binary files: the position is a byte offset.
  static io_error at_byte(const std::string& file, std::size_t offset, const std::string& what) {
    io_error e(file, 0, what);
    e.line_ = 0;
    e.offset_ = offset;
    e.msg_ = file + ": byte " + std::to_string(offset) + ": " + what;
    return e;
  }
  /// Errors about a whole file (cannot open, cannot write).
  static io_error whole(const std::string& file, const std::string& what) {
    io_error e(file, 0, what);
    e.msg_ = file + ": " + what;
    return e;
  }
  const char* what() const noexcept override { return msg_.empty() ? std::runtime_error::what() : msg_.c_str(); }
  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }
  std::size_t offset() const { return offset_; }

 private:
  std::string file_;
  std::size_t line_ = 0;
  std::size_t offset_ = 0;
  std::string msg_;
};

}  // namespace gsse::io
