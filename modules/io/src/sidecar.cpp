#include "gsse/io/sidecar.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "gsse/io/atomic_file.hpp"
#include "gsse/io/error.hpp"

namespace gsse::io {
namespace {

// Just enough JSON to read one array of strings or of integers under a top-level key. The rest of
// the file (other keys of the generator's metadata) is skipped, not validated.
struct json_scan {
  const std::string& s;
  const std::string& file;
  std::size_t line_at(std::size_t pos) const {
    std::size_t l = 1;
    for (std::size_t i = 0; i < pos && i < s.size(); ++i) l += s[i] == '\n';
    return l;
  }
  [[noreturn]] void fail(std::size_t pos, const std::string& what) const { throw io_error(file, line_at(pos), what); }
  std::size_t skip_ws(std::size_t i) const {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')) ++i;
    return i;
  }
  // position just after the top-level object's `"key"` and its colon, or npos (a key of a nested
  // object, e.g. an interface entry's "grade" or a segment named like a key, is not it)
  std::size_t find_key(const std::string& key) const {
    int depth = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const char c = s[i];
      if (c == '{' || c == '[') {
        ++depth;
      } else if (c == '}' || c == ']') {
        --depth;
      } else if (c == '"') {
        const std::size_t start = i + 1;
        for (++i; i < s.size() && s[i] != '"'; ++i)
          if (s[i] == '\\') ++i;
        if (i >= s.size()) return std::string::npos;
        if (depth != 1) continue;
        const std::size_t after = skip_ws(i + 1);
        if (after < s.size() && s[after] == ':' && s.compare(start, i - start, key) == 0 && i - start == key.size())
          return skip_ws(after + 1);
      }
    }
    return std::string::npos;
  }
  std::string string_at(std::size_t& i) const {
    if (i >= s.size() || s[i] != '"') fail(i, "expected a string");
    std::string r;
    for (++i; i < s.size() && s[i] != '"'; ++i) {
      if (s[i] == '\\') {
        if (++i >= s.size()) break;
        switch (s[i]) {
          case 'n': r += '\n'; break;
          case 't': r += '\t'; break;
          case 'u': fail(i, "\\u escapes are not supported in segment names");
          default: r += s[i];
        }
      } else {
        r += s[i];
      }
    }
    if (i >= s.size()) fail(i, "unterminated string");
    ++i;
    return r;
  }
  long integer_at(std::size_t& i) const {
    long v = 0;
    auto [p, ec] = std::from_chars(s.data() + i, s.data() + s.size(), v);
    if (ec != std::errc()) fail(i, "expected an integer");
    i = static_cast<std::size_t>(p - s.data());
    return v;
  }
  // a JSON value (object, array, string, number, true/false/null), for the sizing keys
  struct value {
    enum kind_t { object, array, string, number, literal } kind = literal;
    std::string text;  // string
    double num = 0;    // number
    // object: keys[i] names items[i]; array: items (std::vector, unlike std::pair, may hold the
    // incomplete type)
    std::vector<std::string> keys;
    std::vector<value> items;
    std::size_t pos = 0;
    const value* get(const std::string& k) const {
      for (std::size_t i = 0; i < keys.size(); ++i)
        if (keys[i] == k) return &items[i];
      return nullptr;
    }
  };
  value value_at(std::size_t& i, int depth = 0) const {
    if (depth > 32) fail(i, "nested too deeply");
    i = skip_ws(i);
    value v;
    v.pos = i;
    if (i >= s.size()) fail(i, "expected a value");
    if (s[i] == '"') {
      v.kind = value::string;
      v.text = string_at(i);
    } else if (s[i] == '{' || s[i] == '[') {
      const bool obj = s[i] == '{';
      const char close = obj ? '}' : ']';
      v.kind = obj ? value::object : value::array;
      i = skip_ws(i + 1);
      if (i < s.size() && s[i] == close) {
        ++i;
        return v;
      }
      while (true) {
        i = skip_ws(i);
        if (obj) {
          std::string k = string_at(i);
          i = skip_ws(i);
          if (i >= s.size() || s[i] != ':') fail(i, "expected ':'");
          ++i;
          v.keys.push_back(std::move(k));
          v.items.push_back(value_at(i, depth + 1));
        } else {
          v.items.push_back(value_at(i, depth + 1));
        }
        i = skip_ws(i);
        if (i < s.size() && s[i] == ',') {
          ++i;
          continue;
        }
        if (i < s.size() && s[i] == close) {
          ++i;
          return v;
        }
        fail(i, std::string("expected ',' or '") + close + "'");
      }
    } else if (s.compare(i, 4, "true") == 0 || s.compare(i, 4, "null") == 0 || s.compare(i, 5, "false") == 0) {
      i += s[i] == 'f' ? 5 : 4;
    } else {
      v.kind = value::number;
      auto [p, ec] = std::from_chars(s.data() + i, s.data() + s.size(), v.num);
      if (ec != std::errc() || !std::isfinite(v.num)) fail(i, "expected a number");
      i = static_cast<std::size_t>(p - s.data());
    }
    return v;
  }
  double positive(const value& v, const std::string& what) const {
    if (v.kind != value::number || !(v.num > 0)) fail(v.pos, what + " must be a positive number");
    return v.num;
  }
  template <class F>
  void array_at(std::size_t i, F item) const {
    if (i >= s.size() || s[i] != '[') fail(i, "expected '['");
    i = skip_ws(i + 1);
    if (i < s.size() && s[i] == ']') return;
    while (true) {
      item(i);
      i = skip_ws(i);
      if (i < s.size() && s[i] == ',') {
        i = skip_ws(i + 1);
        continue;
      }
      if (i < s.size() && s[i] == ']') return;
      fail(i, "expected ',' or ']'");
    }
  }
};

/// An entry's own "grade" (above 1), or 0 when it has none.
double own_grade(const json_scan& j, const json_scan::value& entry, const std::string& whose) {
  const json_scan::value* g = entry.get("grade");
  if (!g) return 0;
  if (g->kind != json_scan::value::number || !(g->num > 1)) j.fail(g->pos, whose + " \"grade\" must be a number above 1");
  return g->num;
}

void read_sizing(const json_scan& j, sizing_table& t) {
  using value = json_scan::value;
  if (auto i = j.find_key("sizes"); i != std::string::npos) {
    const value v = j.value_at(i);
    if (v.kind != value::object) j.fail(v.pos, "\"sizes\" must be an object {\"<segment>\": <size>, ...}");
    for (std::size_t k = 0; k < v.keys.size(); ++k) {
      const auto& h = v.items[k];
      t.sizes.push_back({v.keys[k], j.positive(h, "the size of segment '" + v.keys[k] + "'"), j.line_at(h.pos)});
    }
  }
  if (auto i = j.find_key("refine"); i != std::string::npos) {
    const value v = j.value_at(i);
    if (v.kind != value::array) j.fail(v.pos, "\"refine\" must be an array of {\"lo\": [..], \"hi\": [..], \"size\": h}");
    for (const auto& b : v.items) {
      if (b.kind != value::object) j.fail(b.pos, "a refinement box must be an object");
      sizing_table::box box;
      box.line = j.line_at(b.pos);
      for (const char* key : {"lo", "hi"}) {
        const value* c = b.get(key);
        if (!c || c->kind != value::array || c->items.size() < 2 || c->items.size() > 3)
          j.fail(b.pos, std::string("a refinement box needs \"") + key + "\": [x, y] or [x, y, z]");
        for (const auto& x : c->items) {
          if (x.kind != value::number) j.fail(x.pos, "expected a number");
          (key[0] == 'l' ? box.lo : box.hi).push_back(x.num);
        }
      }
      if (box.lo.size() != box.hi.size()) j.fail(b.pos, "\"lo\" and \"hi\" have different dimensions");
      for (std::size_t k = 0; k < box.lo.size(); ++k)
        if (box.lo[k] > box.hi[k]) j.fail(b.pos, "\"lo\" is above \"hi\" in coordinate " + std::to_string(k + 1));
      const value* h = b.get("size");
      if (!h) j.fail(b.pos, "a refinement box needs \"size\"");
      box.size = j.positive(*h, "a refinement box's size");
      box.grade = own_grade(j, b, "a refinement box's");
      t.boxes.push_back(std::move(box));
    }
  }
  if (auto i = j.find_key("interfaces"); i != std::string::npos) {
    const value v = j.value_at(i);
    if (v.kind != value::array) j.fail(v.pos, "\"interfaces\" must be an array of {\"between\": [a, b], \"size\": h}");
    for (const auto& e : v.items) {
      const value* w = e.kind == value::object ? e.get("between") : nullptr;
      if (!w || w->kind != value::array || w->items.size() != 2 || w->items[0].kind != value::string ||
          w->items[1].kind != value::string)
        j.fail(e.pos, "an interface needs \"between\": [\"<segment>\", \"<segment>\"]");
      const value* h = e.get("size");
      if (!h) j.fail(e.pos, "an interface needs \"size\"");
      t.interfaces.push_back({w->items[0].text, w->items[1].text, j.positive(*h, "an interface's size"), j.line_at(e.pos),
                              own_grade(j, e, "an interface's")});
    }
  }
  if (auto i = j.find_key("background"); i != std::string::npos) {
    t.background = j.string_at(i);
    if (t.background.empty()) j.fail(i, "empty \"background\" path");
  }
  if (auto i = j.find_key("grade"); i != std::string::npos) {
    const value v = j.value_at(i);
    if (v.kind != value::number || !(v.num > 1)) j.fail(v.pos, "\"grade\" must be a number above 1");
    t.grade = v.num;
  }
}

}  // namespace

std::string json_string(const std::string& n) {
  std::string r = "\"";
  for (char c : n) {
    if (c == '"' || c == '\\') r += '\\';
    if (c == '\n') { r += "\\n"; continue; }
    if (c == '\t') { r += "\\t"; continue; }
    r += c;
  }
  return r + "\"";
}

std::string base_of(const std::string& path) {
  std::filesystem::path p(path);
  return (p.parent_path() / p.stem()).string();
}

std::string segment_table::name_of(int number) const {
  if (numbers.empty()) {
    if (number >= 1 && static_cast<std::size_t>(number) <= names.size()) return names[static_cast<std::size_t>(number - 1)];
    return {};
  }
  for (std::size_t k = 0; k < numbers.size() && k < names.size(); ++k)
    if (numbers[k] == number) return names[k];
  return {};
}

segment_table read_sidecar(const std::string& json_path) {
  segment_table t;
  std::error_code fs_error;
  if (!std::filesystem::exists(json_path, fs_error)) return t;  // no sidecar: no names
  std::ifstream in(json_path, std::ios::binary);
  if (!in || std::filesystem::is_directory(json_path, fs_error)) throw io_error::whole(json_path, "cannot read the sidecar file");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string s = ss.str();
  json_scan j{s, json_path};
  if (auto i = j.find_key("segments"); i != std::string::npos)
    j.array_at(i, [&](std::size_t& k) {
      if (k < s.size() && s[k] == '{')  // what a gsse-mesh --stats file holds there
        j.fail(k, "\"segments\" lists objects, as a gsse-mesh --stats file does: a sidecar's \"segments\" is a list of "
                  "names (docs/io.md); BASE.json beside an input is read as its sidecar, so keep statistics under another name");
      t.names.push_back(j.string_at(k));
    });
  if (auto i = j.find_key("numbers"); i != std::string::npos)
    j.array_at(i, [&](std::size_t& k) {
      const long v = j.integer_at(k);
      if (v < -1'000'000'000 || v > 1'000'000'000) j.fail(k, "segment number out of range");
      t.numbers.push_back(static_cast<int>(v));
    });
  if (!t.numbers.empty() && t.numbers.size() != t.names.size())
    j.fail(j.find_key("numbers"), "\"numbers\" has " + std::to_string(t.numbers.size()) + " entries, \"segments\" has " +
                                      std::to_string(t.names.size()));
  // an object {"<marker>": "<name>", ...}; a number is the benchmark generator's facet count
  if (auto i = j.find_key("facets"); i != std::string::npos && !(i < s.size() && (s[i] == '-' || (s[i] >= '0' && s[i] <= '9')))) {
    if (i >= s.size() || s[i] != '{') j.fail(i, "\"facets\" must be an object {\"<marker>\": \"<name>\", ...}");
    i = j.skip_ws(i + 1);
    while (i < s.size() && s[i] != '}') {
      const std::size_t at = i;
      const std::string key = j.string_at(i);
      long marker = 0;
      auto [end, ec] = std::from_chars(key.data(), key.data() + key.size(), marker);
      if (ec != std::errc() || end != key.data() + key.size() || marker < -1'000'000'000 || marker > 1'000'000'000)
        j.fail(at, "facet marker '" + key + "' is not an integer");
      i = j.skip_ws(i);
      if (i >= s.size() || s[i] != ':') j.fail(i, "expected ':'");
      i = j.skip_ws(i + 1);
      const std::string name = j.string_at(i);
      if (name.empty()) j.fail(i, "empty name for facet marker " + key);
      if (!t.facet_names.emplace(static_cast<int>(marker), name).second) j.fail(at, "facet marker " + key + " named twice");
      i = j.skip_ws(i);
      if (i < s.size() && s[i] == ',') {
        i = j.skip_ws(i + 1);
        continue;
      }
      if (i >= s.size() || s[i] != '}') j.fail(i, "expected ',' or '}'");
    }
    if (i >= s.size()) j.fail(i, "unterminated \"facets\" object");
  }
  read_sizing(j, t.sizing);
  if (auto i = j.find_key("face_marker_base"); i != std::string::npos) {
    const long v = j.integer_at(i);
    if (v < 0 || v > 1'000'000'000) j.fail(i, "face_marker_base out of range");
    t.face_marker_base = static_cast<int>(v);
  }
  return t;
}

void write_sidecar(const std::string& json_path, const segment_table& t) {
  write_atomically(json_path, [&](std::ostream& o) {
    o << "{\n \"segments\": [";
    for (std::size_t k = 0; k < t.names.size(); ++k) o << (k ? ", " : "") << json_string(t.names[k]);
    o << "],\n \"numbers\": [";
    for (std::size_t k = 0; k < t.numbers.size(); ++k) o << (k ? ", " : "") << t.numbers[k];
    o << "]";
    if (t.face_marker_base > 0) o << ",\n \"face_marker_base\": " << t.face_marker_base;
    if (!t.facet_names.empty()) {
      o << ",\n \"facets\": {";
      bool first = true;
      for (const auto& [m, n] : t.facet_names) {
        o << (first ? "" : ", ") << json_string(std::to_string(m)) << ": " << json_string(n);
        first = false;
      }
      o << "}";
    }
    o << "\n}\n";
  });
}

}  // namespace gsse::io
