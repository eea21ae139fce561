#pragma once
// The one error type of the rule language: parser and validator both report "FILE:LINE: message",
// so an author can jump to the offending line.
#include <stdexcept>
#include <string>

namespace gsse::rules {

class rule_error : public std::runtime_error {
 public:
  rule_error(std::string file, int line, std::string message)
      : std::runtime_error(file + ":" + std::to_string(line) + ": " + message),
        file_(std::move(file)), line_(line), message_(std::move(message)) {}
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  /// The message without the "FILE:LINE: " prefix.
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  int line_ = 0;
  std::string message_;
};

}  // namespace gsse::rules
