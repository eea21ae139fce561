#pragma once
// Writers never leave partial output: they write to a temporary file next to the target (same
// directory, hence same file system, so rename() is atomic) and rename it only once everything
// was written and flushed. Destroying an atomic_file that was not committed removes the temporary.
#include <fstream>
#include <functional>
#include <string>

#include "gsse/io/error.hpp"

namespace gsse::io {

class atomic_file {
 public:
  explicit atomic_file(std::string target);
  atomic_file(const atomic_file&) = delete;
  atomic_file& operator=(const atomic_file&) = delete;
  ~atomic_file();

  std::ostream& stream() { return out_; }
  /// Flushes, checks the stream and renames the temporary onto the target; throws io_error.
  void commit();
  const std::string& target() const { return target_; }
  const std::string& temporary() const { return temp_; }

 private:
  std::string target_;
  std::string temp_;
  std::ofstream out_;
  bool done_ = false;
};

/// Runs `body` on the stream of an atomic_file for `target` and commits if it returns normally.
void write_atomically(const std::string& target, const std::function<void(std::ostream&)>& body);

}  // namespace gsse::io
