#pragma once
// A parsed rule file: split rules for the conformer and/or front rules for the mesher, in one
// language (syntax in docs/rules.md). Parsing checks syntax and references; validate() checks
// geometry and completeness.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "gsse/rules/error.hpp"
#include "gsse/rules/front_rule.hpp"
#include "gsse/rules/split_rule.hpp"

namespace gsse::rules {

struct rule_set {
  std::string file;  // name used in messages
  int dimension = 0;
  split_rule_set split;
  front_rule_set front;
};

/// Parses rule text; throws rule_error("FILE:LINE: message") on the first syntax error.
rule_set parse_rules(std::string_view text, std::string_view file = "<string>");
/// Reads and parses a file; throws rule_error (line 0) if it cannot be read.
rule_set load_rules(const std::filesystem::path& path);

/// All problems of a parsed (or hand-built) set, in file order; empty when valid.
std::vector<rule_error> validate(const rule_set& s);
/// Throws the first problem found by validate().
void require_valid(const rule_set& s);

}  // namespace gsse::rules
