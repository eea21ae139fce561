#include "gsse/io/text_reader.hpp"

#include <charconv>
#include <cmath>
#include <iterator>
#include <sstream>

namespace gsse::io {

text_reader::text_reader(std::string path) : name_(std::move(path)) {
  std::ifstream in(name_, std::ios::binary);
  if (!in) throw io_error::whole(name_, "cannot open file for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  data_ = ss.str();
}

text_reader::text_reader(std::string name, std::string content) : name_(std::move(name)), data_(std::move(content)) {}

bool text_reader::next_line() {
  while (at_ < data_.size()) {
    std::size_t end = data_.find('\n', at_);
    if (end == std::string::npos) end = data_.size();
    std::string_view l(data_.data() + at_, end - at_);
    at_ = end + 1;
    ++line_;
    comment_.clear();
    if (auto h = l.find('#'); h != std::string_view::npos) {
      comment_ = std::string(l.substr(h + 1));
      l = l.substr(0, h);
    }
    split(l);
    if (!tokens_.empty()) return true;
  }
  tokens_.clear();
  pos_ = 0;
  return false;
}

void text_reader::require_line(std::string_view expected) {
  if (!next_line()) {
    ++line_;
    fail("unexpected end of file, expected " + std::string(expected));
  }
}

void text_reader::split(std::string_view l) {
  tokens_.clear();
  pos_ = 0;
  std::size_t i = 0;
  while (i < l.size()) {
    while (i < l.size() && (l[i] == ' ' || l[i] == '\t' || l[i] == '\r' || l[i] == ',')) ++i;
    std::size_t j = i;
    while (j < l.size() && !(l[j] == ' ' || l[j] == '\t' || l[j] == '\r' || l[j] == ',')) ++j;
    if (j > i) tokens_.push_back(l.substr(i, j - i));
    i = j;
  }
}

std::string_view text_reader::token(std::string_view expected) {
  if (pos_ >= tokens_.size()) fail("missing field, expected " + std::string(expected));
  return tokens_[pos_++];
}

long text_reader::integer(std::string_view expected) {
  auto t = token(expected);
  if (t.size() > 1 && t[0] == '+') t.remove_prefix(1);
  long v = 0;
  auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec != std::errc() || p != t.data() + t.size())
    fail("'" + std::string(t) + "' is not an integer, expected " + std::string(expected));
  return v;
}

long text_reader::integer_in(std::string_view expected, long lo, long hi) {
  const long v = integer(expected);
  if (v < lo || v > hi)
    fail(std::string(expected) + " " + std::to_string(v) + " out of range [" + std::to_string(lo) + ", " +
         std::to_string(hi) + "]");
  return v;
}

double text_reader::real(std::string_view expected) {
  auto t = token(expected);
  if (t.size() > 1 && t[0] == '+') t.remove_prefix(1);
  double v = 0;
  auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec == std::errc::result_out_of_range || (ec == std::errc() && p == t.data() + t.size() && !std::isfinite(v)))
    fail("'" + std::string(t) + "' is not a finite number, expected " + std::string(expected));
  if (ec != std::errc() || p != t.data() + t.size())
    fail("'" + std::string(t) + "' is not a number, expected " + std::string(expected));
  return v;
}

long text_reader::optional_integer(std::string_view expected, long fallback) {
  return has_token() ? integer(expected) : fallback;
}
double text_reader::optional_real(std::string_view expected, double fallback) {
  return has_token() ? real(expected) : fallback;
}

void text_reader::fail(std::string_view what) const { throw io_error(name_, line_, std::string(what)); }

}  // namespace gsse::io
