#define BOOST_TEST_MODULE rules_parser
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "gsse/rules/defaults.hpp"
#include "gsse/rules/rule_set.hpp"

using namespace gsse::rules;

BOOST_AUTO_TEST_CASE(parses_a_split_rule) {
  const auto s = parse_rules(R"(# comment line
dimension 2
split s1          # trailing comment
  element subsegment
  relation on-incident-vertex
  try rotate-vertex min-gap 0.125 inside
  try midpoint
end
)",
                             "t.rules");
  BOOST_TEST(s.file == "t.rules");
  BOOST_TEST(s.dimension == 2);
  BOOST_REQUIRE(s.split.rules.size() == 1u);
  const auto& r = s.split.rules[0];
  BOOST_TEST(r.name == "s1");
  BOOST_TEST(r.line == 3);
  BOOST_TEST((r.kind == element_kind::subsegment));
  BOOST_TEST((r.rel == relation::on_incident_vertex));
  BOOST_REQUIRE(r.steps.size() == 2u);
  BOOST_TEST((r.steps[0].action == split_action::rotate_vertex));
  BOOST_TEST(r.steps[0].min_gap == 0.125);
  BOOST_TEST(r.steps[0].inside);
  BOOST_TEST((r.steps[1].action == split_action::midpoint));
  BOOST_TEST(!r.steps[1].inside);
  BOOST_TEST(s.split.lookup(element_kind::subsegment, relation::on_incident_vertex) == &r);
  BOOST_TEST(s.split.lookup(element_kind::subsegment, relation::free) == nullptr);
}

BOOST_AUTO_TEST_CASE(parses_a_front_rule_in_any_statement_order) {
  const auto s = parse_rules(R"(dimension 2
front f
  element a b c          # uses names defined below
  quality 2
  tolerance 0.25
  new c mix 1/2 a 0.5 b shift 0 0.75
  base a b tol 0.4
  match q at 1.5 0.5 tol 0.2
  remove a b
  add a c
  add c b
  orient a b q
  free 0 0, 1 0, 0.5 1
end
)");
  const auto& r = s.front.rules.at(0);
  BOOST_TEST(r.quality == 2);
  BOOST_TEST(r.tolerance == 0.25);
  BOOST_REQUIRE(r.points.size() == 3u);
  BOOST_TEST(r.points[0].name == "a");
  BOOST_TEST(r.points[1].name == "b");
  BOOST_TEST(r.points[1].ref[0] == 1.0);
  BOOST_TEST(r.points[0].tol == 0.4);
  BOOST_TEST(r.points[2].name == "q");
  BOOST_TEST(r.points[2].tol == 0.2);
  BOOST_REQUIRE(r.created.size() == 1u);
  BOOST_TEST(r.created[0].mix.size() == 2u);
  BOOST_TEST(r.created[0].mix[0].weight == 0.5);
  const auto c = r.reference(3);
  BOOST_TEST(c[0] == 0.5);
  BOOST_TEST(c[1] == 0.75);
  BOOST_TEST((r.elements.at(0) == std::vector<std::size_t>{0, 1, 3}));
  BOOST_TEST((r.added_faces.at(1) == std::vector<std::size_t>{3, 1}));
  BOOST_TEST((r.orientations.at(0) == std::vector<std::size_t>{0, 1, 2}));
  BOOST_TEST(r.free_zone.at(0).size() == 3u);
  BOOST_TEST(r.free_zone[0][2][1] == 1.0);
}

BOOST_AUTO_TEST_CASE(eligible_orders_by_quality) {
  const auto s = default_rules("front2d");
  BOOST_TEST(s.front.eligible(1).size() == 1u);
  const auto all = s.front.eligible(10);
  BOOST_REQUIRE(all.size() == 3u);
  BOOST_TEST(all[0]->name == "triangle-ideal");
  BOOST_TEST(all[2]->quality == 3);
}

struct malformed {
  const char* text;
  int line;
  const char* message;
};

// Each file is wrong in exactly one way; the parser must name the line and the problem.
const malformed cases[] = {
    {"split a\nend\n", 1, "'dimension' must come before the first rule"},
    {"dimension 4\n", 1, "dimension must be 2 or 3, got '4'"},
    {"dimension two\n", 1, "expected a number, got 'two'"},
    {"dimension 2\ndimension 2\n", 2, "'dimension' given twice"},
    {"# only a comment\n", 1, "missing 'dimension' statement"},
    {"dimension 2\nfrobnicate 3\n", 2, "unknown keyword 'frobnicate'"},
    {"dimension 2\nelement subsegment\n", 2, "'element' outside a rule"},
    {"dimension 2\nend\n", 2, "'end' outside a rule"},
    {"dimension 2\nsplit\n", 2, "'split': missing rule name"},
    {"dimension 2\nsplit a\n  element subsegment\n  relation free\n  try midpoint\n", 2,
     "unterminated rule 'a': missing 'end'"},
    {"dimension 2\nsplit a\n  element subsegment\nsplit b\n", 4,
     "rule 'a' (line 2) is not terminated: 'end' missing before 'split'"},
    {"dimension 2\nsplit a\n relation free\n try midpoint\nend\n", 2, "split rule 'a': missing 'element'"},
    {"dimension 2\nsplit a\n element subsegment\n try midpoint\nend\n", 2, "split rule 'a': missing 'relation'"},
    {"dimension 2\nsplit a\n element subsegment\n relation free\nend\n", 2, "split rule 'a': missing 'try'"},
    {"dimension 2\nsplit a\n element edge\n", 3, "unknown element kind 'edge' (expected subsegment or subfacet)"},
    {"dimension 2\nsplit a\n relation near\n", 3,
     "unknown relation 'near' (expected free, on-incident-vertex, on-incident-edge or on-carrier)"},
    {"dimension 2\nsplit a\n try bisect\n", 3,
     "unknown action 'bisect' (expected project, rotate-vertex, rotate-edge, midpoint or shell)"},
    {"dimension 2\nsplit a\n try project far\n", 3, "unknown condition 'far' (expected min-gap or inside)"},
    {"dimension 2\nsplit a\n try project min-gap\n", 3, "'try': missing value"},
    {"dimension 2\nsplit a\n try project min-gap 0.1x\n", 3, "expected a number, got '0.1x'"},
    {"dimension 2\nsplit a\n element subsegment\n element subfacet\n", 4, "'element' given twice in rule 'a'"},
    {"dimension 2\nsplit a\n quality 1\n", 3, "'quality' is not allowed in a split rule"},
    {"dimension 2\nsplit a\n element subsegment\n relation free\n try midpoint\nend\nsplit a\n", 7,
     "duplicate rule name 'a' (first defined at line 2)"},
    {"dimension 2\nfront f\n base a b\n new c at 0.5 0.8\n element a b c\nend\n", 2,
     "front rule 'f': missing 'quality'"},
    {"dimension 2\nfront f\n quality 1\n new c at 0.5 0.8\nend\n", 2, "front rule 'f': missing 'base'"},
    {"dimension 2\nfront f\n quality 1\n base a b\nend\n", 2, "front rule 'f': missing 'element'"},
    {"dimension 2\nfront f\n quality 0\n", 3, "quality must be an integer >= 1, got '0'"},
    {"dimension 2\nfront f\n quality 1.5\n", 3, "quality must be an integer >= 1, got '1.5'"},
    {"dimension 3\nfront f\n base a b\n", 3, "'base' needs 3 point names in 3D, got 2"},
    {"dimension 2\nfront f\n new c at 0.5\n", 3, "expected 2 coordinates, got 1"},
    {"dimension 2\nfront f\n new c at 0.5 0.8 0.1\n", 3, "expected 2 coordinates, got more"},
    {"dimension 2\nfront f\n new c near 0.5 0.8\n", 3, "expected 'at' or 'mix' after 'new c', got 'near'"},
    {"dimension 2\nfront f\n new c mix 0.5 a 0.5\n", 3, "'mix': weight without point name"},
    {"dimension 2\nfront f\n new c mix 1/0 a\n", 3, "expected a number, got '1/0'"},
    {"dimension 2\nfront f\n match q 1 1\n", 3, "expected 'match NAME at X Y [tol T]'"},
    {"dimension 2\nfront f\n element a b\n", 3, "'element' needs 3 point names in 2D, got 2"},
    {"dimension 2\nfront f\n free 0 0, 1 0\n", 3, "'free' needs at least 3 points"},
    {"dimension 2\nfront f\n free 0 0 1 0, 1 1\n", 3, "expected 2 coordinates, got more"},
    {"dimension 2\nfront f\n try midpoint\n", 3, "'try' is not allowed in a front rule"},
    {"dimension 2\nfront f\n quality 1\n base a b\n element a b z\nend\n", 5, "unknown point 'z' in rule 'f'"},
    {"dimension 2\nfront f\n quality 1\n base a b\n new a at 0.5 0.5\n element a b a\nend\n", 5,
     "duplicate point name 'a' in rule 'f'"},
    {"dimension 2\nfront f\n quality 1\n base a b\n new c at 0 1\n new d mix 1 c\n element a b d\nend\n", 6,
     "'mix' may only use base and matched points, not 'c'"},
};

BOOST_AUTO_TEST_CASE(malformed_files_report_file_line_and_message) {
  for (const auto& c : cases) {
    BOOST_TEST_CONTEXT(c.text) {
      try {
        (void)parse_rules(c.text, "bad.rules");
        BOOST_ERROR("no error for: " << c.text);
      } catch (const rule_error& e) {
        BOOST_TEST(e.file() == "bad.rules");
        BOOST_TEST(e.line() == c.line);
        BOOST_TEST(e.message() == c.message);
        BOOST_TEST(std::string(e.what()) == "bad.rules:" + std::to_string(c.line) + ": " + c.message);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(unreadable_file) {
  BOOST_CHECK_THROW(load_rules("/nonexistent/x.rules"), rule_error);
}

BOOST_AUTO_TEST_CASE(shipped_files_parse_from_disk_and_embedded_copies_match) {
  BOOST_TEST(embedded_rule_names().size() == 4u);
  for (auto name : embedded_rule_names()) {
    BOOST_TEST_CONTEXT(name) {
      const auto disk = load_rules(default_rules_path(name));
      const auto emb = parse_rules(embedded_rules(name), name);
      BOOST_TEST(disk.dimension == emb.dimension);
      BOOST_TEST(disk.split.rules.size() == emb.split.rules.size());
      BOOST_TEST(disk.front.rules.size() == emb.front.rules.size());
      BOOST_TEST(disk.split.rules.size() + disk.front.rules.size() > 0u);
    }
  }
  BOOST_TEST(embedded_rules("front3d") == embedded_rules("front3d.rules"));
  BOOST_TEST(embedded_rules("nope").empty());
  BOOST_CHECK_THROW(default_rules("nope"), rule_error);
}
