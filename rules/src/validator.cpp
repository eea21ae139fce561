// Validator: geometric and completeness checks that the parser cannot make line by line.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "gsse/rules/rule_set.hpp"

namespace gsse::rules {

namespace {

constexpr double weight_tol = 1e-9;

struct checker {
  const rule_set& s;
  std::vector<rule_error> out;

  void report(int line, std::string msg) { out.emplace_back(s.file, line, std::move(msg)); }

  void split_rules() {
    std::map<std::pair<element_kind, relation>, const split_rule*> seen;
    for (const auto& r : s.split.rules) {
      const std::string who = "split rule '" + r.name + "'";
      if (s.dimension == 2 && r.kind == element_kind::subfacet)
        report(r.line, who + ": 2D has no subfacets");
      if (s.dimension == 2 && r.rel == relation::on_incident_edge)
        report(r.line, who + ": relation on-incident-edge does not exist in 2D");
      if (auto [it, fresh] = seen.emplace(std::pair{r.kind, r.rel}, &r); !fresh)
        report(r.line, who + ": (" + std::string(to_string(r.kind)) + ", " + std::string(to_string(r.rel)) +
                           ") is already handled by rule '" + it->second->name + "'");
      if (r.steps.empty()) report(r.line, who + ": no action");
      for (const auto& st : r.steps) {
        const std::string act(to_string(st.action));
        if (st.action == split_action::rotate_edge && r.kind != element_kind::subfacet)
          report(st.line, who + ": rotate-edge is only valid for subfacets");
        if (st.action == split_action::shell && r.kind != element_kind::subsegment)
          report(st.line, who + ": shell is only valid for subsegments");
        if (st.action == split_action::rotate_vertex && r.rel != relation::on_incident_vertex)
          report(st.line, who + ": rotate-vertex needs relation on-incident-vertex (a shared vertex)");
        if (st.action == split_action::rotate_edge && r.rel != relation::on_incident_edge)
          report(st.line, who + ": rotate-edge needs relation on-incident-edge (a shared edge)");
        if (st.action == split_action::project && r.rel == relation::on_carrier)
          report(st.line, who + ": project of a vertex on the carrier returns the vertex itself");
        const double gmax = r.kind == element_kind::subsegment ? 0.5 : 1.0 / 3;
        if (std::isfinite(st.min_gap) && !(st.min_gap >= 0 && st.min_gap < gmax))
          report(st.line, who + ": min-gap must be in [0, " + (r.kind == element_kind::subsegment ? "0.5" : "1/3") + ")");
      }
      if (!r.steps.empty()) {
        const auto& last = r.steps.back();
        if (last.action != split_action::midpoint || last.inside || last.min_gap > 0)
          report(last.line, who + ": the last action must be an unconditional 'midpoint' (the fallback)");
      }
    }
    if (s.split.rules.empty()) return;
    // every pair that can occur in this dimension needs a rule
    std::vector<element_kind> kinds{element_kind::subsegment};
    std::vector<relation> rels{relation::free, relation::on_incident_vertex, relation::on_carrier};
    if (s.dimension == 3) kinds.push_back(element_kind::subfacet), rels.push_back(relation::on_incident_edge);
    for (auto k : kinds)
      for (auto rel : rels)
        if (!seen.count({k, rel}))
          report(0, "no split rule for (" + std::string(to_string(k)) + ", " + std::string(to_string(rel)) + ")");
  }

  std::string names(const front_rule& r, const std::vector<std::size_t>& t) {
    std::string x;
    for (auto v : t) x += (x.empty() ? "" : " ") + (v < r.vertex_count() ? r.vertex_name(v) : "?");
    return x;
  }

  void front_rule_checks(const front_rule& r) {
    const std::string who = "front rule '" + r.name + "'";
    const auto d = static_cast<std::size_t>(s.dimension);
    if (r.dimension != s.dimension) report(r.line, who + ": dimension differs from the file's");
    if (r.quality < 1) report(r.line, who + ": quality must be >= 1");
    if (r.points.size() < d) {
      report(r.line, who + ": needs " + std::to_string(d) + " base points");
      return;
    }
    std::set<std::string> pn;
    for (std::size_t v = 0; v < r.vertex_count(); ++v)
      if (!pn.insert(r.vertex_name(v)).second) report(r.line, who + ": point name '" + r.vertex_name(v) + "' used twice");
    for (std::size_t i = 0; i < d; ++i)
      if (std::abs(distance(r.points[i].ref, base_reference(s.dimension, i))) > 1e-12)
        report(r.points[i].line, who + ": base point '" + r.points[i].name + "' is not at its reference position");
    for (const auto& p : r.points)
      if (!(p.tol >= 0)) report(p.line, who + ": point '" + p.name + "' has a negative tolerance");

    auto bad_tuple = [&](const std::vector<std::size_t>& t, std::size_t n, int line, const char* what) {
      bool bad = t.size() != n;
      for (auto v : t) bad |= v >= r.vertex_count();
      std::set<std::size_t> u(t.begin(), t.end());
      if (bad) report(line, who + ": " + what + " (" + names(r, t) + ") has invalid vertices");
      else if (u.size() != t.size()) report(line, who + ": " + what + " (" + names(r, t) + ") repeats a vertex");
      return bad || u.size() != t.size();
    };
    auto oriented = [&](const std::vector<std::size_t>& t) {
      std::vector<point3> p;
      for (auto v : t) p.push_back(r.reference(v));
      return orientation(s.dimension, p);
    };

    for (const auto& np : r.created) {
      double w = 0;
      for (const auto& t : np.mix) w += t.weight;
      if (!np.mix.empty() && std::abs(w - 1) > weight_tol)
        report(np.line, who + ": weights of new point '" + np.name + "' sum to " + std::to_string(w) + ", not 1");
      for (const auto& t : np.mix)
        if (t.point >= r.points.size())
          report(np.line, who + ": new point '" + np.name + "' mixes a point that is not base or matched");
      if (r.free_zone.empty()) continue;
      const point3 ref = r.reference(r.points.size() + static_cast<std::size_t>(&np - r.created.data()));
      const bool inside = std::any_of(r.free_zone.begin(), r.free_zone.end(), [&](const auto& piece) {
        return in_convex_piece(s.dimension, piece, ref, -1e-9);
      });
      if (!inside) report(np.line, who + ": new point '" + np.name + "' lies outside the free zone");
    }
    if (r.free_zone.empty() && !r.created.empty()) report(r.line, who + ": creates points but has no free zone");
    for (const auto& piece : r.free_zone) {
      // full-dimensional: some interior point (the vertex average) is strictly inside
      point3 c{0, 0, 0};
      for (const auto& q : piece) c = c + (1.0 / static_cast<double>(piece.size())) * q;
      if (!in_convex_piece(s.dimension, piece, c, 1e-9))
        report(r.line, who + ": a free-zone piece is degenerate (no interior)");
    }

    if (r.elements.empty()) report(r.line, who + ": creates no element");
    // Front update: sum of element boundaries (interior on the positive side) must equal removed
    // faces minus added faces, as oriented chains; every interior face cancels.
    std::map<std::vector<std::size_t>, int> chain;
    auto add_face = [&](std::vector<std::size_t> f, int sign) {
      // orientation sign of the permutation that sorts f
      int parity = 1;
      for (std::size_t i = 0; i < f.size(); ++i)
        for (std::size_t j = i + 1; j < f.size(); ++j)
          if (f[i] > f[j]) parity = -parity;
      std::sort(f.begin(), f.end());
      chain[f] += sign * parity;
    };
    bool chain_ok = true;
    for (const auto& e : r.elements) {
      if (bad_tuple(e, d + 1, r.line, "element")) {
        chain_ok = false;
        continue;
      }
      if (!(oriented(e) > 1e-12)) report(r.line, who + ": element (" + names(r, e) + ") is not positively oriented");
      // faces of e, each oriented with the element's interior on its positive side
      for (std::size_t skip = 0; skip <= d; ++skip) {
        std::vector<std::size_t> f;
        for (std::size_t i = 0; i <= d; ++i)
          if (i != skip) f.push_back(e[i]);
        // In a positive simplex the face omitting vertex i has the interior on its positive side
        // iff (d - i) is even (d = dimension): alternating signs of the boundary operator.
        add_face(f, ((d - skip) % 2 == 0) ? 1 : -1);
      }
    }
    for (const auto& f : r.removed_faces) {
      if (bad_tuple(f, d, r.line, "removed face")) chain_ok = false;
      else add_face(f, -1);
    }
    for (const auto& f : r.added_faces) {
      if (bad_tuple(f, d, r.line, "added face")) chain_ok = false;
      else add_face(f, 1);
    }
    if (chain_ok)
      for (const auto& [f, c] : chain)
        if (c != 0) {
          report(r.line, who + ": faces do not close the front update at (" + names(r, f) +
                             "): 'remove' must list the consumed faces and 'add' the new front faces, "
                             "oriented with the unmeshed side positive");
          break;
        }
    for (const auto& o : r.orientations)
      if (!bad_tuple(o, d + 1, r.line, "orientation") && !(oriented(o) > 0))
        report(r.line, who + ": orientation (" + names(r, o) + ") fails on the reference configuration");
  }
};

}  // namespace

std::vector<rule_error> validate(const rule_set& s) {
  checker c{s, {}};
  if (s.dimension != 2 && s.dimension != 3) {
    c.report(0, "dimension must be 2 or 3");
    return c.out;
  }
  std::map<std::string, int> names;
  auto name = [&](const std::string& n, int line) {
    if (auto [it, fresh] = names.emplace(n, line); !fresh) c.report(line, "rule name '" + n + "' used twice");
  };
  for (const auto& r : s.split.rules) name(r.name, r.line);
  for (const auto& r : s.front.rules) name(r.name, r.line);
  c.split_rules();
  for (const auto& r : s.front.rules) c.front_rule_checks(r);
  std::stable_sort(c.out.begin(), c.out.end(), [](const auto& a, const auto& b) { return a.line() < b.line(); });
  return c.out;
}

void require_valid(const rule_set& s) {
  auto e = validate(s);
  if (!e.empty()) throw e.front();
}

}  // namespace gsse::rules
