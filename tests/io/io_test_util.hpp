#pragma once
// Helpers for the I/O tests: a scratch directory per test executable and file writers.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>

namespace gsse::test {

/// A fresh directory under the build tree (or /tmp), removed at exit unless GSSE_KEEP_TEST_FILES is set.
struct scratch_dir {
  std::filesystem::path path;
  explicit scratch_dir(const std::string& tag) {
    path = std::filesystem::temp_directory_path() / ("gsse_io_" + tag + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~scratch_dir() {
    if (!std::getenv("GSSE_KEEP_TEST_FILES")) {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
  std::string write(const std::string& name, const std::string& content) const {
    const auto p = file(name);
    std::ofstream(p, std::ios::binary) << content;
    return p;
  }
};

inline std::string slurp_file(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace gsse::test
