#pragma once
// The shipped rule sets (conformer2d, conformer3d, front2d, front3d .rules): on disk in the
// source tree and embedded into the library at build time, so the mesher runs from anywhere.
#include <string>
#include <string_view>
#include <vector>

#include "gsse/rules/rule_set.hpp"
#include "gsse/rules/unit_frame.hpp"

namespace gsse::rules {

/// Path of a file in the rules source directory (GSSE_RULES_DIR), e.g. "front2d.rules".
std::string default_rules_path(std::string_view file);
/// The embedded text of a shipped rule set ("front2d.rules" or "front2d"); empty if unknown.
std::string_view embedded_rules(std::string_view name);
/// Names ("front2d.rules", ...) of all embedded sets.
std::vector<std::string_view> embedded_rule_names();
/// Parses and validates an embedded set; throws rule_error if unknown or invalid.
rule_set default_rules(std::string_view name);

}  // namespace gsse::rules
