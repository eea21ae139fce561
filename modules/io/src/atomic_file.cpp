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
  std::filesystem::rename(temp_, target_, ec);
  if (ec) throw io_error::whole(target_, "cannot rename temporary file: " + ec.message());
  done_ = true;
}

void write_atomically(const std::string& target, const std::function<void(std::ostream&)>& body) {
  atomic_file f(target);
  body(f.stream());
  f.commit();
}

}  // namespace gsse::io
