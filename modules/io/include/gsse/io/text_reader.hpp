#pragma once
// Line-oriented tokenizer for the TetGen/Triangle family of text formats: '#' starts a comment,
// blank lines are skipped, every token read is checked (numeric, finite, in range), and every
// failure names file, line and what was expected.
#include <cstddef>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "gsse/io/error.hpp"

namespace gsse::io {

class text_reader {
 public:
  /// Opens `path`; throws io_error if it cannot be read.
  explicit text_reader(std::string path);
  /// Reads from an in-memory buffer (fuzzing, tests); `name` is used in messages.
  text_reader(std::string name, std::string content);

  /// Advances to the next non-empty, non-comment line. Returns false at end of input.
  bool next_line();
  /// Like next_line, but end of input is an error naming `expected`.
  void require_line(std::string_view expected);
  bool has_token() const { return pos_ < tokens_.size(); }
  std::size_t tokens_left() const { return tokens_.size() - pos_; }
  std::string_view token(std::string_view expected);
  long integer(std::string_view expected);
  long integer_in(std::string_view expected, long lo, long hi);
  double real(std::string_view expected);  // finite only
  /// Optional trailing integer (e.g. a marker); `fallback` if the line has no more tokens.
  long optional_integer(std::string_view expected, long fallback);
  double optional_real(std::string_view expected, double fallback);
  /// Rest of the current line after the tokens consumed, comment stripped (names in comments).
  const std::string& comment() const { return comment_; }

  [[noreturn]] void fail(std::string_view what) const;
  const std::string& name() const { return name_; }
  /// Bytes not yet consumed: bounds every count before anything is allocated for it.
  std::size_t bytes_left() const { return at_ < data_.size() ? data_.size() - at_ : 0; }
  std::size_t line() const { return line_; }

 private:
  void split(std::string_view s);
  std::string name_;
  std::string data_;
  std::size_t at_ = 0;
  std::size_t line_ = 0;
  std::vector<std::string_view> tokens_;
  std::string comment_;
  std::size_t pos_ = 0;
};

}  // namespace gsse::io
