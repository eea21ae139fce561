// The .vtu reader (gsse/io/vtu.hpp): a small XML tag scanner (the format needs elements and
// attributes only), the three data formats, and zlib-compressed blocks.
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>

#include "binary_cursor.hpp"
#include "gsse/io/vtu.hpp"
#include "number_format.hpp"

namespace gsse::io {

const vtu_grid::array* vtu_grid::point_array(std::string_view name) const {
  for (const auto& a : point_data)
    if (a.name == name) return &a;
  return nullptr;
}

namespace {

std::string num(double v) {
  std::string s;
  detail::append_real(s, v);
  return s;
}

struct tag {
  std::string name;
  bool closing = false, self_closing = false;
  std::map<std::string, std::string> attrs;
  std::size_t begin = 0, end = 0, line = 1;  // end: just after '>'
  const std::string* attr(const std::string& k) const {
    auto it = attrs.find(k);
    return it == attrs.end() ? nullptr : &it->second;
  }
};

class scanner {
 public:
  scanner(const std::string& file, std::string_view text) : file_(file), text_(text) {}
  std::size_t line_at(std::size_t pos) {
    // positions only move forward in one scan; count newlines incrementally
    if (pos < counted_) counted_ = 0, line_ = 1;
    line_ += static_cast<std::size_t>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(counted_),
                                                 text_.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
    counted_ = pos;
    return line_;
  }
  [[noreturn]] void fail(std::size_t pos, const std::string& what) { throw io_error(file_, line_at(pos), what); }

  /// The next element tag at or after pos (comments, declarations and processing instructions
  /// skipped); false at the end of the text.
  bool next(std::size_t& pos, tag& t) {
    for (;;) {
      const std::size_t lt = text_.find('<', pos);
      if (lt == std::string_view::npos) return false;
      auto skip_to = [&](std::string_view close) {
        const std::size_t e = text_.find(close, lt);
        if (e == std::string_view::npos) fail(lt, "unterminated '" + std::string(text_.substr(lt, 4)) + "'");
        pos = e + close.size();
      };
      if (text_.compare(lt, 4, "<!--") == 0) { skip_to("-->"); continue; }
      if (text_.compare(lt, 9, "<![CDATA[") == 0) { skip_to("]]>"); continue; }
      if (text_.compare(lt, 2, "<?") == 0) { skip_to("?>"); continue; }
      if (text_.compare(lt, 2, "<!") == 0) { skip_to(">"); continue; }
      t = tag{};
      t.begin = lt;
      t.line = line_at(lt);
      std::size_t i = lt + 1;
      if (i < text_.size() && text_[i] == '/') t.closing = true, ++i;
      const std::size_t n0 = i;
      while (i < text_.size() && !std::isspace(static_cast<unsigned char>(text_[i])) && text_[i] != '>' && text_[i] != '/') ++i;
      t.name = std::string(text_.substr(n0, i - n0));
      if (t.name.empty()) fail(lt, "a '<' that starts no element");
      for (;;) {
        while (i < text_.size() && std::isspace(static_cast<unsigned char>(text_[i]))) ++i;
        if (i >= text_.size()) fail(lt, "unterminated element <" + t.name + ">");
        if (text_[i] == '>') { ++i; break; }
        if (text_[i] == '/' && i + 1 < text_.size() && text_[i + 1] == '>') { t.self_closing = true; i += 2; break; }
        const std::size_t a0 = i;
        while (i < text_.size() && text_[i] != '=' && !std::isspace(static_cast<unsigned char>(text_[i])) && text_[i] != '>') ++i;
        const std::string key(text_.substr(a0, i - a0));
        while (i < text_.size() && std::isspace(static_cast<unsigned char>(text_[i]))) ++i;
        if (i >= text_.size() || text_[i] != '=') fail(lt, "attribute '" + key + "' of <" + t.name + "> has no value");
        ++i;
        while (i < text_.size() && std::isspace(static_cast<unsigned char>(text_[i]))) ++i;
        if (i >= text_.size() || (text_[i] != '"' && text_[i] != '\'')) fail(lt, "attribute '" + key + "' of <" + t.name + "> is not quoted");
        const char q = text_[i++];
        const std::size_t v = text_.find(q, i);
        if (v == std::string_view::npos) fail(lt, "unterminated value of attribute '" + key + "'");
        t.attrs[key] = std::string(text_.substr(i, v - i));
        i = v + 1;
      }
      t.end = pos = i;
      return true;
    }
  }

 private:
  std::string file_;
  std::string_view text_;
  std::size_t counted_ = 0, line_ = 1;
};

/// Bytes of one array, from raw bytes or a base64 text. Base64 is decoded quantum by quantum so
/// that a header encoded apart from its data (padding in the middle, as VTK and meshio write
/// compressed arrays) and one encoded with it both decode.
class byte_source {
 public:
  byte_source(std::string_view data, bool base64) : data_(data), base64_(base64) {}
  /// The next n bytes; false if the data ends first.
  bool get(std::size_t n, std::string& out) {
    out.clear();
    if (!base64_) {
      if (data_.size() - pos_ < n) return false;
      out.assign(data_.substr(pos_, n));
      pos_ += n;
      return true;
    }
    while (buf_.size() - used_ < n) {
      if (!quantum()) return false;
    }
    out.assign(buf_, used_, n);
    used_ += n;
    if (used_ > 1 << 16) buf_.erase(0, used_), used_ = 0;
    return true;
  }

 private:
  static int value(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  }
  bool quantum() {
    char q[4];
    int k = 0;
    while (k < 4 && pos_ < data_.size()) {
      const char c = data_[pos_++];
      if (std::isspace(static_cast<unsigned char>(c))) continue;
      if (c != '=' && value(c) < 0) return false;  // end of the base64 text (e.g. '<' of the closing tag)
      q[k++] = c;
    }
    if (k < 4) return false;
    int pad = 0;
    std::uint32_t v = 0;
    for (int j = 0; j < 4; ++j) {
      if (q[j] == '=') {
        ++pad;
        v <<= 6;
      } else {
        if (pad) return false;
        v = (v << 6) | static_cast<std::uint32_t>(value(q[j]));
      }
    }
    if (pad > 2) return false;
    const char b[3] = {static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
    buf_.append(b, static_cast<std::size_t>(3 - pad));
    return true;
  }
  std::string_view data_;
  bool base64_;
  std::size_t pos_ = 0;
  std::string buf_;
  std::size_t used_ = 0;
};

struct file_format {
  bool big_endian = false;
  bool header64 = false;
  bool zlib = false;
};

std::size_t type_size(const std::string& t) {
  static const std::map<std::string, std::size_t> sizes{{"Int8", 1},  {"UInt8", 1},  {"Int16", 2},   {"UInt16", 2},
                                                        {"Int32", 4}, {"UInt32", 4}, {"Int64", 8},   {"UInt64", 8},
                                                        {"Float32", 4}, {"Float64", 8}, {"Char", 1}, {"UChar", 1}};
  auto it = sizes.find(t);
  return it == sizes.end() ? 0 : it->second;
}

template <class T>
T load(const char* p, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

double to_double(const std::string& type, const char* p, bool swap) {
  if (type == "Float64") return load<double>(p, swap);
  if (type == "Float32") return load<float>(p, swap);
  if (type == "Int8" || type == "Char") return load<std::int8_t>(p, swap);
  if (type == "UInt8" || type == "UChar") return load<std::uint8_t>(p, swap);
  if (type == "Int16") return load<std::int16_t>(p, swap);
  if (type == "UInt16") return load<std::uint16_t>(p, swap);
  if (type == "Int32") return load<std::int32_t>(p, swap);
  if (type == "UInt32") return load<std::uint32_t>(p, swap);
  if (type == "Int64") return static_cast<double>(load<std::int64_t>(p, swap));
  return static_cast<double>(load<std::uint64_t>(p, swap));
}

class reader {
 public:
  reader(const std::string& path, std::string text) : path_(path), text_(std::move(text)) {}

  vtu_grid run() {
    vtu_grid g;
    g.source = path_;
    g.cell_start.push_back(0);
    // the XML part ends where raw appended data may begin
    std::size_t xml_end = text_.size();
    const std::size_t app = text_.find("<AppendedData");
    if (app != std::string::npos) xml_end = app;
    scanner sc(path_, std::string_view(text_).substr(0, xml_end));
    if (app != std::string::npos) read_appended(app);

    std::size_t pos = 0;
    tag t;
    bool seen_file = false, seen_grid = false;
    std::string section;  // Points, Cells, PointData, CellData, FieldData
    piece pc;
    bool in_piece = false;
    while (sc.next(pos, t)) {
      if (t.name == "VTKFile" && !t.closing) {
        seen_file = true;
        const std::string* type = t.attr("type");
        if (!type || *type != "UnstructuredGrid")
          throw io_error(path_, t.line, "a VTK XML file of type '" + (type ? *type : std::string("?")) + "'; an UnstructuredGrid (.vtu) is expected");
        if (auto* b = t.attr("byte_order")) {
          if (*b == "BigEndian") fmt_.big_endian = true;
          else if (*b != "LittleEndian") throw io_error(path_, t.line, "unknown byte_order '" + *b + "'");
        }
        if (auto* h = t.attr("header_type")) {
          if (*h == "UInt64") fmt_.header64 = true;
          else if (*h != "UInt32") throw io_error(path_, t.line, "header_type '" + *h + "' (UInt32 or UInt64 expected)");
        }
        if (auto* c = t.attr("compressor")) {
          if (*c == "vtkZLibDataCompressor") fmt_.zlib = true;
          else if (!c->empty())
            throw io_error(path_, t.line, "compressor '" + *c + "' is not supported (uncompressed or vtkZLibDataCompressor; re-save with zlib or no compression)");
        }
      } else if (t.name == "UnstructuredGrid" && !t.closing) {
        if (!seen_file) throw io_error(path_, t.line, "<UnstructuredGrid> outside <VTKFile>");
        seen_grid = true;
      } else if (t.name == "Piece") {
        if (!t.closing) {
          if (!seen_grid) throw io_error(path_, t.line, "<Piece> outside <UnstructuredGrid>");
          pc = piece{};
          pc.line = t.line;
          pc.points = count_attr(t, "NumberOfPoints");
          pc.cells = count_attr(t, "NumberOfCells");
          in_piece = true;
          if (t.self_closing) { finish(g, pc); in_piece = false; }
        } else if (in_piece) {
          finish(g, pc);
          in_piece = false;
        }
      } else if (t.name == "Points" || t.name == "Cells" || t.name == "PointData" || t.name == "CellData" || t.name == "FieldData") {
        section = (t.closing || t.self_closing) ? std::string() : t.name;
        if (t.name == "Cells" && !t.closing) pc.cells_line = t.line;
      } else if (t.name == "DataArray" && !t.closing) {
        std::string_view inline_text;
        if (!t.self_closing) {
          const std::size_t close = text_.find("</DataArray", t.end);
          if (close == std::string::npos || close > xml_end) throw io_error(path_, t.line, "<DataArray> is not closed");
          inline_text = std::string_view(text_).substr(t.end, close - t.end);
          pos = close;
        }
        if (!in_piece || section.empty() || section == "CellData" || section == "FieldData") continue;
        const std::string* name = t.attr("Name");
        array a;
        a.name = name ? *name : std::string();
        a.line = t.line;
        a.components = t.attr("NumberOfComponents") ? count_attr(t, "NumberOfComponents") : 1;
        if (a.components == 0) throw io_error(path_, t.line, "NumberOfComponents 0");
        a.values = decode(t, inline_text);
        if (section == "Points") pc.coords = std::move(a);
        else if (section == "Cells") pc.cell_arrays.push_back(std::move(a));
        else pc.point_data.push_back(std::move(a));
      }
    }
    if (!seen_file) throw io_error(path_, 1, "no <VTKFile> element: not a VTK XML file");
    if (!seen_grid) throw io_error(path_, 1, "no <UnstructuredGrid> element");
    if (in_piece) throw io_error(path_, pc.line, "<Piece> is not closed");
    if (pieces_ == 0) throw io_error(path_, 1, "no <Piece> in the UnstructuredGrid");
    // point arrays kept: those every piece has, with the same number of components
    for (auto& a : data_)
      if (a.pieces == pieces_) g.point_data.push_back(std::move(a.a));
    return g;
  }

 private:
  using array = vtu_grid::array;
  struct piece {
    std::size_t line = 0, cells_line = 0, points = 0, cells = 0;
    array coords;
    std::vector<array> cell_arrays, point_data;
  };
  struct merged {
    array a;
    std::size_t pieces = 0;
  };

  std::size_t count_attr(const tag& t, const std::string& k) {
    const std::string* v = t.attr(k);
    if (!v) throw io_error(path_, t.line, "<" + t.name + "> has no " + k);
    std::uint64_t n = 0;
    auto [end, ec] = std::from_chars(v->data(), v->data() + v->size(), n);
    if (ec != std::errc() || end != v->data() + v->size()) throw io_error(path_, t.line, k + " '" + *v + "' is not a count");
    if (n > (std::uint64_t{1} << 40)) throw io_error(path_, t.line, k + " " + *v + " is too large");
    return static_cast<std::size_t>(n);
  }

  void read_appended(std::size_t at) {
    scanner sc(path_, text_);
    std::size_t pos = at;
    tag t;
    if (!sc.next(pos, t) || t.name != "AppendedData") sc.fail(at, "malformed <AppendedData>");
    const std::string* enc = t.attr("encoding");
    if (!enc) sc.fail(at, "<AppendedData> has no encoding");
    if (*enc == "base64") appended_base64_ = true;
    else if (*enc != "raw") sc.fail(at, "<AppendedData> encoding '" + *enc + "' (raw or base64 expected)");
    std::size_t i = t.end;
    while (i < text_.size() && std::isspace(static_cast<unsigned char>(text_[i]))) ++i;
    if (i >= text_.size() || text_[i] != '_') sc.fail(at, "<AppendedData> does not start with '_'");
    appended_ = std::string_view(text_).substr(i + 1);
    has_appended_ = true;
  }

  std::vector<double> decode(const tag& t, std::string_view inline_text) {
    const std::string* type = t.attr("type");
    if (!type) throw io_error(path_, t.line, "<DataArray> has no type");
    const std::size_t ts = type_size(*type);
    if (ts == 0) throw io_error(path_, t.line, "DataArray type '" + *type + "' is not a VTK numeric type");
    const std::string* f = t.attr("format");
    const std::string format = f ? *f : "ascii";
    std::vector<double> out;
    if (format == "ascii") {
      const char* p = inline_text.data();
      const char* e = p + inline_text.size();
      for (;;) {
        while (p < e && std::isspace(static_cast<unsigned char>(*p))) ++p;
        if (p >= e) break;
        double v = 0;
        auto [q, ec] = std::from_chars(p, e, v);
        if (ec != std::errc()) {
          const char* w = p;
          while (w < e && !std::isspace(static_cast<unsigned char>(*w))) ++w;
          throw io_error(path_, t.line, "'" + std::string(p, std::min<std::size_t>(static_cast<std::size_t>(w - p), 40)) + "' in ascii DataArray '" +
                                            (t.attr("Name") ? *t.attr("Name") : std::string()) + "' is not a number");
        }
        out.push_back(v);
        p = q;
      }
      return out;
    }
    std::string bytes;
    if (format == "binary") {
      byte_source src(inline_text, true);
      bytes = block(src, t);
    } else if (format == "appended") {
      if (!has_appended_) throw io_error(path_, t.line, "an appended DataArray but no <AppendedData>");
      const std::size_t off = t.attr("offset") ? count_attr(t, "offset") : 0;
      if (off > appended_.size()) throw io_error(path_, t.line, "offset " + std::to_string(off) + " beyond the appended data");
      byte_source src(appended_.substr(off), appended_base64_);
      bytes = block(src, t);
    } else {
      throw io_error(path_, t.line, "DataArray format '" + format + "' (ascii, binary or appended expected)");
    }
    if (bytes.size() % ts != 0) throw io_error(path_, t.line, std::to_string(bytes.size()) + " bytes are not a whole number of " + *type);
    out.resize(bytes.size() / ts);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = to_double(*type, bytes.data() + i * ts, fmt_.big_endian);
    return out;
  }

  std::uint64_t header_word(byte_source& src, const tag& t) {
    std::string b;
    const std::size_t w = fmt_.header64 ? 8 : 4;
    if (!src.get(w, b)) throw io_error(path_, t.line, "the data of DataArray '" + name_of(t) + "' end inside its header");
    return fmt_.header64 ? load<std::uint64_t>(b.data(), fmt_.big_endian) : load<std::uint32_t>(b.data(), fmt_.big_endian);
  }
  static std::string name_of(const tag& t) { return t.attr("Name") ? *t.attr("Name") : std::string(); }

  std::string block(byte_source& src, const tag& t) {
    std::string out;
    const std::uint64_t limit = text_.size() * 1100ull + (1u << 20);  // no claim larger than zlib could expand to
    if (!fmt_.zlib) {
      const std::uint64_t n = header_word(src, t);
      if (n > text_.size()) throw io_error(path_, t.line, "DataArray '" + name_of(t) + "' claims " + std::to_string(n) + " bytes, more than the file holds");
      if (!src.get(static_cast<std::size_t>(n), out))
        throw io_error(path_, t.line, "the data of DataArray '" + name_of(t) + "' end before its " + std::to_string(n) + " bytes");
      return out;
    }
    const std::uint64_t nb = header_word(src, t), bs = header_word(src, t), last = header_word(src, t);
    if (nb > text_.size() || bs > limit || last > bs) throw io_error(path_, t.line, "malformed compression header of DataArray '" + name_of(t) + "'");
    std::vector<std::uint64_t> sizes(static_cast<std::size_t>(nb));
    for (auto& s : sizes) s = header_word(src, t);
    std::string comp;
    for (std::uint64_t k = 0; k < nb; ++k) {
      const std::uint64_t want = (k + 1 == nb && last != 0) ? last : bs;
      if (sizes[k] > text_.size() || !src.get(static_cast<std::size_t>(sizes[k]), comp))
        throw io_error(path_, t.line, "the data of DataArray '" + name_of(t) + "' end inside compressed block " + std::to_string(k + 1));
      const std::size_t at = out.size();
      if (at + want > limit) throw io_error(path_, t.line, "DataArray '" + name_of(t) + "' expands beyond any plausible size");
      out.resize(at + static_cast<std::size_t>(want));
      uLongf got = static_cast<uLongf>(want);
      const int rc = uncompress(reinterpret_cast<Bytef*>(out.data() + at), &got, reinterpret_cast<const Bytef*>(comp.data()), static_cast<uLong>(comp.size()));
      if (rc != Z_OK || got != want)
        throw io_error(path_, t.line, "compressed block " + std::to_string(k + 1) + " of DataArray '" + name_of(t) + "' does not inflate to " +
                                          std::to_string(want) + " bytes (zlib: " + (zError(rc) ? zError(rc) : "?") + ")");
    }
    return out;
  }

  void finish(vtu_grid& g, piece& pc) {
    const std::size_t base = g.points.size();
    if (pc.points > 0 && pc.coords.values.empty()) throw io_error(path_, pc.line, "the Piece has " + std::to_string(pc.points) + " points but no <Points> array");
    if (pc.points > 0 && pc.coords.components != 3) throw io_error(path_, pc.coords.line, "Points with " + std::to_string(pc.coords.components) + " components (3 expected)");
    if (pc.coords.values.size() != 3 * pc.points)
      throw io_error(path_, pc.points ? pc.coords.line : pc.line, std::to_string(pc.coords.values.size()) + " coordinates for " + std::to_string(pc.points) + " points");
    for (std::size_t i = 0; i < pc.points; ++i) {
      std::array<double, 3> x{pc.coords.values[3 * i], pc.coords.values[3 * i + 1], pc.coords.values[3 * i + 2]};
      for (double c : x)
        if (!std::isfinite(c)) throw io_error(path_, pc.coords.line, "point " + std::to_string(i) + " has a non-finite coordinate");
      g.points.push_back(x);
    }
    const array *conn = nullptr, *offs = nullptr, *types = nullptr;
    for (const auto& a : pc.cell_arrays) {
      if (a.name == "connectivity") conn = &a;
      else if (a.name == "offsets") offs = &a;
      else if (a.name == "types") types = &a;
    }
    const std::size_t cl = pc.cells_line ? pc.cells_line : pc.line;
    if (pc.cells > 0 && (!conn || !offs || !types)) throw io_error(path_, cl, "the Piece has cells but no connectivity, offsets or types array");
    if (pc.cells > 0) {
      if (offs->values.size() != pc.cells || types->values.size() != pc.cells)
        throw io_error(path_, cl, std::to_string(offs->values.size()) + " offsets and " + std::to_string(types->values.size()) + " types for " +
                                      std::to_string(pc.cells) + " cells");
      std::size_t prev = 0;
      const std::size_t cbase = g.connectivity.size();
      for (std::size_t c = 0; c < pc.cells; ++c) {
        const double o = offs->values[c];
        if (!(o >= static_cast<double>(prev)) || o > static_cast<double>(conn->values.size()) || o != std::floor(o))
          throw io_error(path_, offs->line, "offset " + num(o) + " of cell " + std::to_string(c) + " is not a non-decreasing index into the connectivity");
        prev = static_cast<std::size_t>(o);
        g.cell_start.push_back(cbase + prev);
        const double ty = types->values[c];
        if (!(ty >= 0 && ty < 256) || ty != std::floor(ty)) throw io_error(path_, types->line, "cell " + std::to_string(c) + " has type " + num(ty));
        g.cell_types.push_back(static_cast<std::uint8_t>(ty));
      }
      if (prev != conn->values.size()) throw io_error(path_, offs->line, "the last offset " + std::to_string(prev) + " is not the connectivity's length " + std::to_string(conn->values.size()));
      for (std::size_t k = 0; k < conn->values.size(); ++k) {
        const double v = conn->values[k];
        if (!(v >= 0 && v < static_cast<double>(pc.points)) || v != std::floor(v))
          throw io_error(path_, conn->line, "connectivity entry " + std::to_string(k) + " (" + num(v) + ") is not a point of the Piece (" + std::to_string(pc.points) + " points)");
        g.connectivity.push_back(base + static_cast<std::size_t>(v));
      }
      if (g.cells_line == 0) g.cells_line = cl;
    }
    for (auto& a : pc.point_data) {
      if (a.values.size() != pc.points * a.components)
        throw io_error(path_, a.line, "point data '" + a.name + "' has " + std::to_string(a.values.size()) + " values for " + std::to_string(pc.points) + " points of " +
                                          std::to_string(a.components) + " components");
      auto it = std::find_if(data_.begin(), data_.end(), [&](const merged& m) { return m.a.name == a.name; });
      if (it == data_.end()) {
        if (pieces_ == 0) data_.push_back({std::move(a), 1});
      } else if (it->pieces == pieces_ && it->a.components == a.components) {
        it->a.values.insert(it->a.values.end(), a.values.begin(), a.values.end());
        ++it->pieces;
      }
    }
    ++pieces_;
  }

  std::string path_;
  std::string text_;
  file_format fmt_;
  bool has_appended_ = false, appended_base64_ = false;
  std::string_view appended_;
  std::vector<merged> data_;
  std::size_t pieces_ = 0;
};

}  // namespace

vtu_grid read_vtu(const std::string& path) { return reader(path, detail::slurp(path)).run(); }

}  // namespace gsse::io
