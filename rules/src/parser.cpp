// Parser of the rule language: line oriented, '#' comments, ',' separates coordinate tuples.
// Names inside a front rule are resolved at its 'end', so statements may come in any order.
#include <limits>
#include <charconv>
#include <cmath>
#include <optional>
#include <set>
#include <fstream>
#include <map>
#include <sstream>

#include "gsse/rules/rule_set.hpp"

namespace gsse::rules {

namespace {

struct token_line {
  int line = 0;
  std::vector<std::string> tok;
};

std::vector<std::string> tokenize(std::string_view s) {
  if (const auto h = s.find('#'); h != std::string_view::npos) s = s.substr(0, h);
  std::vector<std::string> t;
  std::string cur;
  auto flush = [&] {
    if (!cur.empty()) t.push_back(std::move(cur)), cur.clear();
  };
  for (char c : s) {
    if (c == ' ' || c == '\t' || c == '\r') flush();
    else if (c == ',') flush(), t.emplace_back(",");
    else cur += c;
  }
  flush();
  return t;
}

std::optional<double> to_double(std::string_view s) {
  double v = 0;
  const auto* e = s.data() + s.size();
  const auto [p, ec] = std::from_chars(s.data(), e, v);
  if (ec != std::errc{} || p != e || !std::isfinite(v)) return std::nullopt;
  return v;
}

// A pending list of point names inside a front rule, resolved at 'end'.
struct pending_ref {
  int line;
  std::vector<std::string> names;
  std::vector<std::vector<std::size_t>>* target;
};
struct pending_mix {
  int line;
  std::size_t created;
  std::vector<std::pair<double, std::string>> terms;
};

class parser {
 public:
  parser(std::string_view text, std::string_view file) : text_(text) { set_.file = file; }

  rule_set run() {
    std::size_t pos = 0;
    int line = 0;
    while (pos <= text_.size()) {
      const auto nl = text_.find('\n', pos);
      const auto end = nl == std::string_view::npos ? text_.size() : nl;
      ++line;
      token_line tl{line, tokenize(text_.substr(pos, end - pos))};
      if (!tl.tok.empty()) statement(tl);
      if (nl == std::string_view::npos) break;
      pos = nl + 1;
    }
    if (in_rule_) fail(rule_line_, "unterminated rule '" + rule_name_ + "': missing 'end'");
    if (set_.dimension == 0) fail(1, "missing 'dimension' statement");
    return std::move(set_);
  }

 private:
  [[noreturn]] void fail(int line, const std::string& msg) const { throw rule_error(set_.file, line, msg); }

  double number(const token_line& l, std::size_t i) const {
    if (i >= l.tok.size()) fail(l.line, "'" + l.tok[0] + "': missing value");
    const std::string& s = l.tok[i];
    if (auto v = to_double(s)) return *v;
    if (const auto slash = s.find('/'); slash != std::string::npos) {  // fractions like 1/3
      const auto a = to_double(std::string_view(s).substr(0, slash));
      const auto b = to_double(std::string_view(s).substr(slash + 1));
      if (a && b && *b != 0) return *a / *b;
    }
    fail(l.line, "expected a number, got '" + s + "'");
  }

  void arity(const token_line& l, std::size_t n) const {
    if (l.tok.size() < n + 1) fail(l.line, "'" + l.tok[0] + "': missing value");
    if (l.tok.size() > n + 1) fail(l.line, "'" + l.tok[0] + "': unexpected '" + l.tok[n + 1] + "'");
  }

  // D numbers starting at token i; returns the index after them.
  std::size_t coords(const token_line& l, std::size_t i, point3& p) const {
    const auto d = static_cast<std::size_t>(set_.dimension);
    p = {0, 0, 0};
    for (std::size_t k = 0; k < d; ++k) {
      if (i + k >= l.tok.size() || l.tok[i + k] == ",")
        fail(l.line, "expected " + std::to_string(d) + " coordinates, got " + std::to_string(k));
      p[k] = number(l, i + k);
    }
    if (i + d < l.tok.size() && l.tok[i + d] != "," && to_double(l.tok[i + d]))
      fail(l.line, "expected " + std::to_string(d) + " coordinates, got more");
    return i + d;
  }

  void statement(const token_line& l) {
    const std::string& k = l.tok[0];
    if (k == "dimension") {
      if (in_rule_) fail(l.line, "'dimension' inside rule '" + rule_name_ + "'");
      if (set_.dimension != 0) fail(l.line, "'dimension' given twice");
      arity(l, 1);
      const double d = number(l, 1);
      if (d != 2 && d != 3) fail(l.line, "dimension must be 2 or 3, got '" + l.tok[1] + "'");
      set_.dimension = static_cast<int>(d);
    } else if (k == "split" || k == "front") {
      if (in_rule_)
        fail(l.line, "rule '" + rule_name_ + "' (line " + std::to_string(rule_line_) + ") is not terminated: 'end' missing before '" + k + "'");
      if (set_.dimension == 0) fail(l.line, "'dimension' must come before the first rule");
      if (l.tok.size() < 2) fail(l.line, "'" + k + "': missing rule name");
      arity(l, 1);
      begin_rule(l, k == "split");
    } else if (k == "end") {
      if (!in_rule_) fail(l.line, "'end' outside a rule");
      arity(l, 0);
      is_split_ ? end_split() : end_front();
      in_rule_ = false;
    } else if (!in_rule_) {
      fail(l.line, known(k) ? "'" + k + "' outside a rule" : "unknown keyword '" + k + "'");
    } else if (is_split_) {
      split_statement(l);
    } else {
      front_statement(l);
    }
  }

  static bool known(const std::string& k) {
    for (auto s : {"element", "relation", "try", "quality", "tolerance", "base", "match", "new", "add", "remove",
                   "orient", "free"})
      if (k == s) return true;
    return false;
  }

  void begin_rule(const token_line& l, bool split) {
    const std::string& name = l.tok[1];
    if (auto it = names_.find(name); it != names_.end())
      fail(l.line, "duplicate rule name '" + name + "' (first defined at line " + std::to_string(it->second) + ")");
    names_[name] = l.line;
    in_rule_ = true;
    is_split_ = split;
    rule_name_ = name;
    rule_line_ = l.line;
    seen_.clear();
    if (split) {
      set_.split.rules.push_back({});
      set_.split.rules.back().name = name;
      set_.split.rules.back().line = l.line;
    } else {
      set_.front.rules.push_back({});
      auto& r = set_.front.rules.back();
      r.name = name;
      r.line = l.line;
      r.dimension = set_.dimension;
      refs_.clear();
      mixes_.clear();
    }
  }

  void once(const token_line& l) {
    if (!seen_.insert(l.tok[0]).second) fail(l.line, "'" + l.tok[0] + "' given twice in rule '" + rule_name_ + "'");
  }

  void split_statement(const token_line& l) {
    auto& r = set_.split.rules.back();
    const std::string& k = l.tok[0];
    if (k == "element") {
      once(l);
      arity(l, 1);
      const auto v = element_kind_from(l.tok[1]);
      if (!v) fail(l.line, "unknown element kind '" + l.tok[1] + "' (expected subsegment or subfacet)");
      r.kind = *v;
    } else if (k == "relation") {
      once(l);
      arity(l, 1);
      const auto v = relation_from(l.tok[1]);
      if (!v)
        fail(l.line, "unknown relation '" + l.tok[1] + "' (expected free, on-incident-vertex, on-incident-edge or on-carrier)");
      r.rel = *v;
    } else if (k == "try") {
      seen_.insert("try");
      if (l.tok.size() < 2) fail(l.line, "'try': missing action");
      const auto a = split_action_from(l.tok[1]);
      if (!a) fail(l.line, "unknown action '" + l.tok[1] + "' (expected project, rotate-vertex, rotate-edge, midpoint or shell)");
      split_step s{*a, -std::numeric_limits<double>::infinity(), false, l.line};  // no bound unless given
      for (std::size_t i = 2; i < l.tok.size(); ++i) {
        if (l.tok[i] == "inside") s.inside = true;
        else if (l.tok[i] == "min-gap") s.min_gap = number(l, ++i);
        else fail(l.line, "unknown condition '" + l.tok[i] + "' (expected min-gap or inside)");
      }
      r.steps.push_back(s);
    } else {
      fail(l.line, known(k) ? "'" + k + "' is not allowed in a split rule" : "unknown keyword '" + k + "'");
    }
  }

  void front_statement(const token_line& l) {
    auto& r = set_.front.rules.back();
    const std::string& k = l.tok[0];
    const auto d = static_cast<std::size_t>(set_.dimension);
    if (k == "quality") {
      once(l);
      arity(l, 1);
      const double q = number(l, 1);
      if (q < 1 || q != static_cast<int>(q)) fail(l.line, "quality must be an integer >= 1, got '" + l.tok[1] + "'");
      r.quality = static_cast<int>(q);
    } else if (k == "tolerance") {
      once(l);
      arity(l, 1);
      r.tolerance = number(l, 1);
      if (r.tolerance < 0) fail(l.line, "tolerance must be >= 0");
    } else if (k == "base") {
      once(l);
      // base NAME... [tol T]
      std::size_t n = 1;
      while (n < l.tok.size() && l.tok[n] != "tol") ++n;
      if (n - 1 != d)
        fail(l.line, "'base' needs " + std::to_string(d) + " point names in " + std::to_string(d) + "D, got " + std::to_string(n - 1));
      double tol = -1;  // -1: the rule's tolerance, filled in at 'end'
      if (n < l.tok.size()) {
        arity(l, n + 1);
        tol = number(l, n + 1);
      }
      std::vector<rule_point> base;
      for (std::size_t i = 0; i < d; ++i)
        base.push_back({l.tok[1 + i], base_reference(set_.dimension, i), tol, l.line});
      r.points.insert(r.points.begin(), base.begin(), base.end());
      base_given_ = true;
    } else if (k == "match") {
      // match NAME at X Y [Z] [tol T]
      if (l.tok.size() < 3 || l.tok[2] != "at") fail(l.line, "expected 'match NAME at X Y" + std::string(d == 3 ? " Z" : "") + " [tol T]'");
      rule_point p{l.tok[1], {}, -1, l.line};
      std::size_t i = coords(l, 3, p.ref);
      if (i < l.tok.size()) {
        if (l.tok[i] != "tol") fail(l.line, "'match': unexpected '" + l.tok[i] + "'");
        arity(l, i + 1);
        p.tol = number(l, i + 1);
      }
      r.points.push_back(p);
    } else if (k == "new") {
      // new NAME at X Y [Z]  |  new NAME mix W P [W P ...] [shift X Y [Z]]
      if (l.tok.size() < 3) fail(l.line, "expected 'new NAME at ...' or 'new NAME mix ...'");
      new_point p{l.tok[1], {}, {}, l.line};
      if (l.tok[2] == "at") {
        if (coords(l, 3, p.shift) != l.tok.size()) fail(l.line, "'new': unexpected '" + l.tok[3 + d] + "'");
      } else if (l.tok[2] == "mix") {
        pending_mix m{l.line, r.created.size(), {}};
        std::size_t i = 3;
        while (i < l.tok.size() && l.tok[i] != "shift") {
          const double w = number(l, i);
          if (i + 1 >= l.tok.size() || l.tok[i + 1] == "shift") fail(l.line, "'mix': weight without point name");
          m.terms.emplace_back(w, l.tok[i + 1]);
          i += 2;
        }
        if (m.terms.empty()) fail(l.line, "'mix': missing weights and points");
        if (i < l.tok.size() && coords(l, i + 1, p.shift) != l.tok.size())
          fail(l.line, "'new': unexpected '" + l.tok[i + 1 + d] + "'");
        mixes_.push_back(std::move(m));
      } else {
        fail(l.line, "expected 'at' or 'mix' after 'new " + p.name + "', got '" + l.tok[2] + "'");
      }
      r.created.push_back(p);
    } else if (k == "element" || k == "add" || k == "remove" || k == "orient") {
      const std::size_t n = k == "element" || k == "orient" ? d + 1 : d;
      if (l.tok.size() - 1 != n)
        fail(l.line, "'" + k + "' needs " + std::to_string(n) + " point names in " + std::to_string(d) + "D, got " +
                         std::to_string(l.tok.size() - 1));
      auto* target = k == "element" ? &r.elements : k == "add" ? &r.added_faces : k == "remove" ? &r.removed_faces : &r.orientations;
      refs_.push_back({l.line, {l.tok.begin() + 1, l.tok.end()}, target});
      target->emplace_back();  // filled at 'end'
    } else if (k == "free") {
      std::vector<point3> piece;
      std::size_t i = 1;
      while (true) {
        point3 p;
        i = coords(l, i, p);
        piece.push_back(p);
        if (i == l.tok.size()) break;
        if (l.tok[i] != ",") fail(l.line, "'free': expected ',' between points, got '" + l.tok[i] + "'");
        ++i;
      }
      if (piece.size() < d + 1) fail(l.line, "'free' needs at least " + std::to_string(d + 1) + " points");
      r.free_zone.push_back(std::move(piece));
    } else {
      fail(l.line, known(k) ? "'" + k + "' is not allowed in a front rule" : "unknown keyword '" + k + "'");
    }
  }

  void end_split() {
    const auto& r = set_.split.rules.back();
    for (const char* f : {"element", "relation", "try"})
      if (!seen_.count(f)) fail(r.line, "split rule '" + r.name + "': missing '" + f + "'");
  }

  void end_front() {
    auto& r = set_.front.rules.back();
    if (!seen_.count("quality")) fail(r.line, "front rule '" + r.name + "': missing 'quality'");
    if (!base_given_) fail(r.line, "front rule '" + r.name + "': missing 'base'");
    base_given_ = false;
    if (r.elements.empty()) fail(r.line, "front rule '" + r.name + "': missing 'element'");
    for (auto& p : r.points)
      if (p.tol < 0) p.tol = r.tolerance;
    std::map<std::string, std::size_t> index;
    auto define = [&](const std::string& name, std::size_t i, int line) {
      if (!index.emplace(name, i).second) fail(line, "duplicate point name '" + name + "' in rule '" + r.name + "'");
    };
    for (std::size_t i = 0; i < r.points.size(); ++i) define(r.points[i].name, i, r.points[i].line);
    for (std::size_t j = 0; j < r.created.size(); ++j) define(r.created[j].name, r.points.size() + j, r.created[j].line);
    auto resolve = [&](const std::string& name, int line) {
      const auto it = index.find(name);
      if (it == index.end()) fail(line, "unknown point '" + name + "' in rule '" + r.name + "'");
      return it->second;
    };
    std::map<const void*, std::size_t> next;  // fill order per target list
    for (const auto& ref : refs_) {
      auto& slot = (*ref.target)[next[ref.target]++];
      for (const auto& n : ref.names) slot.push_back(resolve(n, ref.line));
    }
    for (const auto& m : mixes_)
      for (const auto& [w, n] : m.terms) {
        const auto i = resolve(n, m.line);
        if (i >= r.points.size()) fail(m.line, "'mix' may only use base and matched points, not '" + n + "'");
        r.created[m.created].mix.push_back({w, i});
      }
  }

  std::string_view text_;
  rule_set set_;
  std::map<std::string, int> names_;
  bool in_rule_ = false, is_split_ = false, base_given_ = false;
  std::string rule_name_;
  int rule_line_ = 0;
  std::set<std::string> seen_;
  std::vector<pending_ref> refs_;
  std::vector<pending_mix> mixes_;
};

}  // namespace

rule_set parse_rules(std::string_view text, std::string_view file) { return parser(text, file).run(); }

rule_set load_rules(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw rule_error(path.string(), 0, "cannot read rule file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_rules(ss.str(), path.string());
}

}  // namespace gsse::rules
