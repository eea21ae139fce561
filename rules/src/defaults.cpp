// Locating and loading the shipped rule sets. The texts themselves are generated into
// embedded_rules_data.cpp (see rules/CMakeLists.txt).
#include <span>

#include "gsse/rules/defaults.hpp"

namespace gsse::rules {

namespace detail {
struct embedded_entry {
  std::string_view name;
  std::string_view text;
};
std::span<const embedded_entry> embedded_entries();  // generated
}  // namespace detail

std::string default_rules_path(std::string_view file) {
  return std::string(GSSE_RULES_DIR) + "/" + std::string(file);
}

std::string_view embedded_rules(std::string_view name) {
  for (const auto& e : detail::embedded_entries())
    if (e.name == name || e.name == std::string(name) + ".rules") return e.text;
  return {};
}

std::vector<std::string_view> embedded_rule_names() {
  std::vector<std::string_view> r;
  for (const auto& e : detail::embedded_entries()) r.push_back(e.name);
  return r;
}

rule_set default_rules(std::string_view name) {
  const auto text = embedded_rules(name);
  if (text.empty()) throw rule_error(std::string(name), 0, "no embedded rule set of this name");
  std::string file(name);
  if (!file.ends_with(".rules")) file += ".rules";
  auto s = parse_rules(text, file);
  require_valid(s);
  return s;
}

}  // namespace gsse::rules
