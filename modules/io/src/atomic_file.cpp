#include "gsse/io/atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include "gsse/io/error.hpp"

namespace gsse::io {
namespace {
std::string temporary_name(const std::string& target) {
  // random part: concurrent writers of the same target must not share a temporary
  static std::atomic<unsigned> counter{0};
  std::random_device rd;
  const auto tag = std::to_string(rd()) + "-" + std::to_string(counter++);
  const std::filesystem::path p(target);
  return (p.parent_path() / ("." + p.filename().string() + "." + tag + ".tmp")).string();
}
}  // namespace

atomic_file::atomic_file(std::string target) : target_(std::move(target)), temp_(temporary_name(target_)) {
  out_.open(temp_, std::ios::binary | std::ios::trunc);
  if (!out_) throw io_error::whole(target_, "cannot create file for writing: " + std::string(std::strerror(errno)));
}

atomic_file::~atomic_file() {
  if (done_) return;
  out_.close();
  std::error_code ec;
  std::filesystem::remove(temp_, ec);  // nothing sensible to do if this fails in a destructor
}

void atomic_file::commit() {
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok || out_.fail()) throw io_error::whole(target_, "write failed (disk full?)");
  std::error_code ec;
  // An existing target is first moved aside, so that the final rename does not replace a file:
  // ext4 (auto_da_alloc) writes the new file's blocks out synchronously inside a rename that
  // replaces one, which made the commit of a 20 MB mesh cost 20-30 ms instead of 2.
  std::string aside;
  if (std::filesystem::is_regular_file(std::filesystem::symlink_status(target_, ec))) {
    aside = temp_ + ".old";
    std::filesystem::rename(target_, aside, ec);
    if (ec) aside.clear();  // e.g. removed meanwhile: rename over whatever is there
  }
  std::filesystem::rename(temp_, target_, ec);
  if (ec) {
    std::error_code ignored;
    if (!aside.empty()) std::filesystem::rename(aside, target_, ignored);  // put the old file back
    throw io_error::whole(target_, "cannot rename temporary file: " + ec.message());
  }
  done_ = true;
  if (!aside.empty()) std::filesystem::remove(aside, ec);  // a leftover is harmless; nothing to report
}

void write_atomically(const std::string& target, const std::function<void(std::ostream&)>& body) {
  atomic_file f(target);
  body(f.stream());
  f.commit();
}

}  // namespace gsse::io
