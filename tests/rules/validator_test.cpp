#define BOOST_TEST_MODULE rules_validator
#include <boost/test/unit_test.hpp>

#include <string>

#include "gsse/rules/defaults.hpp"
#include "gsse/rules/rule_set.hpp"

using namespace gsse::rules;

BOOST_AUTO_TEST_CASE(every_shipped_rule_set_is_valid) {
  for (auto name : embedded_rule_names()) {
    BOOST_TEST_CONTEXT(name) {
      for (const auto& s : {load_rules(default_rules_path(name)), parse_rules(embedded_rules(name), name)}) {
        const auto problems = validate(s);
        for (const auto& p : problems) BOOST_ERROR(p.what());
        BOOST_TEST(problems.empty());
      }
      BOOST_CHECK_NO_THROW(default_rules(name));
    }
  }
}

BOOST_AUTO_TEST_CASE(shipped_conformer_sets_cover_every_pair) {
  const auto s2 = default_rules("conformer2d");
  const auto s3 = default_rules("conformer3d");
  for (auto rel : {relation::free, relation::on_incident_vertex, relation::on_carrier})
    BOOST_TEST(s2.split.lookup(element_kind::subsegment, rel) != nullptr);
  BOOST_TEST(s2.split.lookup(element_kind::subsegment, relation::on_incident_edge) == nullptr);
  for (auto k : {element_kind::subsegment, element_kind::subfacet})
    for (auto rel : {relation::free, relation::on_incident_vertex, relation::on_incident_edge, relation::on_carrier})
      BOOST_TEST(s3.split.lookup(k, rel) != nullptr);
  // the documented policy: projection for free vertices, rotations for incident ones, midpoint last
  BOOST_TEST((s3.split.lookup(element_kind::subfacet, relation::free)->steps[0].action == split_action::project));
  BOOST_TEST((s3.split.lookup(element_kind::subfacet, relation::on_incident_vertex)->steps[0].action ==
              split_action::rotate_vertex));
  BOOST_TEST((s3.split.lookup(element_kind::subfacet, relation::on_incident_edge)->steps[0].action ==
              split_action::rotate_edge));
  for (const auto& r : s3.split.rules) BOOST_TEST((r.steps.back().action == split_action::midpoint));
}

struct invalid {
  const char* text;
  int line;
  const char* message;  // the first problem reported
};

// A valid 2D triangle rule body, to be broken one statement at a time.
#define TRI_HEAD "dimension 2\nfront t\n quality 1\n base a b\n"
#define TRI_FACES " remove a b\n add a c\n add c b\n"
#define TRI_FREE " free 0 0, 1 0, 1 1, 0 1\n"
#define SPLIT2D(rules)                                                                                   \
  "dimension 2\n" rules                                                                                  \
  "split z1\n element subsegment\n relation on-carrier\n try midpoint\nend\n"                            \
  "split z2\n element subsegment\n relation on-incident-vertex\n try midpoint\nend\n"

const invalid cases[] = {
    {TRI_HEAD " new c at 0.5 0.8\n element a c b\n" TRI_FACES TRI_FREE "end\n", 2,
     "front rule 't': element (a c b) is not positively oriented"},
    {TRI_HEAD " new c at 0.5 1.5\n element a b c\n" TRI_FACES TRI_FREE "end\n", 5,
     "front rule 't': new point 'c' lies outside the free zone"},
    {TRI_HEAD " new c at 0.5 0.8\n element a b c\n" TRI_FACES "end\n", 2,
     "front rule 't': creates points but has no free zone"},
    {TRI_HEAD " new c mix 0.5 a 0.6 b shift 0 0.8\n element a b c\n" TRI_FACES TRI_FREE "end\n", 5,
     "front rule 't': weights of new point 'c' sum to 1.100000, not 1"},
    {TRI_HEAD " new c at 0.5 0.8\n element a b c\n remove a b\n add a c\n" TRI_FREE "end\n", 2,
     "front rule 't': faces do not close the front update at (b c): 'remove' must list the consumed faces and "
     "'add' the new front faces, oriented with the unmeshed side positive"},
    {TRI_HEAD " new c at 0.5 0.8\n element a b c\n remove a b\n add c a\n add c b\n" TRI_FREE "end\n", 2,
     "front rule 't': faces do not close the front update at (a c): 'remove' must list the consumed faces and "
     "'add' the new front faces, oriented with the unmeshed side positive"},
    {TRI_HEAD " new c at 0.5 0.8\n element a b c\n orient b a c\n" TRI_FACES TRI_FREE "end\n", 2,
     "front rule 't': orientation (b a c) fails on the reference configuration"},
    {TRI_HEAD " new c at 0.5 0.8\n element a b c\n" TRI_FACES " free 0 0, 1 0, 2 0\nend\n", 2,
     "front rule 't': a free-zone piece is degenerate (no interior)"},
    {"dimension 2\nsplit a\n element subfacet\n relation free\n try midpoint\nend\n", 0,
     "no split rule for (subsegment, free)"},
    {SPLIT2D("split a\n element subsegment\n relation free\n try rotate-edge\n try midpoint\nend\n"), 5,
     "split rule 'a': rotate-edge is only valid for subfacets"},
    {SPLIT2D("split a\n element subsegment\n relation free\n try rotate-vertex\n try midpoint\nend\n"), 5,
     "split rule 'a': rotate-vertex needs relation on-incident-vertex (a shared vertex)"},
    {SPLIT2D("split a\n element subsegment\n relation free\n try project min-gap 0.5\n try midpoint\nend\n"), 5,
     "split rule 'a': min-gap must be in [0, 0.5)"},
    {SPLIT2D("split a\n element subsegment\n relation free\n try project\nend\n"), 5,
     "split rule 'a': the last action must be an unconditional 'midpoint' (the fallback)"},
    {SPLIT2D("split a\n element subsegment\n relation free\n try midpoint inside\nend\n"), 5,
     "split rule 'a': the last action must be an unconditional 'midpoint' (the fallback)"},
    {SPLIT2D("split a\n element subsegment\n relation free\n try midpoint\nend\n"
             "split b\n element subsegment\n relation free\n try midpoint\nend\n"),
     7, "split rule 'b': (subsegment, free) is already handled by rule 'a'"},
    {SPLIT2D("split a\n element subsegment\n relation free\n try midpoint\nend\n"
             "split b\n element subsegment\n relation on-incident-edge\n try midpoint\nend\n"),
     7, "split rule 'b': relation on-incident-edge does not exist in 2D"},
};

BOOST_AUTO_TEST_CASE(invalid_sets_report_the_problem) {
  for (const auto& c : cases) {
    BOOST_TEST_CONTEXT(c.text) {
      const auto s = parse_rules(c.text, "v.rules");
      const auto problems = validate(s);
      BOOST_REQUIRE(!problems.empty());
      BOOST_TEST(problems.front().line() == c.line);
      BOOST_TEST(problems.front().message() == c.message);
      BOOST_CHECK_THROW(require_valid(s), rule_error);
    }
  }
}

BOOST_AUTO_TEST_CASE(hand_built_sets_are_checked_for_duplicate_names) {
  auto s = default_rules("front2d");
  s.front.rules[1].name = s.front.rules[0].name;  // the parser would have refused this
  s.front.rules[0].created[0].name = "a";         // and this
  const auto problems = validate(s);
  bool rule_dup = false, point_dup = false;
  for (const auto& p : problems) {
    rule_dup |= p.message() == "rule name 'triangle-ideal' used twice";
    point_dup |= p.message() == "front rule 'triangle-ideal': point name 'a' used twice";
  }
  BOOST_TEST(rule_dup);
  BOOST_TEST(point_dup);
}
